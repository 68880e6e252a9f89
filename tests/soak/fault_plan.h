#pragma once
// The faults of a soak run, drawn from one seed before the run starts, so a
// failing run can be repeated: the same seed gives the same faults at the same
// frame counts (what the processes are doing at that moment still varies).
#include <cstdint>
#include <string>
#include <vector>

namespace igi::soak {

enum class FaultKind { KillWorker, StopWorker, SlowWorker, Garbage, RestartMaster, CutLink, Hostile };
inline constexpr int kFaultKinds = 7;
const char* fault_name(FaultKind kind);

struct Fault {
  int at_frame = 0;     // fires once this many frames are on disk
  FaultKind kind = FaultKind::Garbage;
  int worker = 0;       // the worker slot (kill, stop, slow)
  double seconds = 0;   // stop/slow/cut/hostile: how long; kill/restart: delay before the replacement starts
  uint64_t seed = 0;    // garbage: the burst's own seed; hostile: which peer (seed % kHostileKinds)
};

// splitmix64: small, fast, the same everywhere (unlike std:: distributions).
class Rng {
 public:
  explicit Rng(uint64_t seed) : state_(seed) {}
  uint64_t next();
  int below(int n) { return int(next() % uint64_t(n)); }
  double uniform(double lo, double hi) { return lo + (hi - lo) * double(next() >> 11) * 0x1.0p-53; }

 private:
  uint64_t state_;
};

// Which kinds a plan may draw, from "kill,stop,slow,garbage,restart,cut,hostile"; throws on an unknown name.
std::vector<bool> parse_fault_kinds(const std::string& list);

// `count` faults spread over frames [5, frames - 3): every allowed kind at least
// once when count allows, the rest drawn by weight. Sorted by frame.
std::vector<Fault> plan_faults(uint64_t seed, int frames, int count, int workers, double timeout_seconds,
                               const std::vector<bool>& allowed);
std::string describe(const Fault& fault);

}  // namespace igi::soak
