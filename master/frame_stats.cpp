#include "frame_stats.h"

#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <sys/resource.h>

namespace igi {

static void write_frame(std::ofstream& out, const FrameRecord& f) {
  out << "    {\"frame\": " << f.frame_id << ", \"seconds\": " << f.seconds << ", \"tiles\": " << f.tiles
      << ", \"rays\": " << f.rays.total() << ", \"mrays_per_s\": " << (f.seconds > 0 ? f.rays.total() * 1e-6 / f.seconds : 0.0)
      << ", \"reissued_total\": " << f.reissued << ", \"duplicated_total\": " << f.duplicated
      << ", \"late_dropped_total\": " << f.late_dropped << ", \"verified_total\": " << f.verified
      << ", \"failed_results_total\": " << f.failed_results << ", \"quarantined_total\": " << f.quarantined
      << ", \"nonfinite_pixels\": " << f.nonfinite_pixels << ",\n     \"workers\": {";
  bool first = true;
  for (const auto& [name, w] : f.workers) {
    out << (first ? "" : ", ") << "\"" << name << "\": {\"tiles\": " << w.tiles << ", \"busy_seconds\": " << w.busy_seconds
        << ", \"bytes_in\": " << w.bytes_in << ", \"bytes_out\": " << w.bytes_out << "}";
    first = false;
  }
  out << "}}";
}

// A JSON string of plain text (our own messages: escapes quotes, backslashes and control bytes).
static std::string quoted(const std::string& text) {
  std::string q = "\"";
  for (char c : text) {
    if (c == '"' || c == '\\') q += '\\', q += c;
    else if (static_cast<unsigned char>(c) < 0x20) q += ' ';
    else q += c;
  }
  return q + "\"";
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
  t.nonfinite_pixels = session.nonfinite_pixels();
  t.quarantined = session.quarantined();
  t.master_cpu_seconds = process_cpu_seconds() - cpu_start;
  t.session_cpu_seconds = session.session_cpu_seconds();
  t.wall_seconds = wall_seconds;
  t.pixel_format = pixel_format_name(session.pixel_format());
  t.io_threads = io_threads;
  return t;
}

void write_stats_json(const std::string& path, const std::vector<FrameRecord>& frames, const RunTotals& totals) {
  const std::string temporary = path + ".part";
  std::ofstream out(temporary);
  if (!out) throw std::runtime_error(path + ": cannot write statistics");
  uint64_t tiles = 0;
  for (const FrameRecord& f : frames) tiles += f.tiles;
  out << "{\n  \"complete\": " << (totals.complete ? "true" : "false") << ",\n  \"bad_messages\": " << totals.bad_messages
      << ",\n  \"refused_keys\": " << totals.refused_keys
      << ",\n  \"failed_handshakes\": " << totals.failed_handshakes << ",\n  \"nonfinite_pixels\": " << totals.nonfinite_pixels
      << ",\n  \"quarantined\": [";
  for (size_t i = 0; i < totals.quarantined.size(); ++i) out << (i ? ", " : "") << quoted(totals.quarantined[i]);
  out << "],\n  \"pixel_format\": \"" << totals.pixel_format << "\",\n  \"io_threads\": " << totals.io_threads
      << ",\n  \"master_cpu_seconds\": " << totals.master_cpu_seconds
      << ",\n  \"session_cpu_seconds\": " << totals.session_cpu_seconds
      << ",\n  \"wall_seconds\": " << totals.wall_seconds << ",\n  \"tiles\": " << tiles
      << ",\n  \"master_cpu_us_per_tile\": " << (tiles ? 1e6 * totals.master_cpu_seconds / double(tiles) : 0.0)
      << ",\n  \"frames\": [\n";
  for (size_t i = 0; i < frames.size(); ++i) {
    write_frame(out, frames[i]);
    out << (i + 1 < frames.size() ? ",\n" : "\n");
  }
  out << "  ]\n}\n";
  out.close();
  if (!out) throw std::runtime_error(path + ": cannot write statistics");
  std::filesystem::rename(temporary, path);
}

}  // namespace igi
