#pragma once
// Per-frame statistics of a master run, written as JSON.
#include <string>
#include <vector>

#include "master_session.h"

namespace igi {

struct RunTotals {
  uint64_t bad_messages = 0;       // frames that did not decode, dropped
  uint64_t refused_keys = 0;       // CURVE: worker keys the ZAP handler refused
  uint64_t failed_handshakes = 0;  // CURVE: peers without CURVE or the right master key
  double master_cpu_seconds = 0.0;  // process CPU during the session loop (includes image writing unless --no-write)
  double wall_seconds = 0.0;
  bool complete = false;           // false while the run goes on (the file is rewritten once a second)
};

// Replaces `path` atomically (a reader never sees half a file).
void write_stats_json(const std::string& path, const std::vector<FrameRecord>& frames, const RunTotals& totals);
// CPU time this process has used (user + system).
double process_cpu_seconds();

}  // namespace igi
