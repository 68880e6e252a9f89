// Headless --motion: a scripted user moves the camera while the session
// renders, through the same planner and history as the window
// (motion_planner.h, view_history.h), so the motion benchmark
// (scripts/bench-motion.sh) measures what the window shows.
//
// The script: for --motion-seconds the camera moves (drag: turns 30 degrees
// a second about the vertical, one way for the first half and back for the
// second, as a user looks aside and back; walk: goes forward at the window's
// W speed, a quarter of the scene's diagonal a second), in poses of 1/30 s; then it
// stands still at the last pose for --still-seconds. Every frame shown is
// logged in DIR/motion.jsonl (its time, pose, level, cost, the share of
// pixels that kept their history, and the mean luminance of the frame as
// rendered, before the history: its flicker); the images of frames at every 10th pose
// and of the still part go to DIR/shown-NNNN.exr after the run (writing
// them during it would take the session's time), and each 10th pose's
// camera to DIR/camera-POSE.json, for references.
//
// --motion-legacy: the behaviour before motion was handled, for comparison:
// no budget, no cancelled frames, frames of an older camera dropped, and
// the accumulated image thrown away on every move.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "view/camera_bookmark.h"
#include "view/motion_planner.h"
#include "run/run_modes.h"
#include "sampling/warp.h"
#include "scene/animation.h"
#include "render/view_history.h"

namespace igi {
namespace {

using Clock = std::chrono::steady_clock;
constexpr double kPosesPerSecond = 30.0;
constexpr int kReferenceEvery = 10;  // poses

Camera pose_camera(const MasterOptions& o, const Camera& home, float speed, int pose) {
  Camera c = home;
  const double seconds = pose / kPosesPerSecond;
  if (o.motion == "drag") {
    const double half = 0.5 * o.motion_seconds;
    const float a = float(glm::radians(30.0 * (seconds <= half ? seconds : 2.0 * half - seconds)));
    const glm::mat3 r(glm::vec3(std::cos(a), 0, -std::sin(a)), glm::vec3(0, 1, 0), glm::vec3(std::sin(a), 0, std::cos(a)));
    c.forward = r * c.forward;
    c.up = r * c.up;
  } else {  // walk
    c.position += glm::normalize(c.forward) * float(speed * seconds);
  }
  return c;
}

struct Kept {
  int shown;
  Image image;
};

}  // namespace

int run_motion(const MasterOptions& o, const Scene& scene, MasterSession& session, LocalWorkers& workers,
               const std::atomic<bool>& interrupted) {
  namespace fs = std::filesystem;
  fs::create_directories(o.motion_out);
  std::ofstream log(fs::path(o.motion_out) / "motion.jsonl");
  const bool legacy = o.motion_legacy;
  const double budget_ms = legacy ? 0.0 : o.frame_budget_ms >= 0.0 ? o.frame_budget_ms : kWindowFrameBudgetMs;
  MasterOptions planned = o;
  planned.reproject = o.reproject && !legacy;
  MotionPlanner planner(planned, scene, budget_ms);
  ViewHistory history(o.render.width, o.render.height, o.history_frames);
  const Camera home = scene_camera(scene, o.render.time);
  const float speed = 0.25f * scene.bounds().diagonal();
  const int last_pose = int(std::lround(o.motion_seconds * kPosesPerSecond));
  MovingView view{home, o.render.settings, 0, 0, glm::vec3(0.0f), false};
  for (int pose = 0; pose <= last_pose; pose += kReferenceEvery)
    write_camera_file((fs::path(o.motion_out) / ("camera-" + std::to_string(pose) + ".json")).string(),
                      pose_camera(o, home, speed, pose));
  if (last_pose % kReferenceEvery)
    write_camera_file((fs::path(o.motion_out) / ("camera-" + std::to_string(last_pose) + ".json")).string(),
                      pose_camera(o, home, speed, last_pose));
  char header[160];
  std::snprintf(header, sizeof header, "{\"motion_seconds\": %.3f, \"still_seconds\": %.3f, \"budget_ms\": %.1f}\n",
                o.motion_seconds, o.still_seconds, budget_ms);
  log << header;
  // Frames start once a worker is there: the script's clock starts with the first frame shown.
  std::vector<Kept> kept;
  int shown = 0;
  std::optional<Clock::time_point> start;
  const double end = o.motion_seconds + o.still_seconds;
  while (!interrupted) {
    const double t = start ? std::chrono::duration<double>(Clock::now() - *start).count() : 0.0;
    if (t > end) break;
    const int pose = std::min(last_pose, int(t * kPosesPerSecond));
    if (uint64_t(pose) != view.camera_generation) {
      view.camera = pose_camera(o, home, speed, pose);
      view.camera_generation = uint64_t(pose);
    }
    for (MovedFrame& f : planner.turn(session, view, true, 2)) {
      if (!start) start = Clock::now();
      const int frame_pose = int(f.planned.camera_generation);
      if (legacy && f.planned.camera_generation != view.camera_generation) continue;  // stale: dropped
      // (Legacy frames carry no surfaces: a moved camera starts the history over.)
      Image rendered = f.frame.pixels->to_image();
      const float mean = luminance(rendered.mean());  // the frame's own brightness: flicker between frames
      history.add(std::move(rendered), f.frame.surfaces, f.frame.setup.camera, f.weight, f.frame.surface_offset);
      const double now = std::chrono::duration<double>(Clock::now() - *start).count();
      char line[320];
      std::snprintf(line, sizeof line,
                    "{\"shown\": %d, \"t\": %.4f, \"pose\": %d, \"moving\": %s, \"level\": \"%s\", \"divisor\": %d, "
                    "\"ms\": %.2f, \"weight\": %.4f, \"carried\": %.4f, \"mean\": %.6g}\n",
                    shown, now, frame_pose, frame_pose < last_pose ? "true" : "false", level_name(f.level).c_str(),
                    f.level.divisor, 1e3 * f.frame.record.seconds, history.weight(), history.carried(), mean);
      log << line << std::flush;
      if (frame_pose % kReferenceEvery == 0 || frame_pose == last_pose) kept.push_back({shown, history.resolve()});
      ++shown;
    }
  }
  session.close(interrupted ? "interrupted" : "done");
  workers.stop_all();
  for (const Kept& k : kept) {
    char name[32];
    std::snprintf(name, sizeof name, "shown-%04d.exr", k.shown);
    write_image(k.image, (fs::path(o.motion_out) / name).string());
  }
  if (!o.render.quiet) std::fprintf(stderr, "igi-master: --motion %s: %d frames shown\n", o.motion.c_str(), shown);
  return 0;
}

}  // namespace igi
