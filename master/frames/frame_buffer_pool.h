#pragma once
// Frame buffers for the master's open frames, recycled: a 1920x1080 float
// frame is 25 MB, and a fresh one each frame costs the session thread its
// page faults (or a memset) 30 times a second. A buffer goes back to the pool
// when its last shared_ptr goes, on whatever thread that is (the writer, the
// window); the pool keeps at most `keep` spare buffers, so memory stays flat.
// Buffers come back with the pixels of an old frame: tiles overwrite every one.
#include <memory>
#include <mutex>
#include <vector>

#include "image/frame_buffer.h"

namespace igi {

class FrameBufferPool {
 public:
  explicit FrameBufferPool(size_t keep = 6) : state_(std::make_shared<State>()) { state_->keep = keep; }
  // Thread-safe. The buffer may outlive the pool.
  std::shared_ptr<FrameBuffer> acquire(int width, int height, PixelFormat format);
  size_t spare() const;

 private:
  struct State {
    std::mutex mutex;
    std::vector<std::unique_ptr<FrameBuffer>> spare;
    size_t keep = 6;
  };
  std::shared_ptr<State> state_;
};

}  // namespace igi
