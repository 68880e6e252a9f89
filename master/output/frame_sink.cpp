#include "output/frame_sink.h"

namespace igi {

FrameSink::FrameSink(int width, int height, ExposureChoice exposure, ViewTransform view, bool progressive)
    : exposure_(exposure), view_(view) {
  if (progressive) accumulator_.emplace(width, height);
  thread_ = std::thread([this] { run(); });
}

void FrameSink::finish() {
  {
    std::lock_guard lock(mutex_);
    stopping_ = true;
  }
  wake_.notify_one();
  if (thread_.joinable()) thread_.join();
}

void FrameSink::push(std::shared_ptr<FrameBuffer> pixels, std::string path) {
  {
    std::lock_guard lock(mutex_);
    queue_.emplace_back(std::move(pixels), std::move(path));
  }
  wake_.notify_one();
}

size_t FrameSink::backlog() const {
  std::lock_guard lock(mutex_);
  return queue_.size() + busy_;
}

std::string FrameSink::error() const {
  std::lock_guard lock(mutex_);
  return error_;
}

std::optional<Image> FrameSink::last_written() const {
  std::lock_guard lock(mutex_);
  return last_written_;
}

float FrameSink::last_exposure() const {
  std::lock_guard lock(mutex_);
  return last_exposure_;
}

void FrameSink::consume(const FrameBuffer& pixels, const std::string& path) {
  if (!accumulator_ && path.empty()) return;
  Image image = pixels.to_image();
  if (accumulator_) {
    accumulator_->add(image, 1.0);
    if (path.empty()) return;
    image = accumulator_->resolve();
  }
  const float exposure = is_float_format(path) ? exposure_.factor : exposure_for(image, exposure_);
  write_image(image, path, {exposure, view_});
  std::lock_guard lock(mutex_);
  last_written_ = std::move(image);
  last_exposure_ = exposure;
}

void FrameSink::run() {
  std::unique_lock lock(mutex_);
  for (;;) {
    wake_.wait(lock, [&] { return stopping_ || !queue_.empty(); });
    if (queue_.empty()) return;  // stopping, and nothing left to do
    auto [pixels, path] = std::move(queue_.front());
    queue_.pop_front();
    ++busy_;
    lock.unlock();
    std::string failure;
    try {
      consume(*pixels, path);
    } catch (const std::exception& e) {
      failure = e.what();
    }
    pixels.reset();  // back to the session's pool
    lock.lock();
    --busy_;
    if (error_.empty()) error_ = failure;
  }
}

}  // namespace igi
