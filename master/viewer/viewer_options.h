#pragma once
// igi-view's command line: where the master's viewer port is, the keys, and
// how the window opens.
#include <string>
#include <vector>

namespace igi {

struct ViewerOptions {
  std::string connect;     // the master's --viewer-listen, as this machine reaches it
  std::string key_file;    // the viewer's NAME.key (igi-keys new NAME)
  std::string master_key;  // the master's NAME.pub
  bool panel = true;       // the panel and the frame rate at start (Tab toggles)
  std::string bookmark = "camera.json";  // F5 / F9: on this machine
  int wait_seconds = 10;   // for the master's Welcome
  std::string screenshot;  // save the window after --screenshot-after accumulated frames, then exit
  int screenshot_after = 4;
  std::string exit_screenshot;  // save the window as it is when it closes (scripts/bench-viewer.sh)
  std::string frame_log;        // a line per frame shown (scripts/bench-viewer.sh)
  bool quiet = false;
  bool help = false;
};

// Parses argv[1] on; throws cli::OptionError naming the option and the value.
ViewerOptions parse_viewer_options(const std::vector<std::string>& args);
std::string viewer_usage(const std::string& program);

}  // namespace igi
