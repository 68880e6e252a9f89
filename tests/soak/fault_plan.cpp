#include "fault_plan.h"

#include <algorithm>
#include <cstdio>
#include <stdexcept>

#include "hostile_peer.h"

namespace igi::soak {

const char* fault_name(FaultKind kind) {
  switch (kind) {
    case FaultKind::KillWorker: return "worker killed";
    case FaultKind::StopWorker: return "worker stopped";
    case FaultKind::SlowWorker: return "slow worker";
    case FaultKind::Garbage: return "garbage burst";
    case FaultKind::RestartMaster: return "master restarted";
    case FaultKind::CutLink: return "link cut";
    case FaultKind::Hostile: return "hostile peer";
  }
  return "?";
}

uint64_t Rng::next() {
  uint64_t z = (state_ += 0x9e3779b97f4a7c15ull);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  return z ^ (z >> 31);
}

std::vector<bool> parse_fault_kinds(const std::string& list) {
  static const char* names[kFaultKinds] = {"kill", "stop", "slow", "garbage", "restart", "cut", "hostile"};
  std::vector<bool> allowed(kFaultKinds, false);
  if (list == "none") return allowed;
  size_t start = 0;
  while (start <= list.size()) {
    const size_t end = std::min(list.find(',', start), list.size());
    const std::string name = list.substr(start, end - start);
    int k = 0;
    while (k < kFaultKinds && name != names[k]) ++k;
    if (k == kFaultKinds) throw std::invalid_argument("--kinds: unknown fault '" + name + "' (kill, stop, slow, garbage, restart, cut, hostile)");
    allowed[size_t(k)] = true;
    start = end + 1;
  }
  return allowed;
}

static FaultKind draw_kind(Rng& rng, const std::vector<bool>& allowed) {
  // Weights: garbage and kills are cheap and common; a master restart costs seconds.
  struct Weighted { FaultKind kind; int weight; };
  const Weighted table[] = {{FaultKind::KillWorker, 3}, {FaultKind::StopWorker, 2}, {FaultKind::SlowWorker, 2},
                            {FaultKind::Garbage, 4},    {FaultKind::RestartMaster, 1}, {FaultKind::CutLink, 1},
                            {FaultKind::Hostile, 2}};
  int total = 0;
  for (const Weighted& w : table) total += allowed[size_t(w.kind)] ? w.weight : 0;
  int pick = rng.below(total);
  for (const Weighted& w : table) {
    if (!allowed[size_t(w.kind)]) continue;
    if ((pick -= w.weight) < 0) return w.kind;
  }
  return FaultKind::Garbage;
}

static Fault make_fault(Rng& rng, FaultKind kind, int workers, double timeout) {
  Fault f;
  f.kind = kind;
  f.worker = rng.below(workers);
  switch (kind) {
    case FaultKind::KillWorker: f.seconds = rng.uniform(0.0, 0.3); break;          // then a replacement
    case FaultKind::StopWorker: f.seconds = rng.uniform(1.5, 3.0) * timeout; break;  // declared dead meanwhile
    case FaultKind::SlowWorker: f.seconds = rng.uniform(1.0, 3.0); break;
    case FaultKind::Garbage: f.seed = rng.next(); break;
    case FaultKind::RestartMaster: f.seconds = rng.uniform(0.1, 1.0); break;     // down meanwhile
    case FaultKind::CutLink: f.seconds = rng.uniform(0.5, 3.0) * timeout + rng.uniform(0.0, 1.0); break;
    case FaultKind::Hostile: f.seed = rng.next(), f.seconds = rng.uniform(1.0, 3.0); break;
  }
  return f;
}

std::vector<Fault> plan_faults(uint64_t seed, int frames, int count, int workers, double timeout,
                               const std::vector<bool>& allowed) {
  Rng rng(seed);
  std::vector<FaultKind> kinds;
  if (std::find(allowed.begin(), allowed.end(), true) == allowed.end()) return {};
  for (int k = 0; k < kFaultKinds && int(kinds.size()) < count; ++k)
    if (allowed[size_t(k)]) kinds.push_back(FaultKind(k));
  if (kinds.empty()) return {};
  while (int(kinds.size()) < count) kinds.push_back(draw_kind(rng, allowed));
  for (size_t i = kinds.size(); i > 1; --i) std::swap(kinds[i - 1], kinds[rng.below(int(i))]);  // Fisher-Yates

  // One fault in each of `count` equal stretches of [5, frames - 3).
  const int first = std::min(5, frames / 4), span = std::max(1, frames - 3 - first);
  std::vector<Fault> plan;
  for (int i = 0; i < count; ++i) {
    Fault f = make_fault(rng, kinds[i], workers, timeout);
    const int lo = first + span * i / count, hi = first + span * (i + 1) / count;
    f.at_frame = lo + rng.below(std::max(1, hi - lo));
    plan.push_back(f);
  }
  std::stable_sort(plan.begin(), plan.end(), [](const Fault& a, const Fault& b) { return a.at_frame < b.at_frame; });
  return plan;
}

std::string describe(const Fault& f) {
  char text[160];
  switch (f.kind) {
    case FaultKind::KillWorker:
      std::snprintf(text, sizeof text, "SIGKILL worker %d, replacement after %.2f s", f.worker, f.seconds); break;
    case FaultKind::StopWorker:
      std::snprintf(text, sizeof text, "SIGSTOP worker %d for %.2f s, then SIGCONT", f.worker, f.seconds); break;
    case FaultKind::SlowWorker:
      std::snprintf(text, sizeof text, "worker %d slowed to 1/4 speed for %.2f s", f.worker, f.seconds); break;
    case FaultKind::Garbage:
      std::snprintf(text, sizeof text, "garbage burst (seed %llu)", (unsigned long long)f.seed); break;
    case FaultKind::RestartMaster:
      std::snprintf(text, sizeof text, "SIGKILL the master, restart after %.2f s", f.seconds); break;
    case FaultKind::CutLink:
      std::snprintf(text, sizeof text, "cut the namespace worker's link for %.2f s", f.seconds); break;
    case FaultKind::Hostile:
      std::snprintf(text, sizeof text, "hostile peer: %s for %.2f s", hostile_name(HostileKind(f.seed % kHostileKinds)),
                    f.seconds);
      break;
  }
  return "frame " + std::to_string(f.at_frame) + ": " + text;
}

}  // namespace igi::soak
