#pragma once
// The session thread's half of a view that moves (the window, the motion
// benchmark): which frame to render next for the latest view, at which
// preview level, and which open frames the view has left behind.
//
//  - Passes count on across camera moves (seed + pass: fresh VPL sets, the
//    next sub-pixel position), so a moving image averages independent sets;
//    a settings change or a moved light starts them at 0. The clamp relaxes
//    (FrameSetup.sample_begin) only with the passes since the camera last
//    moved: a reprojected history holds no more than those of one view.
//  - A frame is "moving" when the camera changed within kStillAfter of it
//    (a drag's events come every 10-50 ms: a frame planned between two of
//    them is still part of the move): it renders at the level FrameBudget
//    picks; a still frame at full level.
//  - When the view moves on, open frames of an older view are cancelled,
//    but for the oldest one if it is a preview (or there is no budget): it
//    is about to come, and it is what the window shows while the camera
//    moves. A frame of older settings is always cancelled.
#include <chrono>
#include <cstdint>
#include <map>
#include <vector>

#include <glm/glm.hpp>

#include "view/frame_budget.h"
#include "options/master_options.h"
#include "session/master_session.h"
#include "scene/scene.h"

namespace igi {

struct MovingView {
  Camera camera;
  RenderSettings settings;
  uint64_t camera_generation = 0;    // bumped by every camera move
  uint64_t settings_generation = 0;  // bumped by a settings change or a moved light
  glm::vec3 light_offset{0.0f};      // where the keys moved the lights
  bool follow_camera = false;        // an animated camera the user has not placed: frames take the animation's
  int preview = -1;                  // the panel's pin: -1 the budget picks the level, else this level index
};

// What a frame was planned as.
struct PlannedFrame {
  uint64_t camera_generation = 0, settings_generation = 0;
  int level = 0;        // index into FrameBudget::levels()
  bool moving = false;
  bool surfaces = false;  // it asked for its pixels' surfaces
};

// A completed frame as the view's history takes it.
struct MovedFrame {
  CompletedFrame frame;
  PlannedFrame planned;
  PreviewLevel level;
  double weight = 1.0;  // what it counts for in an accumulated image (level_weight())
};

class MotionPlanner {
 public:
  // `budget_ms`: FrameBudget's (0: every frame full).
  MotionPlanner(const MasterOptions& options, const Scene& scene, double budget_ms);

  // Open frames (oldest first) that `view` has left behind: cancel them.
  std::vector<uint64_t> stale(const MovingView& view, const std::vector<uint64_t>& open) const;
  // The next frame for `view`, and the settings it renders with.
  using Clock = std::chrono::steady_clock;
  static constexpr std::chrono::milliseconds kStillAfter{150};
  FrameSetup next(const MovingView& view, RenderSettings& settings, Clock::time_point now = Clock::now());
  // A frame completed: its level's cost is measured. Returns what it was planned as.
  PlannedFrame completed(uint64_t frame_id, double seconds);
  // One turn of the session thread's loop (the window's and the motion
  // benchmark's): cancels what `view` left behind, adds a frame when the
  // session has room and `room` says the display does, and pumps the session
  // for up to `pump_ms`. Returns the frames completed meanwhile.
  std::vector<MovedFrame> turn(MasterSession& session, const MovingView& view, bool room, int pump_ms);
  FrameBudget& budget() { return budget_; }

 private:
  const MasterOptions& options_;
  const Scene& scene_;
  FrameBudget budget_;
  std::map<uint64_t, PlannedFrame> planned_;  // open frames
  uint64_t next_id_ = 0;
  uint64_t settings_generation_ = ~uint64_t(0), camera_generation_ = ~uint64_t(0);
  uint64_t seen_settings_ = ~uint64_t(0), seen_camera_ = ~uint64_t(0);  // the view turn() last cancelled for
  Clock::time_point camera_moved_{};  // when next() last saw a new camera
  // The view (camera, settings generation) a full-size frame with surfaces
  // has completed for: the window's history keeps only that one's while the
  // camera stands still (view_history.h), so later passes ask for none.
  std::pair<uint64_t, uint64_t> surfaces_for_{~uint64_t(0), ~uint64_t(0)};
  int pass_ = 0, still_passes_ = 0, animation_frame_ = 0;
};

}  // namespace igi
