#pragma once
// The worker's render threads. The socket loop pushes jobs and pops results;
// render threads never touch the socket, so heartbeats never wait on a tile.
//
// Frames may stand at different scene poses (animation time, moved lights).
// The scene is posed between tiles, never under one: a thread whose job needs
// another pose waits until no tile renders, poses the scene, and goes on; a
// frame's method is made and begun only once its pose stands, so no tile of
// a frame ever sees another frame's scene.
//
// These are threads of their own, not tasks of the shared pool
// (core/parallel.h): they block on the queue and on a pose change, which
// a TBB task must not do. Work inside a frame (begin_frame's per-set work,
// photons, the light tree) runs on the shared pool.
#include <condition_variable>
#include <deque>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "core/method.h"
#include "render/frame_job.h"
#include "protocol/messages.h"
#include "render/scene_state.h"

namespace igi {

class RenderPool {
 public:
  // Results carry their pixels in `format`, made sendable (protocol::wire_pixels: finite, in range).
  // Frames whose VPLs or photons would not fit in `memory_bytes` (0: this machine's) are refused.
  RenderPool(SceneState& scene, PixelFormat format, int threads, uint64_t memory_bytes = 0);
  ~RenderPool();  // finishes nothing further: pending jobs are dropped

  // A frame's setup must be added before its jobs; its method is made for the
  // frame's own settings (they may change between frames). Throws
  // std::invalid_argument for settings this machine cannot render. The four
  // newest frames are kept (results of older ones may still be in flight); an
  // older one is forgotten, and its jobs still queued are dropped.
  void add_frame(const FrameSetup& frame, const RenderSettings& settings);
  void add_job(const protocol::TileJobMsg& job);
  // The master left the frame behind: its queued jobs are dropped and it is
  // forgotten; a tile of it rendering now is finished and sent as usual.
  void cancel_frame(uint64_t frame_id);
  std::vector<protocol::TileResult> take_results();
  // Why a frame could not be rendered here (its method threw: memory, a
  // setting this machine cannot hold); empty while all is well. The worker
  // then says so to the master and exits: its other results are not sent.
  std::string failure() const;
  // Readable (poll) whenever results are waiting; take_results() clears it.
  int results_fd() const { return results_fd_; }

 private:
  struct FrameState {
    FrameSetup setup;
    RenderSettings settings;
    std::unique_ptr<FrameJob> job;
    std::once_flag begun;  // made and begun (VPLs) by the first job, off the socket thread, at the frame's pose
  };
  void run();
  // With the lock held: waits until the scene stands at `pose`, posing it when no tile renders.
  bool wait_for_pose(std::unique_lock<std::mutex>& lock, const ScenePose& pose);
  protocol::TileResult render(const protocol::TileJobMsg& job, FrameState& frame);

  SceneState& scene_;
  int rendering_ = 0;  // tiles being rendered now
  PixelFormat format_;
  uint64_t memory_bytes_;
  mutable std::mutex mutex_;
  std::condition_variable wake_;   // a job was queued
  std::condition_variable posed_;  // no tile renders any more: a waiting thread may pose
  std::deque<protocol::TileJobMsg> queue_;
  std::vector<protocol::TileResult> results_;
  std::string failure_;  // the first
  std::map<uint64_t, std::shared_ptr<FrameState>> frames_;
  bool stopping_ = false;
  int results_fd_ = -1;  // eventfd
  std::vector<std::thread> threads_;
};

}  // namespace igi
