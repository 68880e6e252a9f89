#include "frame_stats.h"

#include <fstream>
#include <stdexcept>

namespace igi {

static void write_frame(std::ofstream& out, const FrameRecord& f) {
  out << "    {\"frame\": " << f.frame_id << ", \"seconds\": " << f.seconds << ", \"tiles\": " << f.tiles
      << ", \"rays\": " << f.rays.total() << ", \"mrays_per_s\": " << (f.seconds > 0 ? f.rays.total() * 1e-6 / f.seconds : 0.0)
      << ", \"reissued_total\": " << f.reissued << ", \"duplicated_total\": " << f.duplicated
      << ", \"late_dropped_total\": " << f.late_dropped << ",\n     \"workers\": {";
  bool first = true;
  for (const auto& [name, w] : f.workers) {
    out << (first ? "" : ", ") << "\"" << name << "\": {\"tiles\": " << w.tiles << ", \"busy_seconds\": " << w.busy_seconds
        << ", \"bytes_in\": " << w.bytes_in << ", \"bytes_out\": " << w.bytes_out << "}";
    first = false;
  }
  out << "}}";
}

void write_stats_json(const std::string& path, const std::vector<FrameRecord>& frames, uint64_t bad_messages) {
  std::ofstream out(path);
  if (!out) throw std::runtime_error(path + ": cannot write statistics");
  out << "{\n  \"bad_messages\": " << bad_messages << ",\n  \"frames\": [\n";
  for (size_t i = 0; i < frames.size(); ++i) {
    write_frame(out, frames[i]);
    out << (i + 1 < frames.size() ? ",\n" : "\n");
  }
  out << "  ]\n}\n";
}

}  // namespace igi
