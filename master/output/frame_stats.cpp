#include "output/frame_stats.h"

#include <sys/resource.h>

namespace igi {

nlohmann::ordered_json frame_json(const FrameRecord& f) {
  nlohmann::ordered_json workers = nlohmann::ordered_json::object();
  for (const auto& [name, w] : f.workers)
    workers[name] = {{"tiles", w.tiles}, {"busy_seconds", w.busy_seconds}, {"bytes_in", w.bytes_in},
                     {"bytes_out", w.bytes_out}};
  return {{"frame", f.frame_id}, {"seconds", f.seconds}, {"completed_at", f.completed_at}, {"tiles", f.tiles},
          {"rays", f.rays.total()},
          {"mrays_per_s", f.seconds > 0 ? double(f.rays.total()) * 1e-6 / f.seconds : 0.0},
          // The scheduler's counts are totals over the run, as of this frame.
          {"reissued_total", f.reissued}, {"duplicated_total", f.duplicated}, {"late_dropped_total", f.late_dropped},
          {"verified_total", f.verified}, {"failed_results_total", f.failed_results},
          {"quarantined_total", f.quarantined}, {"own_tiles_total", f.own_tiles},
          {"nonfinite_pixels", f.nonfinite_pixels}, {"workers", workers}};
}

nlohmann::ordered_json totals_json(const RunTotals& t, uint64_t tiles) {
  return {{"complete", t.complete}, {"outcome", t.outcome}, {"bad_messages", t.bad_messages},
          {"refused_keys", t.refused_keys},
          {"failed_handshakes", t.failed_handshakes}, {"nonfinite_pixels", t.nonfinite_pixels},
          {"declared_dead", t.declared_dead}, {"master_unlistened_seconds", t.unlistened_seconds},
          {"quarantined", t.quarantined}, {"own_tiles", t.own_tiles}, {"benched", t.benched},
          {"doubted", t.doubted},
          {"master_follows_workers", t.follows_workers}, {"pixel_format", t.pixel_format},
          {"pixel_codec", t.pixel_codec},
          {"io_threads", t.io_threads},
          {"master_cpu_seconds", t.master_cpu_seconds}, {"session_cpu_seconds", t.session_cpu_seconds},
          {"master_hash_frames", t.hash_frames}, {"master_hash_seconds", t.hash_seconds},
          {"master_peak_rss_mib", t.peak_rss_mib},
          {"wall_seconds", t.wall_seconds}, {"tiles", tiles},
          {"master_cpu_us_per_tile", tiles ? 1e6 * t.master_cpu_seconds / double(tiles) : 0.0}};
}

double process_cpu_seconds() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return double(usage.ru_utime.tv_sec + usage.ru_stime.tv_sec) + 1e-6 * double(usage.ru_utime.tv_usec + usage.ru_stime.tv_usec);
}

RunTotals run_totals(const MasterSession& session, int io_threads, double cpu_start, double wall_seconds) {
  RunTotals t;
  t.bad_messages = session.bad_messages();
  t.refused_keys = session.refused_keys();
  t.failed_handshakes = session.failed_handshakes();
  t.declared_dead = session.declared_dead();
  t.unlistened_seconds = session.unlistened_seconds();
  t.nonfinite_pixels = session.nonfinite_pixels();
  t.quarantined = session.quarantined();
  t.own_tiles = session.own_tiles();
  t.follows_workers = session.follows_workers();
  t.benched = session.benched();
  t.doubted = session.doubted();
  t.hash_frames = session.reference_frames();
  t.hash_seconds = session.reference_seconds();
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  t.peak_rss_mib = double(usage.ru_maxrss) / 1024.0;  // Linux: KiB
  t.master_cpu_seconds = process_cpu_seconds() - cpu_start;
  t.session_cpu_seconds = session.session_cpu_seconds();
  t.wall_seconds = wall_seconds;
  t.pixel_format = pixel_format_name(session.pixel_format());
  t.pixel_codec = session.pixel_codec();
  t.io_threads = io_threads;
  return t;
}

}  // namespace igi
