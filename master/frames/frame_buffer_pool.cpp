#include "frames/frame_buffer_pool.h"

namespace igi {

std::shared_ptr<FrameBuffer> FrameBufferPool::acquire(int width, int height, PixelFormat format) {
  std::unique_ptr<FrameBuffer> buffer;
  {
    std::lock_guard lock(state_->mutex);
    auto& spare = state_->spare;
    for (auto it = spare.begin(); it != spare.end(); ++it)
      if ((*it)->width == width && (*it)->height == height && (*it)->format == format) {
        buffer = std::move(*it);
        spare.erase(it);
        break;
      }
  }
  if (!buffer) buffer = std::make_unique<FrameBuffer>(width, height, format);
  std::weak_ptr<State> pool = state_;
  return std::shared_ptr<FrameBuffer>(buffer.release(), [pool](FrameBuffer* b) {
    std::unique_ptr<FrameBuffer> owned(b);
    if (auto state = pool.lock()) {
      std::lock_guard lock(state->mutex);
      if (state->spare.size() < state->keep) state->spare.push_back(std::move(owned));
    }
  });
}

size_t FrameBufferPool::spare() const {
  std::lock_guard lock(state_->mutex);
  return state_->spare.size();
}

}  // namespace igi
