#include "reference_hashes.h"

#include <exception>
#include <memory>
#include <utility>

#include <sys/eventfd.h>
#include <unistd.h>

#include "core/method.h"
#include "render/scene_state.h"

namespace igi {

ReferenceHashes::ReferenceHashes(Scene scene) : fd_(eventfd(0, EFD_NONBLOCK | EFD_CLOEXEC)) {
  thread_ = std::thread([this, s = std::move(scene)]() mutable { run(std::move(s)); });
}

ReferenceHashes::~ReferenceHashes() {
  {
    std::lock_guard lock(mutex_);
    stopping_ = true;
    requests_.clear();
  }
  wake_.notify_all();
  thread_.join();
  close(fd_);
}

void ReferenceHashes::request(const FrameSetup& frame, const RenderSettings& settings) {
  {
    std::lock_guard lock(mutex_);
    requests_.push_back({frame, settings});
  }
  wake_.notify_one();
}

std::vector<ReferenceHashes::Answer> ReferenceHashes::take() {
  std::lock_guard lock(mutex_);
  uint64_t count;
  while (read(fd_, &count, sizeof count) > 0) {}
  return std::exchange(answers_, {});
}

// As a worker's render pool does it: the scene posed for the frame, then the
// frame's method made and begun (render_pool.cpp).
void ReferenceHashes::run(Scene scene) {
  enable_flush_to_zero();  // as on every render thread: the VPLs' floats must be the workers'
  std::unique_ptr<SceneState> state;
  std::string load_error;
  try {
    state = std::make_unique<SceneState>(std::move(scene));
  } catch (const std::exception& e) {
    load_error = std::string("the master cannot build the scene: ") + e.what();
  }
  std::unique_lock lock(mutex_);
  for (;;) {
    wake_.wait(lock, [&] { return stopping_ || !requests_.empty(); });
    if (stopping_) return;
    const Request request = std::move(requests_.front());
    requests_.pop_front();
    lock.unlock();
    Answer answer;
    answer.frame_id = request.frame.frame_id;
    answer.error = load_error;
    if (state) {
      try {
        state->set_pose(request.frame.pose);
        answer.hash = expected_frame_state_hash(state->context(), request.frame, request.settings);
      } catch (const std::exception& e) {
        answer.error = e.what();
      }
    }
    lock.lock();
    answers_.push_back(std::move(answer));
    const uint64_t one = 1;
    (void)!write(fd_, &one, sizeof one);
  }
}

}  // namespace igi
