// igi-soak: faults under load. Renders frames on igi-master and igi-worker
// processes while killing, stopping and slowing workers, sending the master
// garbage, killing and restarting the master and (where the machine allows)
// cutting a namespaced worker's link; then checks every frame bit for bit
// against the single-process render and the master's memory for growth.
#include <atomic>
#include <csignal>
#include <iostream>

#include "cli/option_checks.h"

#include "soak_options.h"
#include "soak_run.h"

namespace {
std::atomic<bool> g_stop{false};  // set by SIGINT/SIGTERM/SIGHUP only
}

int main(int argc, char** argv) {
  for (int sig : {SIGINT, SIGTERM, SIGHUP}) std::signal(sig, [](int) { g_stop = true; });
  std::signal(SIGPIPE, SIG_IGN);
  return igi::cli::run_program("igi-soak", 2, 2, [&] {
    igi::soak::SoakOptions o = igi::soak::parse_soak_options({argv + 1, argv + argc});
    if (o.help) { std::cout << igi::soak::soak_usage(); return 0; }
    if (o.master_binary.empty()) o.master_binary = IGI_MASTER_BINARY;
    if (o.worker_binary.empty()) o.worker_binary = IGI_WORKER_BINARY;
    return igi::soak::SoakRun(o, g_stop).run();
  });
}
