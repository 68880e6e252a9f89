// igi-view: the window of an igi-master that runs on another machine
// (igi-master --viewer-listen): viewer/viewer_window.h.
#include <atomic>
#include <csignal>
#include <cstdio>
#include <iostream>

#include "cli/option_checks.h"
#include "viewer/viewer_options.h"
#include "viewer/viewer_window.h"

namespace {

std::atomic<bool> g_interrupted{false};  // set by SIGINT/SIGTERM only

}  // namespace

int main(int argc, char** argv) {
  std::signal(SIGINT, [](int) { g_interrupted = true; });
  std::signal(SIGTERM, [](int) { g_interrupted = true; });
  return igi::cli::run_program("igi-view", 1, 1, [&] {
    const igi::ViewerOptions o = igi::parse_viewer_options({argv + 1, argv + argc});
    if (o.help) {
      std::cout << igi::viewer_usage(argv[0]);
      return 0;
    }
    const igi::ViewerFigures figures = igi::run_viewer(o, g_interrupted);
    if (!o.quiet) std::fprintf(stderr, "igi-view: %s\n", figures.summary().c_str());
    return 0;
  });
}
