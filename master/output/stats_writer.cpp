#include "output/stats_writer.h"

#include <cstdio>
#include <stdexcept>
#include <utility>

namespace igi {

StatsWriter::StatsWriter(std::string path)
    : path_(std::move(path)), out_(path_, std::ios::trunc), thread_([this] { run(); }) {}

StatsWriter::~StatsWriter() {
  {
    std::lock_guard lock(mutex_);
    stopping_ = true;
  }
  wake_.notify_one();
  if (thread_.joinable()) thread_.join();
}

void StatsWriter::add(const FrameRecord& record) {
  std::unique_lock lock(mutex_);
  drained_.wait(lock, [&] { return incoming_.size() < kMaxPending || stopping_; });
  incoming_.push_back(record);
  if (incoming_.size() == kFlushRecords) wake_.notify_one();
}

void StatsWriter::write(const RunTotals& totals) {
  {
    std::lock_guard lock(mutex_);
    pending_ = totals;
  }
  wake_.notify_one();
}

void StatsWriter::write_final(const RunTotals& totals) {
  {
    std::unique_lock lock(mutex_);
    stopping_ = true;
    pending_.reset();
  }
  wake_.notify_one();
  thread_.join();  // the thread has appended whatever it was appending
  if (!append(incoming_, totals)) throw std::runtime_error(path_ + ": cannot write statistics");
}

bool StatsWriter::append(std::vector<FrameRecord>& records, const std::optional<RunTotals>& totals) {
  // A line at a time, so a reader (or a kill) sees whole lines but perhaps the last.
  const auto line = [](const nlohmann::ordered_json& j) {
    return j.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace) + "\n";
  };
  for (const FrameRecord& r : records) {
    out_ << line(frame_json(r));
    tiles_ += r.tiles;
  }
  records.clear();
  if (totals) out_ << line(totals_json(*totals, tiles_));
  out_.flush();
  return bool(out_);
}

void StatsWriter::run() {
  bool reported = false;  // a file that cannot be written is said once
  std::unique_lock lock(mutex_);
  for (;;) {
    wake_.wait_for(lock, kFlushInterval,
                   [&] { return stopping_ || pending_ || incoming_.size() >= kFlushRecords; });
    if (stopping_) return;
    if (incoming_.empty() && !pending_) continue;
    const std::optional<RunTotals> totals = std::exchange(pending_, std::nullopt);
    std::vector<FrameRecord> records;
    records.swap(incoming_);
    drained_.notify_all();
    lock.unlock();
    if (!append(records, totals) && !reported) {
      std::fprintf(stderr, "igi-master: %s: cannot write statistics\n", path_.c_str());
      reported = true;
    }
    lock.lock();
  }
}

}  // namespace igi
