#include "render_pool.h"

#include <chrono>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>

#include "methods/memory_check.h"
#include "protocol/tile_result.h"

#include <sys/eventfd.h>
#include <unistd.h>

namespace igi {

RenderPool::RenderPool(SceneState& scene, PixelFormat format, int threads, uint64_t memory_bytes)
    : scene_(scene),
      format_(format),
      memory_bytes_(memory_bytes > 0 ? memory_bytes : machine_memory_bytes()),
      results_fd_(eventfd(0, EFD_NONBLOCK)) {
  for (int i = 0; i < threads; ++i) threads_.emplace_back([this] { run(); });
}

RenderPool::~RenderPool() {
  {
    std::lock_guard lock(mutex_);
    stopping_ = true;
    queue_.clear();
  }
  wake_.notify_all();
  posed_.notify_all();
  for (std::thread& t : threads_) t.join();
  close(results_fd_);
}

void RenderPool::add_frame(const FrameSetup& frame, const RenderSettings& settings) {
  // The method is made later, on a render thread at the frame's pose: what
  // its constructor would refuse is refused here, on the caller's thread.
  if (settings.method != MethodKind::PathTracer)
    if (auto error = settings_error(settings)) throw std::invalid_argument(*error);
  // The master checked its own memory; this machine may have less.
  if (std::string error = memory_error(settings, memory_bytes_); !error.empty()) throw std::invalid_argument(error);
  auto state = std::make_shared<FrameState>();
  state->setup = frame;
  state->settings = settings;
  std::lock_guard lock(mutex_);
  frames_[frame.frame_id] = std::move(state);
  // Keep the newest few: results of older frames may still be in flight.
  while (frames_.size() > 4) frames_.erase(frames_.begin());
}

void RenderPool::add_job(const protocol::TileJobMsg& job) {
  {
    std::lock_guard lock(mutex_);
    queue_.push_back(job);
  }
  wake_.notify_one();
}

void RenderPool::cancel_frame(uint64_t frame_id) {
  std::lock_guard lock(mutex_);
  std::erase_if(queue_, [&](const protocol::TileJobMsg& job) { return job.frame_id == frame_id; });
  frames_.erase(frame_id);  // a tile rendering now keeps its state alive until it is done
}

std::string RenderPool::failure() const {
  std::lock_guard lock(mutex_);
  return failure_;
}

std::vector<protocol::TileResult> RenderPool::take_results() {
  std::lock_guard lock(mutex_);
  uint64_t count;
  while (read(results_fd_, &count, sizeof count) > 0) {}
  return std::exchange(results_, {});
}

protocol::TileResult RenderPool::render(const protocol::TileJobMsg& job, FrameState& frame) {
  auto start = std::chrono::steady_clock::now();
  std::call_once(frame.begun, [&] {  // as every node renders a frame's jobs (render/frame_job.h)
    frame.job = std::make_unique<FrameJob>(scene_.context(), frame.settings);
    frame.job->begin(frame.setup);
  });
  // Each render thread keeps its tile's scratch: the master could not know how many this machine has.
  if (std::string error = tile_memory_error(frame.settings, job.tile.w, job.tile.h, int(threads_.size()), memory_bytes_);
      !error.empty())
    throw std::invalid_argument(error);
  RenderedTile tile = frame.job->render(job.tile);
  protocol::TileResult r = protocol::make_tile_result(job.frame_id, job.job_id, job.tile, std::move(tile.pixels),
                                                      std::move(tile.surfaces), tile.rays, frame.job->state_hash(),
                                                      format_);
  r.render_seconds = std::chrono::duration<float>(std::chrono::steady_clock::now() - start).count();
  return r;
}

bool RenderPool::wait_for_pose(std::unique_lock<std::mutex>& lock, const ScenePose& pose) {
  for (;;) {
    if (stopping_) return false;
    if (scene_.pose() && *scene_.pose() == pose) return true;
    if (rendering_ == 0) {
      scene_.set_pose(pose);  // under the lock: no tile starts meanwhile
      return true;
    }
    posed_.wait(lock);
  }
}

void RenderPool::run() {
  enable_flush_to_zero();
  std::unique_lock lock(mutex_);
  for (;;) {
    wake_.wait(lock, [&] { return stopping_ || !queue_.empty(); });
    if (stopping_) return;
    protocol::TileJobMsg job = queue_.front();
    queue_.pop_front();
    auto frame = frames_.find(job.frame_id);
    if (frame == frames_.end()) continue;  // a frame we were never told about: drop
    std::shared_ptr<FrameState> state = frame->second;  // alive while we wait, even if forgotten meanwhile
    const FrameSetup& setup = state->setup;
    if (job.tile.x + job.tile.w > setup.width || job.tile.y + job.tile.h > setup.height) continue;  // outside the image
    if (!wait_for_pose(lock, setup.pose)) return;
    ++rendering_;
    lock.unlock();
    std::optional<protocol::TileResult> result;
    std::string error;
    try {
      result = render(job, *state);
    } catch (const std::exception& e) {  // a throw would end the process without a word to the master
      error = "frame " + std::to_string(job.frame_id) + ": " + e.what();
    }
    lock.lock();
    --rendering_;
    if (rendering_ == 0) posed_.notify_all();  // a thread may wait for this, to pose the scene
    if (result) results_.push_back(std::move(*result));
    else if (failure_.empty()) failure_ = error;
    const uint64_t one = 1;
    (void)!write(results_fd_, &one, sizeof one);  // wakes the socket loop
  }
}

}  // namespace igi
