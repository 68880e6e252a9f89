#pragma once
// igi-soak's options: how long to run, which faults, how to judge.
#include <cstdint>
#include <string>
#include <vector>

namespace igi::soak {

struct SoakOptions {
  std::string master_binary, worker_binary;  // default: next to igi-soak in the build tree
  std::string dir = "soak-run";              // frames, logs, stats, diff images (emptied first)
  int frames = 300;
  int width = 128, height = 96;
  std::string render_args = "--scene cornell --method igi --vpl-paths 16 --clamp 0.05 --tile 16";
  int workers = 3;                            // on loopback
  uint64_t seed = 0;                          // 0: from the clock (printed, so a run can be repeated)
  int faults = 0;                             // 0: one per 10 frames
  std::string kinds = "kill,stop,slow,garbage,restart,cut,hostile";  // which faults the plan may draw
  int heartbeat_ms = 100, timeout_ms = 500;   // the master's; workers take the heartbeat from it
  double deadline_seconds = 0;                // 0: 30 s + 0.6 s a frame
  std::string netns = "auto";                 // auto | on | off: a worker behind a veth link that is cut
  bool real_oversized = false;                // also send one real message over the size limit (512 MB)
  int corrupt_frame = -1;                     // self-test: alter this frame's file before checking
  int delete_frame = -1;                      // self-test: delete this frame's file before checking
  bool memory_check = true;                   // off: report the master's memory, judge nothing (sanitizer builds)
  double rss_margin_mib = 2.0;                // allowed growth of a master's median RSS from its first to second half
  bool help = false;
};

SoakOptions parse_soak_options(const std::vector<std::string>& args);
std::string soak_usage();

}  // namespace igi::soak
