#include "trust/master_renderer.h"

#include <chrono>
#include <exception>
#include <memory>
#include <utility>

#include <sys/eventfd.h>
#include <unistd.h>

#include "render/frame_job.h"
#include "protocol/codec.h"
#include "protocol/tile_result.h"
#include "render/scene_state.h"

namespace igi {

MasterRenderer::MasterRenderer(Scene scene) : fd_(eventfd(0, EFD_NONBLOCK | EFD_CLOEXEC)) {
  thread_ = std::thread([this, s = std::move(scene)]() mutable { run(std::move(s)); });
}

MasterRenderer::~MasterRenderer() {
  {
    std::lock_guard lock(mutex_);
    stopping_ = true;
    requests_.clear();
  }
  wake_.notify_all();
  thread_.join();
  close(fd_);
}

void MasterRenderer::request(const FrameSetup& frame, const RenderSettings& settings) {
  {
    std::lock_guard lock(mutex_);
    requests_.push_back({frame, settings, std::nullopt, {}, PixelFormat::Float32});
  }
  wake_.notify_one();
}

void MasterRenderer::request_tile(const FrameSetup& frame, const RenderSettings& settings, uint64_t job_id,
                                  const TileJob& tile, PixelFormat format) {
  {
    std::lock_guard lock(mutex_);
    requests_.push_back({frame, settings, job_id, tile, format});
  }
  wake_.notify_one();
}

std::vector<MasterRenderer::Answer> MasterRenderer::take() {
  std::lock_guard lock(mutex_);
  uint64_t count;
  while (read(fd_, &count, sizeof count) > 0) {}
  return std::exchange(answers_, {});
}

std::vector<MasterRenderer::TileAnswer> MasterRenderer::take_tiles() {
  std::lock_guard lock(mutex_);
  uint64_t count;
  while (read(fd_, &count, sizeof count) > 0) {}
  return std::exchange(tile_answers_, {});
}

// As a worker's render pool does it: the scene posed for the frame, then the
// frame's job made and begun (render/frame_job.h), then its hash or the tile.
void MasterRenderer::run(Scene scene) {
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
    const auto start = std::chrono::steady_clock::now();
    Answer answer;
    TileAnswer tile;
    answer.frame_id = request.frame.frame_id;
    answer.error = tile.error = load_error;
    if (state) {
      try {
        state->set_pose(request.frame.pose);
        FrameJob job(state->context(), request.settings);
        job.begin(request.frame);
        if (request.job_id) {
          RenderedTile t = job.render(request.tile);
          tile.result = protocol::encode(protocol::make_tile_result(request.frame.frame_id, *request.job_id,
                                                                    request.tile, std::move(t.pixels),
                                                                    std::move(t.surfaces), t.rays, job.state_hash(),
                                                                    request.format));
        } else {
          answer.hash = job.state_hash();
        }
      } catch (const std::exception& e) {
        answer.error = tile.error = e.what();
      }
    }
    answer.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    lock.lock();
    if (request.job_id) {
      tile.job_id = *request.job_id;
      tile_answers_.push_back(std::move(tile));
    } else {
      answers_.push_back(std::move(answer));
    }
    const uint64_t one = 1;
    (void)!write(fd_, &one, sizeof one);
  }
}

}  // namespace igi
