#include "memory_monitor.h"

#include <algorithm>
#include <cstdio>
#include <fstream>

#include "child_process.h"

namespace igi::soak {

void MemoryMonitor::start_process(int run) {
  if (int(runs_.size()) <= run) runs_.resize(size_t(run) + 1);
}

void MemoryMonitor::sample(pid_t pid, int frames) {
  const long rss = rss_kib(pid);
  const int fds = open_fds(pid);
  if (rss > 0 && fds >= 0 && !runs_.empty()) runs_.back().push_back({frames, rss, fds});
}

long MemoryMonitor::peak_kib() const {
  long peak = 0;
  for (const auto& run : runs_)
    for (const Sample& s : run) peak = std::max(peak, s.rss_kib);
  return peak;
}

void MemoryMonitor::write_csv(const std::string& path) const {
  std::ofstream out(path);
  out << "run,frames,rss_kib,fds\n";
  for (size_t r = 0; r < runs_.size(); ++r)
    for (const Sample& s : runs_[r]) out << r << "," << s.frames << "," << s.rss_kib << "," << s.fds << "\n";
}

static int quantile(std::vector<int> v, double q) {
  if (v.empty()) return 0;
  const size_t k = std::min(v.size() - 1, size_t(q * double(v.size())));
  std::nth_element(v.begin(), v.begin() + long(k), v.end());
  return v[k];
}

std::vector<MemoryMonitor::Verdict> MemoryMonitor::judge(double margin_mib) const {
  std::vector<Verdict> verdicts;
  for (size_t r = 0; r < runs_.size(); ++r) {
    const std::vector<Sample>& samples = runs_[r];
    Verdict v;
    v.run = int(r);
    for (const Sample& s : samples) v.frames = std::max(v.frames, s.frames);
    std::vector<int> rss[2], fds[2];
    // Warm-up left out: until its first frames are written (a restarted master waits about a
    // second for its workers) the master has not loaded its image writer or grown its buffers.
    const int warm = std::max(5, v.frames / 10);
    for (const Sample& s : samples) {
      v.peak_kib = std::max(v.peak_kib, s.rss_kib);
      if (s.frames < warm) continue;
      const int half = 2 * (s.frames - warm) >= v.frames - warm ? 1 : 0;
      rss[half].push_back(int(s.rss_kib));
      fds[half].push_back(s.fds);
    }
    v.first_kib = quantile(rss[0], 0.5);
    v.second_kib = quantile(rss[1], 0.5);
    v.first_fds = quantile(fds[0], 0.0);  // the floors: garbage connections come and go above them
    v.second_fds = quantile(fds[1], 0.0);
    v.judged = v.frames >= kMinFrames && !rss[0].empty() && !rss[1].empty();
    const long margin_kib = long(margin_mib * 1024);
    v.bounded = !v.judged || (v.second_kib <= v.first_kib + margin_kib && v.second_fds <= v.first_fds + 8);
    char text[240];
    std::snprintf(text, sizeof text, "master process %d: %d frames, median RSS %.1f MiB (first half) -> %.1f MiB "
                  "(second half), peak %.1f MiB; fewest fds %d -> %d: %s", v.run, v.frames, v.first_kib / 1024.0,
                  v.second_kib / 1024.0, v.peak_kib / 1024.0, v.first_fds, v.second_fds,
                  !v.judged ? "too short to judge" : v.bounded ? "bounded" : "GREW");
    v.text = text;
    verdicts.push_back(v);
  }
  return verdicts;
}

}  // namespace igi::soak
