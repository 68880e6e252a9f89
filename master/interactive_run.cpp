// The window: the session runs on a thread of its own; this thread draws.
//
// The display thread owns the window and the camera; it publishes the camera
// (with a generation that changes on every move) and takes completed frames.
// The session thread plans frames for the latest camera (pass p: seed + p and
// a new sub-pixel position, for accumulation), pumps the session, and hands
// each finished frame over with the generation it was planned for. Frames of
// an old generation are dropped on arrival. The hand-over queue is short: the
// session adds no frame while the display has frames it has not taken.
#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <deque>
#include <map>
#include <mutex>
#include <thread>
#include <utility>

#include "display/interactive_window.h"
#include "frame_plan.h"
#include "render/accumulator.h"
#include "run_modes.h"

namespace igi {
namespace {

struct Shown {
  CompletedFrame frame;
  uint64_t generation = 0;
  size_t workers = 0;  // when it completed (the display thread must not ask the session)
};

// What the two threads share, under one mutex.
class Handover {
 public:
  void publish(const Camera& camera, uint64_t generation) {
    std::lock_guard lock(mutex_);
    camera_ = camera;
    generation_ = generation;
  }
  std::pair<Camera, uint64_t> view() {
    std::lock_guard lock(mutex_);
    return {camera_, generation_};
  }
  void deliver(Shown shown) {
    {
      std::lock_guard lock(mutex_);
      frames_.push_back(std::move(shown));
    }
    arrived_.notify_one();
  }
  size_t waiting() {
    std::lock_guard lock(mutex_);
    return frames_.size();
  }
  // Waits up to `wait` for a frame (the window keeps polling input meanwhile).
  std::deque<Shown> take(std::chrono::milliseconds wait) {
    std::unique_lock lock(mutex_);
    arrived_.wait_for(lock, wait, [&] { return !frames_.empty() || stop_; });
    return std::exchange(frames_, {});
  }
  void stop(const std::string& error = {}) {
    {
      std::lock_guard lock(mutex_);
      stop_ = true;
      if (error_.empty()) error_ = error;
    }
    arrived_.notify_all();
  }
  bool stopped() {
    std::lock_guard lock(mutex_);
    return stop_;
  }
  std::string error() {
    std::lock_guard lock(mutex_);
    return error_;
  }

 private:
  std::mutex mutex_;
  std::condition_variable arrived_;
  Camera camera_;
  uint64_t generation_ = 0;
  std::deque<Shown> frames_;
  bool stop_ = false;
  std::string error_;
};

void session_loop(const MasterOptions& o, const Scene& scene, MasterSession& session, Handover& handover) {
  std::map<uint64_t, uint64_t> generation_of_frame;  // open frames only
  uint64_t generation = ~uint64_t(0), next_id = 0;
  int pass = 0;
  try {
    while (!handover.stopped()) {
      auto [camera, now_generation] = handover.view();
      if (now_generation != generation) {  // the camera moved: start over
        generation = now_generation;
        pass = 0;
      }
      if (session.can_add_frame() && handover.waiting() < 2) {
        FrameSetup f = plan_frame(o.render, o.camera_path, scene, pass++, true);
        f.frame_id = next_id++;
        f.camera = camera;
        generation_of_frame[f.frame_id] = generation;
        session.add_frame(f);
      }
      for (CompletedFrame& f : session.pump(5)) {
        const uint64_t g = generation_of_frame[f.setup.frame_id];
        generation_of_frame.erase(f.setup.frame_id);
        handover.deliver({std::move(f), g, session.worker_count()});
      }
    }
  } catch (const std::exception& e) {
    handover.stop(e.what());
  }
}

std::string status_line(const CompletedFrame& f, size_t workers, int accumulated, double fps) {
  char text[160];
  const double s = f.record.seconds;
  std::snprintf(text, sizeof text, "%.1f fps  %.0f ms/frame  %.1f Mrays/s  %zu workers  %d frames accumulated", fps,
                1e3 * s, s > 0 ? f.record.rays.total() * 1e-6 / s : 0.0, workers, accumulated);
  return text;
}

}  // namespace

int run_interactive(const MasterOptions& o, const Scene& scene, MasterSession& session, LocalWorkers& workers,
                    std::atomic<bool>& interrupted) {
  InteractiveWindow window(o.render.width, o.render.height, "igi-master: " + o.render.scene);
  CameraController controller(scene.camera_or_auto(), 0.25f * scene.bounds().diagonal());
  Accumulator accumulator(o.render.width, o.render.height);
  Handover handover;
  handover.publish(controller.camera(), controller.generation());
  std::thread session_thread([&] { session_loop(o, scene, session, handover); });
  uint64_t generation = controller.generation();
  auto last_frame = std::chrono::steady_clock::now();
  while (window.poll(controller) && !interrupted && !handover.stopped()) {
    if (controller.generation() != generation) {
      generation = controller.generation();
      accumulator.reset();
      handover.publish(controller.camera(), generation);
    }
    for (Shown& shown : handover.take(std::chrono::milliseconds(5))) {
      if (shown.generation != generation) continue;  // rendered for an old camera
      accumulator.add(shown.frame.pixels->to_image(), 1.0);
      shown.frame.pixels.reset();  // back to the pool
      const auto now = std::chrono::steady_clock::now();
      const double fps = 1.0 / std::max(1e-6, std::chrono::duration<double>(now - last_frame).count());
      last_frame = now;
      window.show(accumulator.resolve(), o.render.exposure);
      window.set_status(status_line(shown.frame, shown.workers, int(accumulator.weight()), fps));
      if (!o.render.screenshot.empty() && accumulator.weight() >= o.screenshot_after) {
        window.screenshot(o.render.screenshot);
        interrupted = true;
      }
      window.present();
    }
  }
  handover.stop();
  session_thread.join();
  session.close("window closed");
  workers.stop_all();
  if (const std::string error = handover.error(); !error.empty()) throw std::runtime_error(error);
  return 0;
}

}  // namespace igi
