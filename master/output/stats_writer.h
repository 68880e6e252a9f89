#pragma once
// --stats on a thread of its own: the session thread hands over each frame's
// record and, now and then, the run's totals; this thread appends their lines
// to the file (JSON Lines, frame_stats.h), so writing never stalls the loop
// that feeds the workers. Records are appended by count and by time (every
// kFlushRecords, and at least once a second), so a killed master leaves all
// but the last second's, and memory holds only the records not yet written:
// at most kMaxPending waiting (add() waits for the file beyond that) and the
// batch being appended.
#include <chrono>
#include <condition_variable>
#include <fstream>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "output/frame_stats.h"

namespace igi {

class StatsWriter {
 public:
  static constexpr size_t kFlushRecords = 256;
  static constexpr size_t kMaxPending = 4096;
  static constexpr std::chrono::milliseconds kFlushInterval{1000};

  explicit StatsWriter(std::string path);  // starts the file afresh
  ~StatsWriter();  // stops the thread once its current append is done
  void add(const FrameRecord& record);  // waits while kMaxPending records wait for the file
  // Appends the records so far and these totals (soon, on the writer's thread).
  void write(const RunTotals& totals);
  // Appends the last records and the final totals now, on the caller's thread, and waits. Throws when it cannot.
  void write_final(const RunTotals& totals);

 private:
  void run();
  // Appends `records`' lines, then the totals' line if any; false when the file cannot be written.
  bool append(std::vector<FrameRecord>& records, const std::optional<RunTotals>& totals);
  std::string path_;
  std::ofstream out_;  // the writer's thread's, then write_final()'s
  uint64_t tiles_ = 0;  // of every frame appended
  std::mutex mutex_;
  std::condition_variable wake_, drained_;
  std::vector<FrameRecord> incoming_;
  std::optional<RunTotals> pending_;
  bool stopping_ = false;
  std::thread thread_;
};

}  // namespace igi
