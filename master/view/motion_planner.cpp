#include "view/motion_planner.h"

#include "view/frame_plan.h"
#include "scene/animation.h"

namespace igi {

MotionPlanner::MotionPlanner(const MasterOptions& options, const Scene& scene, double budget_ms)
    : options_(options), scene_(scene), budget_(options.render.width, options.render.height, budget_ms, options.sharp_previews) {}

std::vector<uint64_t> MotionPlanner::stale(const MovingView& view, const std::vector<uint64_t>& open) const {
  std::vector<uint64_t> out;
  bool oldest = true;
  for (uint64_t id : open) {
    auto it = planned_.find(id);
    if (it == planned_.end()) continue;
    const PlannedFrame& p = it->second;
    const bool old_settings = p.settings_generation != view.settings_generation;
    const bool old_camera = p.camera_generation != view.camera_generation;
    const bool keep = oldest && (p.level != 0 || budget_.budget_ms() <= 0.0 || budget_.pinned());
    if (old_settings || (old_camera && !keep)) out.push_back(id);
    oldest = false;
  }
  return out;
}

FrameSetup MotionPlanner::next(const MovingView& view, RenderSettings& settings, Clock::time_point now) {
  if (view.settings_generation != settings_generation_) {  // new settings or lights: passes start over
    settings_generation_ = view.settings_generation;
    pass_ = 0;
    still_passes_ = 0;
  }
  if (view.camera_generation != camera_generation_ && camera_generation_ != ~uint64_t(0)) camera_moved_ = now;
  const bool moving = camera_moved_ != Clock::time_point{} && now - camera_moved_ < kStillAfter;
  camera_generation_ = view.camera_generation;
  if (moving) still_passes_ = 0;
  budget_.pin(view.preview >= 0 ? std::optional<int>(view.preview) : std::nullopt);
  const int level = budget_.pick(moving);
  const PreviewLevel& preview = budget_.levels()[size_t(level)];

  RenderOptions render = options_.render;
  render.settings = view.settings;  // pt's samples per pass depend on the method
  const bool animated = scene_.animation && scene_.animation->animated();
  // An animation's frame k stands at its own time, as headless frame k: nothing accumulates.
  FrameSetup f = plan_frame(render, options_.camera_path, scene_, animated ? animation_frame_++ : pass_++, true);
  if (!animated && view.settings.method != MethodKind::PathTracer) f.sample_begin = uint32_t(still_passes_);
  ++still_passes_;
  f.pose.light_offset = options_.render.light_offset + view.light_offset;
  f.frame_id = next_id_++;
  if (!view.follow_camera) f.camera = view.camera;  // else where the animation puts it at the frame's time
  f.width /= preview.divisor;
  f.height /= preview.divisor;
  // Surfaces for every moving frame and preview; at a still view, until a
  // full-size frame with them has come (its pixels' surfaces do not change
  // from pass to pass: a pixel's centre ray, the same camera).
  const std::pair<uint64_t, uint64_t> here{view.camera_generation, view.settings_generation};
  f.want_surfaces = options_.reproject && !animated && surfaces_for_ != here;
  settings = preview_settings(view.settings, preview);
  planned_[f.frame_id] = {view.camera_generation, view.settings_generation, level, moving, f.want_surfaces};
  return f;
}

PlannedFrame MotionPlanner::completed(uint64_t frame_id, double seconds) {
  auto it = planned_.find(frame_id);
  if (it == planned_.end()) return {};
  const PlannedFrame p = it->second;
  planned_.erase(it);
  // Cancelled frames never come: forget those planned before this one.
  planned_.erase(planned_.begin(), planned_.lower_bound(frame_id));
  budget_.measured(p.level, seconds);
  if (p.surfaces && budget_.levels()[size_t(p.level)].divisor == 1)
    surfaces_for_ = {p.camera_generation, p.settings_generation};
  return p;
}

std::vector<MovedFrame> MotionPlanner::turn(MasterSession& session, const MovingView& view, bool room, int pump_ms) {
  if (view.camera_generation != seen_camera_ || view.settings_generation != seen_settings_) {
    for (uint64_t id : stale(view, session.open_frames())) session.cancel_frame(id);
    seen_camera_ = view.camera_generation;
    seen_settings_ = view.settings_generation;
  }
  if (room && session.can_add_frame()) {
    RenderSettings settings;
    const FrameSetup f = next(view, settings);
    session.add_frame(f, settings);
  }
  std::vector<MovedFrame> out;
  for (CompletedFrame& f : session.pump(pump_ms)) {
    const PlannedFrame p = completed(f.setup.frame_id, f.record.seconds);
    const PreviewLevel level = budget_.levels()[size_t(p.level)];
    out.push_back({std::move(f), p, level, level_weight(view.settings, level)});
  }
  return out;
}

}  // namespace igi
