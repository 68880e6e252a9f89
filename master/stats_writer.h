#pragma once
// --stats on a thread of its own: the session thread hands over each frame's
// record and, now and then, the run's totals; this thread keeps the records
// and rewrites the file (atomically), so a long run's growing file never
// stalls the loop that feeds the workers. Memory: one record per frame, by
// request (the file holds them all).
#include <condition_variable>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "frame_stats.h"

namespace igi {

class StatsWriter {
 public:
  explicit StatsWriter(std::string path);
  ~StatsWriter();  // writes what was asked last, then returns
  void add(const FrameRecord& record);
  // Rewrites the file with every record so far and these totals (soon, on the writer's thread).
  void write(const RunTotals& totals);
  // Writes now, on the caller's thread, and waits: the final file. Throws when it cannot.
  void write_final(const RunTotals& totals);

 private:
  void run();
  std::string path_;
  std::mutex mutex_;
  std::condition_variable wake_;
  std::vector<FrameRecord> records_, incoming_;
  std::optional<RunTotals> pending_;
  bool stopping_ = false;
  std::thread thread_;
};

}  // namespace igi
