#include "stats_writer.h"

#include <cstdio>

namespace igi {

StatsWriter::StatsWriter(std::string path) : path_(std::move(path)), thread_([this] { run(); }) {}

StatsWriter::~StatsWriter() {
  {
    std::lock_guard lock(mutex_);
    stopping_ = true;
  }
  wake_.notify_one();
  if (thread_.joinable()) thread_.join();
}

void StatsWriter::add(const FrameRecord& record) {
  std::lock_guard lock(mutex_);
  incoming_.push_back(record);
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
  thread_.join();  // the thread has written whatever it was writing
  for (FrameRecord& r : incoming_) records_.push_back(std::move(r));
  incoming_.clear();
  write_stats_json(path_, records_, totals);
}

void StatsWriter::run() {
  std::unique_lock lock(mutex_);
  for (;;) {
    wake_.wait(lock, [&] { return stopping_ || pending_; });
    if (stopping_) return;
    const RunTotals totals = *pending_;
    pending_.reset();
    for (FrameRecord& r : incoming_) records_.push_back(std::move(r));
    incoming_.clear();
    lock.unlock();
    try {
      write_stats_json(path_, records_, totals);
    } catch (const std::exception& e) {
      std::fprintf(stderr, "igi-master: %s\n", e.what());
    }
    lock.lock();
  }
}

}  // namespace igi
