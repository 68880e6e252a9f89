#include "soak_report.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <numeric>

#include <nlohmann/json.hpp>

#include "support/stats_file.h"

namespace igi::soak {

namespace fs = std::filesystem;

static uint64_t count_lines(const std::string& path, const std::string& text) {
  std::ifstream in(path);
  uint64_t n = 0;
  for (std::string line; std::getline(in, line);) n += line.find(text) != std::string::npos;
  return n;
}

MasterFigures read_master_figures(const std::string& dir, int runs) {
  MasterFigures m;
  m.runs = runs;
  for (int r = 0; r < runs; ++r) {
    const std::string log = (fs::path(dir) / "logs" / ("master-" + std::to_string(r) + ".log")).string();
    m.bad_messages_logged += count_lines(log, "dropped a bad message");
    m.declared_dead += count_lines(log, "declared dead");
    const fs::path path = fs::path(dir) / ("stats-" + std::to_string(r) + ".json");
    if (!fs::exists(path)) continue;
    const nlohmann::json stats = test::read_stats(path.string());
    // A killed master leaves its statistics as of its last totals line (once a second).
    if (stats.value("complete", false)) ++m.runs_finished;
    ++m.runs_with_stats;
    m.bad_messages_json += stats.value("bad_messages", uint64_t(0));
    if (stats["frames"].empty()) continue;
    const nlohmann::json& last = stats["frames"].back();  // the scheduler's counts are totals over the run
    m.reissued += last.value("reissued_total", uint64_t(0));
    m.duplicated += last.value("duplicated_total", uint64_t(0));
    m.late_dropped += last.value("late_dropped_total", uint64_t(0));
  }
  return m;
}

static void print_faults(const SoakTotals& t) {
  int total = 0;
  std::string kinds;
  for (int k = 0; k < kFaultKinds; ++k) {
    const auto it = t.faults.find(FaultKind(k));
    const int n = it == t.faults.end() ? 0 : it->second;
    total += n;
    kinds += std::string(kinds.empty() ? "" : ", ") + fault_name(FaultKind(k)) + " " + std::to_string(n);
  }
  std::printf("soak: faults injected: %d (%s)\n", total, kinds.c_str());
  std::printf("soak: garbage sent: %llu ZeroMQ messages, by kind:\n", (unsigned long long)t.garbage_zmq_messages);
  for (const auto& [kind, n] : t.garbage) std::printf("soak:   %6llu  %s\n", (unsigned long long)n, kind.c_str());
}

static void print_restarts(const SoakTotals& t) {
  if (t.restart_seconds.empty()) return;
  const double sum = std::accumulate(t.restart_seconds.begin(), t.restart_seconds.end(), 0.0);
  const double worst = *std::max_element(t.restart_seconds.begin(), t.restart_seconds.end());
  std::printf("soak: master restarts: %zu; from the kill to the next frame on disk: mean %.2f s, max %.2f s\n",
              t.restart_seconds.size(), sum / double(t.restart_seconds.size()), worst);
}

int report(const SoakTotals& t, const FrameVerdict& frames, const MasterFigures& m,
           const std::vector<MemoryMonitor::Verdict>& memory, long peak_rss_kib, double margin_mib) {
  std::vector<std::string> failures = t.failures;
  for (const std::string& note : frames.notes) failures.push_back(note);
  for (const MemoryMonitor::Verdict& v : memory)
    if (!v.bounded) failures.push_back("master memory grew: " + v.text);
  const int lost = int(frames.missing.size());

  std::printf("soak: ---- summary (seed %llu) ----\n", (unsigned long long)t.seed);
  std::printf("soak: frames rendered: %d of %d on disk (%d re-rendered after master kills); identical to the "
              "single-process render: %d, differing: %zu\n", t.frames - lost, t.frames, t.frames_rerendered,
              frames.identical, frames.differing.size());
  print_faults(t);
  std::printf("soak: tiles re-issued: %llu (duplicated near a frame's end: %llu, late results dropped: %llu), "
              "from the statistics of %d of %d master processes (%d finished; killed ones up to their last "
              "flush, once a second)\n",
              (unsigned long long)m.reissued, (unsigned long long)m.duplicated, (unsigned long long)m.late_dropped,
              m.runs_with_stats, m.runs, m.runs_finished);
  std::printf("soak: bad messages dropped by the master: %llu (its logs, every process; its statistics: %llu); "
              "workers declared dead: %llu\n", (unsigned long long)m.bad_messages_logged,
              (unsigned long long)m.bad_messages_json, (unsigned long long)m.declared_dead);
  std::printf("soak: lost frames: %d\n", lost);
  print_restarts(t);
  std::printf("soak: master memory: peak RSS %.1f MiB; rule: median RSS over the second half of a master process's "
              "frames <= that over the first half + %.1f MiB (processes of >= %d frames)\n", peak_rss_kib / 1024.0,
              margin_mib, MemoryMonitor::kMinFrames);
  for (const MemoryMonitor::Verdict& v : memory) std::printf("soak:   %s\n", v.text.c_str());
  std::printf("soak: network namespaces: %s\n", t.netns.c_str());
  std::printf("soak: wall time: %.1f s\n", t.wall_seconds);
  for (const std::string& f : failures) std::printf("soak: FAIL: %s\n", f.c_str());
  std::printf("soak: %s\n", failures.empty() ? "PASS" : "FAIL");
  return failures.empty() ? 0 : 1;
}

}  // namespace igi::soak
