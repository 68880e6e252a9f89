#include "viewer/viewer_options.h"

#include <CLI/CLI.hpp>
#include <climits>

#include "cli/option_checks.h"
#include "display/window_keys.h"

namespace igi {
namespace {

void declare(CLI::App& app, ViewerOptions& o) {
  cli::add_version_flag(app);
  app.footer("window keys (as igi-master's window; F5/F9 keep the camera file here; F12 saves the master's float "
             "image on the master and here, as igi-shot-NNNN.exr and .png):\n" + window_keys_text("  "));
  app.add_option("--connect", o.connect, "the master's viewer port (igi-master --viewer-listen), as this machine "
                 "reaches it: tcp://127.0.0.1:PORT through ssh -N -L PORT:127.0.0.1:PORT MASTER_HOST")
      ->required()->type_name("ENDPOINT");
  app.add_option("--key", o.key_file, "this viewer's secret key (igi-keys new NAME writes NAME.key; the master's "
                 "operator adds NAME.pub to its --viewer-keys)")->required()->type_name("FILE");
  app.add_option("--master-key", o.master_key, "the master's public key (the .pub of its --key)")
      ->required()->type_name("FILE");
  app.add_option_function<std::string>(
         "--panel", [&o](const std::string& v) { o.panel = v == "on"; },
         "the settings panel and the frame rate beside the image at start (Tab toggles them) [on]")
      ->check(cli::one_of({"on", "off"}))->type_name("on|off");
  app.add_option("--camera-file", o.bookmark, "where F5 saves the camera and F9 loads it, on this machine "
                 "[camera.json]")->type_name("FILE");
  app.add_option("--wait", o.wait_seconds, "seconds to wait for the master's answer [10]")
      ->check(cli::integer(1, 3600))->type_name("S");
  app.add_option("--screenshot", o.screenshot, "save the window as an image once --screenshot-after frames have "
                 "accumulated, then exit")->type_name("FILE");
  app.add_option("--screenshot-after", o.screenshot_after, "see --screenshot [4]")
      ->check(cli::integer(1, INT_MAX))->type_name("N");
  app.add_option("--screenshot-at-exit", o.exit_screenshot, "save the window as an image when it closes (Esc)")
      ->type_name("FILE");
  app.add_option("--frame-log", o.frame_log, "a line per frame shown: the wall clock (ms since 1970), codec "
                 "(zstd, h264), bytes, pixels, and the ms from the input it first shows (- for none)")
      ->type_name("FILE");
  app.add_flag("--quiet", o.quiet, "no summary at exit");
}

}  // namespace

ViewerOptions parse_viewer_options(const std::vector<std::string>& args) {
  ViewerOptions o;
  o.help = !cli::parse_into(o, declare, args);
  return o;
}

std::string viewer_usage(const std::string& program) {
  return cli::help<ViewerOptions>("igi-view: the window of an igi-master on another machine (igi-master "
                                  "--viewer-listen): shows its frames, drives its camera and settings",
                                  program, declare);
}

}  // namespace igi
