#pragma once
// What a soak run counts, and the summary it prints at the end.
#include <map>
#include <string>
#include <vector>

#include "fault_plan.h"
#include "frame_check.h"
#include "memory_monitor.h"

namespace igi::soak {

// The master's own figures: from the statistics JSON of each master process
// (a killed one's as of its last flush, once a second) and from the logs of
// every master process.
struct MasterFigures {
  int runs = 0, runs_finished = 0, runs_with_stats = 0;  // master processes: all, complete, with statistics
  uint64_t reissued = 0, duplicated = 0, late_dropped = 0, bad_messages_json = 0;
  uint64_t bad_messages_logged = 0, declared_dead = 0;
};
MasterFigures read_master_figures(const std::string& dir, int runs);

struct SoakTotals {
  uint64_t seed = 0;
  int frames = 0, frames_rerendered = 0;
  std::map<FaultKind, int> faults;
  std::map<std::string, uint64_t> garbage;
  uint64_t garbage_zmq_messages = 0;
  std::vector<double> restart_seconds;  // master kill -> its successor's first frame on disk
  std::string netns;                    // what the network-namespace part did
  double wall_seconds = 0;
  std::vector<std::string> failures;    // anything here fails the run
};

// Prints the summary; returns the exit code (0: every frame identical, none lost, memory bounded, no failures).
int report(const SoakTotals& totals, const FrameVerdict& frames, const MasterFigures& master,
           const std::vector<MemoryMonitor::Verdict>& memory, long peak_rss_kib, double rss_margin_mib);

}  // namespace igi::soak
