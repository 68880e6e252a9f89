#pragma once
// igi-loadgen's command line: the run (LoadgenOptions) and how its simulated
// workers behave, including a seeded schedule of faults for a soak at scale.
#include <cstdint>
#include <string>
#include <vector>

#include "loadgen_run.h"

namespace igi::loadgen {

struct CommandLine {
  LoadgenOptions run;
  uint64_t churn_seed = 0;   // not 0: workers join late, stall past the timeout, die and are replaced
  int diverging = 0;         // workers whose VPL-set hash differs (the first N)
  int hoarders = 0;          // workers that take jobs and never answer (the last N)
  int nan_every = 0;         // worker 0 sends a NaN tile every n-th answer
  int wrong_tile_every = 0;  // worker 0 claims a wrong rectangle every n-th answer
  int flood = 0;             // one more worker, which sends this many results a second for jobs never issued
  int check_every = 0;       // with --write-frames: check every n-th frame pixel by pixel
  std::string csv;           // append a row of figures
  std::string label;
  bool help = false;
};

CommandLine parse_command_line(const std::vector<std::string>& args);
std::string usage();
// The behaviours the command line asks for.
std::vector<SimBehaviour> behaviours(const CommandLine& c);

}  // namespace igi::loadgen
