// The window: the session runs on a thread of its own (session_thread.h); this thread draws.
//
// The display thread owns the window and the camera; it publishes the view
// (camera and settings, each with a generation bumped by every change) and
// takes completed frames. The session thread plans frames for the latest
// view (motion_planner.h: previews within --frame-budget-ms while the camera
// moves, full frames once it is still), cancels the frames the view has left
// behind, pumps the session, and hands each finished frame over. The display
// thread shows every frame of the current settings, even one planned for a
// camera the user has since moved (so a drag shows frames as they come),
// carrying the accumulated image into each frame's view (view_history.h);
// a frame of older settings is dropped. It uploads floats and lets the GPU
// apply the tone mapping; the session thread only moves frames. The
// hand-over queue is short: the session adds no frame while the display has
// frames it has not taken.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <optional>
#include <thread>
#include <utility>

#include "view/camera_bookmark.h"
#include "display/interactive_window.h"
#include "display/view_changes.h"
#include "display/window_panel.h"
#include "view/frame_rate.h"
#include "image/exposure_check.h"
#include "view/motion_planner.h"
#include "run/run_modes.h"
#include "run/session_thread.h"
#include "scene/animation.h"
#include "output/stats_writer.h"
#include "render/view_history.h"

namespace igi {
namespace {

std::string metered_line(float exposure) {
  char text[64];
  std::snprintf(text, sizeof text, "exposure metered: %+.2f EV", std::log2(exposure));
  return text;
}

// The exposure metered from the image shown (M, the panel's "auto"), or the
// camera file or image files named in the panel: a failure is shown there, the window goes on.
std::string act(const PanelActions& a, WindowPanel& panel, CameraController& controller, float speed,
                const ViewHistory& history, int& shots) {
  const PanelOptions& p = panel.options();
  try {
    if (a.meter) {
      if (history.weight() <= 0.0) return "no image to meter yet";
      panel.settings().set_exposure(metered_exposure(history.resolve()));
      return metered_line(panel.settings().tone().exposure);
    }
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
      const Image image = history.resolve();
      write_image(image, p.shot_prefix + name + ".exr");
      write_image(image, p.shot_prefix + name + ".png", panel.settings().tone());
      char frames[64];
      std::snprintf(frames, sizeof frames, " (%.1f frames accumulated)", history.weight());
      return "saved " + p.shot_prefix + name + ".exr and .png" + frames;
    }
  } catch (const std::exception& e) {
    return e.what();
  }
  return {};
}

PanelOptions panel_options(const MasterOptions& o, const InteractiveWindow& window) {
  PanelOptions p;
  p.image_width = o.render.width;
  p.image_height = o.render.height;
  p.shown = o.panel && panel_opens(float(window.width()), float(window.height()), o.render.width, o.render.height,
                                   panel_layout(o.render.width).width);
  p.help = o.help;
  p.overlay = *parse_overlay(o.overlay);  // checked with the options
  if (!o.render.camera_file.empty()) p.bookmark = o.render.camera_file;
  const FrameBudget budget(o.render.width, o.render.height, 0.0, o.sharp_previews);
  for (const PreviewLevel& level : budget.levels()) p.preview_levels.push_back(level_name(level));
  return p;
}

// The exposure on opening (--exposure auto, the window's default): the
// image is metered after each frame it takes until a full frame has come
// (frames that arrive together are metered one by one, so the exposure is
// the first full frame's, as igi-render's of the same image), said once, and
// then holds while the view changes (M meters again).
struct OpeningMeter {
  bool metering;
  bool quiet;
  void shown(const Image& image, bool full, SettingsPanel& settings) {
    if (!metering) return;
    settings.set_exposure(metered_exposure(image));
    metering = !full;
    if (full && !quiet)
      std::fprintf(stderr, "igi-master: %s (M meters again)\n", metered_line(settings.tone().exposure).c_str());
  }
};

// A frame of the current settings: into the history (carried into its view),
// the opening meter, the status line, the stats file and the panel.
struct Shower {
  InteractiveWindow& window;
  WindowPanel& panel;
  CameraController& controller;
  ViewHistory& history;
  std::optional<StatsWriter>& stats;
  OpeningMeter& meter;
  bool animated, camera_animated;
  int shown_frames = 0;
  FrameRate rate;

  void show(Shown& shown) {
    if (animated) history.reset();  // each frame stands at its own time
    if (camera_animated) controller.follow(shown.frame.setup.camera);  // a first move starts from the view shown
    ++shown_frames;
    history.add(shown.frame.pixels->to_image(), shown.frame.surfaces, shown.frame.setup.camera, shown.weight,
                shown.frame.surface_offset);
    shown.frame.pixels.reset();  // back to the pool
    if (meter.metering) meter.shown(history.resolve(), shown.planned.level == 0, panel.settings());  // 0: full
    const auto now = FrameRate::Clock::now();
    rate.shown(now);
    const double fps = rate.fps(now);
    window.set_status(status_line(shown, history.weight(), fps, animated));
    FrameRecord& record = shown.frame.record;
    std::vector<TileSource> sources = std::move(record.tile_sources);  // the overlay's, not the file's
    if (stats) stats->add(record);
    record.tile_sources = std::move(sources);
    panel.frame_shown(record, std::move(shown.peers), fps, shown.level);
  }
};

// The window's loop until it closes, is interrupted or the session stops.
void window_loop(const MasterOptions& o, const Scene& scene, MasterSession& session, std::atomic<bool>& interrupted,
                 Handover& handover, std::optional<StatsWriter>& stats) {
  InteractiveWindow window(o.render.width, o.render.height, panel_layout(o.render.width).width, o.panel,
                           "igi-master: " + o.render.scene);
  const RenderOptions& r = o.render;
  OpeningMeter meter{!r.exposure_given || r.exposure.metered, r.quiet};
  WindowPanel panel(window.handle(), r.settings, {meter.metering ? 1.0f : r.exposure.factor, r.view},
                    panel_options(o, window));
  const float speed = 0.25f * scene.bounds().diagonal();
  const bool animated = scene.animation && scene.animation->animated();
  const bool camera_animated = animated && scene.camera && scene.animation->camera_node >= 0;
  CameraController controller(scene_camera(scene, o.render.time), speed);
  ViewHistory history(o.render.width, o.render.height, o.history_frames);
  ViewChanges changes(controller);
  auto view = [&] {
    return Handover::View{controller.camera(), panel.settings().settings(), changes.camera_generation(),
                          changes.settings_generation(), controller.light_offset(),
                          camera_animated && !controller.placed(), panel.options().preview};
  };
  handover.publish(view());
  const double budget_ms = o.frame_budget_ms >= 0.0 ? o.frame_budget_ms : kWindowFrameBudgetMs;
  std::thread session_thread([&] { session_loop(o, scene, session, handover, budget_ms); });
  auto last_draw = std::chrono::steady_clock::now();
  bool edited = !o.test_panel_settings;  // the test hook edits once, after the first frame shown
  int shots = 0;
  Shower shower{window, panel, controller, history, stats, meter, animated, camera_animated, 0, {}};
  while (window.poll(controller) && !interrupted && !handover.stopped()) {
    const ViewChanges::Change change = changes.take(panel, controller, handover.view().preview);
    if (change == ViewChanges::Change::Settings) history.reset();  // the image starts over; a camera's is carried
    if (change != ViewChanges::Change::None) handover.publish(view());
    bool fresh = false;
    for (Shown& shown : handover.take(std::chrono::milliseconds(5))) {
      if (shown.planned.settings_generation != changes.settings_generation()) continue;  // rendered with old settings
      shower.show(shown);
      fresh = true;
    }
    const auto now = std::chrono::steady_clock::now();
    if (!fresh && now - last_draw < std::chrono::milliseconds(50)) continue;  // redraw for the panel at 20 Hz
    last_draw = now;
    if (fresh) window.upload(history.resolve());
    if (!fresh && shower.rate.waiting(now) > 1.0) window.set_status(waiting_line(shower.rate.waiting(now)));
    if (!fresh) panel.set_waiting(shower.rate.waiting(now));
    window.draw(panel.image_viewport(float(window.width()), float(window.height())), panel.settings().tone());
    const PanelActions actions = panel.draw(int(history.weight()), window.take_panel_taps());
    window.set_input_captured(panel.wants_mouse(), panel.wants_keyboard());
    if (std::string m = act(actions, panel, controller, speed, history, shots); !m.empty()) {
      std::fprintf(stderr, "igi-master: %s\n", m.c_str());  // on the terminal, and on screen for a few seconds
      panel.set_message(m);
    }
    if (actions.load_camera) changes.forget_camera(controller);  // a new controller: a new view
    const int settled = animated ? shower.shown_frames : int(history.weight());  // an animation never accumulates
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
    t.outcome = "done";
    stats->write_final(t);
  }
  if (const std::string error = handover.error(); !error.empty()) throw std::runtime_error(error);
  return 0;
}

}  // namespace igi
