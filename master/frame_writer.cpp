#include "frame_writer.h"

namespace igi {

FrameWriter::FrameWriter(float exposure) : exposure_(exposure), thread_([this] { run(); }) {}

FrameWriter::~FrameWriter() {
  {
    std::lock_guard lock(mutex_);
    stopping_ = true;
  }
  wake_.notify_one();
  thread_.join();
}

void FrameWriter::write(Image image, std::string path) {
  {
    std::lock_guard lock(mutex_);
    queue_.emplace_back(std::move(image), std::move(path));
  }
  wake_.notify_one();
}

std::string FrameWriter::error() const {
  std::lock_guard lock(mutex_);
  return error_;
}

void FrameWriter::run() {
  std::unique_lock lock(mutex_);
  for (;;) {
    wake_.wait(lock, [&] { return stopping_ || !queue_.empty(); });
    if (queue_.empty()) return;  // stopping, and nothing left to write
    auto [image, path] = std::move(queue_.front());
    queue_.pop_front();
    lock.unlock();
    std::string failure;
    try {
      write_image(image, path, exposure_);
    } catch (const std::exception& e) {
      failure = e.what();
    }
    lock.lock();
    if (error_.empty()) error_ = failure;
  }
}

}  // namespace igi
