#pragma once
// The master's own renders, from the scene as workers load it:
//  - each frame's VPL-set hash. Every worker gets the same scene, settings
//    and frame setup, so the master can make and begin the same method itself
//    and judge each worker's hash against what it must have computed: no vote
//    among workers, which two fake peers that agree could win;
//  - a tile job whose results failed validation on every worker that could
//    take it (the scheduler's take_own_jobs()): the master renders it as a
//    worker would (render/frame_job.h), so no failing worker, nor two,
//    can keep a frame from completing.
//
// One thread of its own: the scene's BVH is built there (the session thread
// goes on answering peers meanwhile), then requests are served one after
// another, each at its frame's pose. Answers come back through take() and
// take_tiles(); fd() is readable while any wait, so the session's poll()
// wakes for them.
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "core/frame.h"
#include "core/settings.h"
#include "protocol/messages.h"
#include "scene/scene.h"

namespace igi {

class MasterRenderer {
 public:
  explicit MasterRenderer(Scene scene);
  ~MasterRenderer();  // abandons requests not yet begun
  MasterRenderer(const MasterRenderer&) = delete;
  MasterRenderer& operator=(const MasterRenderer&) = delete;

  // The frame's VPL-set hash, answered through take().
  void request(const FrameSetup& frame, const RenderSettings& settings);
  // One tile of the frame in `format`, answered through take_tiles(). The
  // frame's method is begun again for it: this is for the rare job no worker
  // could render, not for sharing the frame's work.
  void request_tile(const FrameSetup& frame, const RenderSettings& settings, uint64_t job_id, const TileJob& tile,
                    PixelFormat format);

  struct Answer {
    uint64_t frame_id = 0;
    std::optional<uint64_t> hash;  // none when the master could not compute it (error says why)
    std::string error;
    double seconds = 0.0;          // the thread's time for it (pose, method, VPL sets)
  };
  struct TileAnswer {
    uint64_t job_id = 0;
    std::vector<uint8_t> result;  // the encoded TileResult, as a worker sends it; empty on error
    std::string error;
  };
  std::vector<Answer> take();
  std::vector<TileAnswer> take_tiles();
  int fd() const { return fd_; }

 private:
  struct Request {
    FrameSetup frame;
    RenderSettings settings;
    std::optional<uint64_t> job_id;  // a tile request
    TileJob tile;
    PixelFormat format = PixelFormat::Float32;
  };
  void run(Scene scene);

  std::mutex mutex_;
  std::condition_variable wake_;
  std::deque<Request> requests_;
  std::vector<Answer> answers_;
  std::vector<TileAnswer> tile_answers_;
  bool stopping_ = false;
  int fd_ = -1;  // eventfd
  std::thread thread_;
};

}  // namespace igi
