#pragma once
// Timing for the benchmark programs: wall time next to the CPU time the
// process actually received (the machine is shared: compare ratios measured
// in one run, and quote medians).
#include <algorithm>
#include <chrono>
#include <ctime>
#include <vector>

namespace igi::bench {

struct Clock {
  double wall, cpu;  // seconds
  static Clock now() {
    timespec t{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return {std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count(),
            double(t.tv_sec) + 1e-9 * double(t.tv_nsec)};
  }
  Clock operator-(const Clock& o) const { return {wall - o.wall, cpu - o.cpu}; }
};

inline double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0.0 : v[v.size() / 2];
}

}  // namespace igi::bench
