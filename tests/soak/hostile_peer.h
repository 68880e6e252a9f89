#pragma once
// Hostile peers that speak the real protocol with the right build id, so the
// master cannot tell them from workers by their bytes, only by what they do:
//  - sybil: two connections that answer every job at once with made-up
//    pixels and the same made-up VPL-set hash (two fakes that agree);
//  - hoarder: claims 32 threads, takes jobs, heartbeats, never answers;
//  - failer: answers every job with a result that fails validation (a
//    rectangle that is not its job's);
//  - ghosts: connections that say hello and close, over and over.
// Each runs for a while on the caller's thread (the soak runs it async) and
// reports what it did, and whether the master told it it was quarantined.
#include <cstdint>
#include <string>

namespace igi::soak {

enum class HostileKind { Sybil, Hoarder, Failer, Ghosts };
inline constexpr int kHostileKinds = 4;
const char* hostile_name(HostileKind kind);

struct HostileReport {
  HostileKind kind = HostileKind::Sybil;
  int connections = 0;
  uint64_t jobs_taken = 0, results_sent = 0;
  int quarantined = 0;  // connections the master told so (Bye, kind Quarantined)
};

HostileReport run_hostile(const std::string& endpoint, HostileKind kind, double seconds);

}  // namespace igi::soak
