// The window: the session runs on a thread of its own; this thread draws.
//
// The display thread owns the window and the camera; it publishes the camera
// (with a generation that changes on every move) and takes completed frames.
// The session thread plans frames for the latest camera (pass p: seed + p and
// a new sub-pixel position, for accumulation) with the latest settings (the
// panel's; they travel in each FrameSetup), pumps the session, and hands
// each finished frame over with the generation it was planned for. A camera
// move or a settings change starts a new generation; frames of an old one are
// dropped on arrival. The display thread accumulates, uploads floats and lets
// the GPU apply exposure and sRGB; the session thread only moves frames. The hand-over queue is short: the
// session adds no frame while the display has frames it has not taken.
#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <deque>
#include <map>
#include <mutex>
#include <optional>
#include <thread>
#include <utility>

#include "camera_bookmark.h"
#include "display/interactive_window.h"
#include "display/window_panel.h"
#include "frame_plan.h"
#include "render/accumulator.h"
#include "run_modes.h"
#include "scene/animation.h"
#include "stats_writer.h"

namespace igi {
namespace {

struct Shown {
  CompletedFrame frame;
  uint64_t generation = 0;
  size_t workers = 0;  // when it completed (the display thread must not ask the session)
  std::vector<PeerView> peers;
};

// What the two threads share, under one mutex.
class Handover {
 public:
  struct View {
    Camera camera;
    RenderSettings settings;
    uint64_t generation = 0;
    glm::vec3 light_offset{0.0f};  // where the keys moved the lights
    bool follow_camera = false;    // an animated camera the user has not placed: frames take the animation's
  };
  void publish(const View& view) {
    std::lock_guard lock(mutex_);
    view_ = view;
  }
  View view() {
    std::lock_guard lock(mutex_);
    return view_;
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
  View view_;
  std::deque<Shown> frames_;
  bool stop_ = false;
  std::string error_;
};

void session_loop(const MasterOptions& o, const Scene& scene, MasterSession& session, Handover& handover) {
  std::map<uint64_t, uint64_t> generation_of_frame;  // open frames only
  uint64_t generation = ~uint64_t(0), next_id = 0;
  int pass = 0, animation_frame = 0;
  const bool animated = scene.animation && scene.animation->animated();
  try {
    while (!handover.stopped()) {
      const Handover::View view = handover.view();
      if (view.generation != generation) {  // the camera moved or the settings changed: start over
        generation = view.generation;
        pass = 0;
      }
      if (session.can_add_frame() && handover.waiting() < 2) {
        RenderOptions render = o.render;
        render.settings = view.settings;  // pt's samples per pass depend on the method
        // An animation's frame k stands at its own time, as headless frame k: nothing accumulates.
        FrameSetup f = plan_frame(render, o.camera_path, scene, animated ? animation_frame++ : pass++, true);
        f.pose.light_offset = o.render.light_offset + view.light_offset;
        f.frame_id = next_id++;
        if (!view.follow_camera) f.camera = view.camera;  // else where the animation puts it at the frame's time
        generation_of_frame[f.frame_id] = generation;
        session.add_frame(f, view.settings);
      }
      for (CompletedFrame& f : session.pump(5)) {
        const uint64_t g = generation_of_frame[f.setup.frame_id];
        generation_of_frame.erase(f.setup.frame_id);
        handover.deliver({std::move(f), g, session.worker_count(), session.peer_views()});
      }
    }
  } catch (const std::exception& e) {
    handover.stop(e.what());
  }
}

std::string status_line(const CompletedFrame& f, size_t workers, int accumulated, double fps, bool animated) {
  char text[192];
  const double s = f.record.seconds;
  const int n = std::snprintf(text, sizeof text, "%.1f fps  %.0f ms/frame  %.1f Mrays/s  %zu workers  ", fps, 1e3 * s,
                              s > 0 ? f.record.rays.total() * 1e-6 / s : 0.0, workers);
  if (animated) std::snprintf(text + n, sizeof text - size_t(n), "t = %.2f s", f.setup.pose.time);
  else std::snprintf(text + n, sizeof text - size_t(n), "%d frames accumulated", accumulated);
  return text;
}

// Camera file, or image files, named in the panel: a failure is shown there, the window goes on.
std::string act(const PanelActions& a, const PanelOptions& p, CameraController& controller, float speed,
                const Accumulator& accumulator, float exposure, int& shots) {
  try {
    if (a.save_camera) {
      write_camera_file(p.bookmark, controller.camera());
      return "camera saved to " + p.bookmark;
    }
    if (a.load_camera) {
      controller = CameraController(read_camera_file(p.bookmark), speed);
      controller.hold();  // where the bookmark puts it, not where an animation would
      return "camera loaded from " + p.bookmark;
    }
    if (a.save_image) {
      char name[32];
      std::snprintf(name, sizeof name, "-%04d", shots++);
      const Image image = accumulator.resolve();
      write_image(image, p.shot_prefix + name + ".exr");
      write_image(image, p.shot_prefix + name + ".png", exposure);
      return "saved " + p.shot_prefix + name + ".exr and .png (" + std::to_string(int(accumulator.weight())) +
             " frames accumulated)";
    }
  } catch (const std::exception& e) {
    return e.what();
  }
  return {};
}

PanelOptions panel_options(const MasterOptions& o) {
  PanelOptions p;
  p.shown = o.panel;
  p.help = o.help;
  p.overlay = *parse_overlay(o.overlay);  // checked with the options
  if (!o.render.camera_file.empty()) p.bookmark = o.render.camera_file;
  return p;
}

// A frame the session rendered for the current view: into the accumulator,
// the status line, the stats file and the panel.
struct Shower {
  InteractiveWindow& window;
  WindowPanel& panel;
  CameraController& controller;
  Accumulator& accumulator;
  std::optional<StatsWriter>& stats;
  bool animated, camera_animated;
  int shown_frames = 0;
  std::chrono::steady_clock::time_point last_frame = std::chrono::steady_clock::now();

  void show(Shown& shown) {
    if (animated) accumulator.reset();  // each frame stands at its own time
    if (camera_animated) controller.follow(shown.frame.setup.camera);  // a first move starts from the view shown
    ++shown_frames;
    accumulator.add(shown.frame.pixels->to_image(), 1.0);
    shown.frame.pixels.reset();  // back to the pool
    const auto now = std::chrono::steady_clock::now();
    const double fps = 1.0 / std::max(1e-6, std::chrono::duration<double>(now - last_frame).count());
    last_frame = now;
    window.set_status(status_line(shown.frame, shown.workers, int(accumulator.weight()), fps, animated));
    FrameRecord& record = shown.frame.record;
    std::vector<TileSource> sources = std::move(record.tile_sources);  // the overlay's, not the file's
    if (stats) stats->add(record);
    record.tile_sources = std::move(sources);
    panel.frame_shown(record, std::move(shown.peers), fps);
  }
};

// The window's loop until it closes, is interrupted or the session stops.
void window_loop(const MasterOptions& o, const Scene& scene, MasterSession& session, std::atomic<bool>& interrupted,
                 Handover& handover, std::optional<StatsWriter>& stats) {
  InteractiveWindow window(o.render.width, o.render.height, "igi-master: " + o.render.scene);
  WindowPanel panel(window.handle(), o.render.settings, o.render.exposure, panel_options(o));
  const float speed = 0.25f * scene.bounds().diagonal();
  const bool animated = scene.animation && scene.animation->animated();
  const bool camera_animated = animated && scene.camera && scene.animation->camera_node >= 0;
  CameraController controller(scene_camera(scene, o.render.time), speed);
  Accumulator accumulator(o.render.width, o.render.height);
  uint64_t generation = 0, camera_generation = controller.generation();
  auto view = [&] {
    return Handover::View{controller.camera(), panel.settings().settings(), generation, controller.light_offset(),
                          camera_animated && !controller.placed()};
  };
  handover.publish(view());
  std::thread session_thread([&] { session_loop(o, scene, session, handover); });
  auto last_draw = std::chrono::steady_clock::now();
  bool edited = !o.test_panel_settings;  // the test hook edits once, after the first frame shown
  int shots = 0;
  Shower shower{window, panel, controller, accumulator, stats, animated, camera_animated};
  while (window.poll(controller) && !interrupted && !handover.stopped()) {
    if (controller.generation() != camera_generation || panel.settings().take_change()) {
      camera_generation = controller.generation();
      accumulator.reset();
      ++generation;
      handover.publish(view());
    }
    bool fresh = false;
    for (Shown& shown : handover.take(std::chrono::milliseconds(5))) {
      if (shown.generation != generation) continue;  // rendered for an old camera or old settings
      shower.show(shown);
      fresh = true;
    }
    const auto now = std::chrono::steady_clock::now();
    if (!fresh && now - last_draw < std::chrono::milliseconds(50)) continue;  // redraw for the panel at 20 Hz
    last_draw = now;
    if (fresh) window.upload(accumulator.resolve());
    window.draw(panel.settings().exposure());
    const PanelActions actions = panel.draw(int(accumulator.weight()));
    window.set_input_captured(panel.wants_mouse(), panel.wants_keyboard());
    if (std::string m = act(actions, panel.options(), controller, speed, accumulator, panel.settings().exposure(), shots);
        !m.empty())
      panel.set_message(m);
    if (actions.load_camera) camera_generation = ~controller.generation();  // a new controller: a new view
    const int settled = animated ? shower.shown_frames : int(accumulator.weight());  // an animation never accumulates
    if (fresh && edited && !o.render.screenshot.empty() && settled >= o.screenshot_after) {
      window.screenshot(o.render.screenshot);
      interrupted = true;
    }
    if (fresh && !edited) {  // as if the widgets had made this change: it shows from the next view on
      panel.settings().commit(*o.test_panel_settings);
      edited = true;
    }
    window.present();
  }
  handover.stop();
  session_thread.join();
}

}  // namespace

int run_interactive(const MasterOptions& o, const Scene& scene, MasterSession& session, LocalWorkers& workers,
                    std::atomic<bool>& interrupted) {
  std::optional<StatsWriter> stats;  // the frames the window showed
  if (!o.stats.empty()) stats.emplace(o.stats);
  session.set_detailed_stats(true);  // the cluster panel
  session.record_tile_sources(true);  // the tile overlay
  Handover handover;
  const auto wall_start = std::chrono::steady_clock::now();
  const double cpu_start = process_cpu_seconds();
  window_loop(o, scene, session, interrupted, handover, stats);
  session.close("window closed");
  workers.stop_all();
  if (stats) {  // the session thread has ended: its counts can be read here
    // The window's drawing is in the master's CPU time.
    RunTotals t = run_totals(session, o.io_threads, cpu_start,
                             std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count());
    t.complete = true;
    stats->write_final(t);
  }
  if (const std::string error = handover.error(); !error.empty()) throw std::runtime_error(error);
  return 0;
}

}  // namespace igi
