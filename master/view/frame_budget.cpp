#include "view/frame_budget.h"

#include <algorithm>

namespace igi {
namespace {

// The share of a full frame's shading a level does.
double pixels(const PreviewLevel& level) {
  const double d = double(level.divisor) * level.light;
  return 1.0 / (d * d);
}

}  // namespace

RenderSettings preview_settings(RenderSettings settings, const PreviewLevel& level) {
  if (level.cheap) {
    // One sub-sample with the light paths one of the full frame's sub-samples has: 1/S of its shadow rays.
    settings.paths_per_set = std::max(1, settings.paths_per_set / std::max(1, settings.aa_samples));
    settings.aa_samples = 1;
    settings.compensation_samples = 0;
    settings.caustics = false;  // 20,000 photon paths a frame: 40 % of a Sponza preview's time at 1/5
  }
  settings.light_divisor = level.light;
  return settings;
}

double level_weight(const RenderSettings& full, const PreviewLevel& level) {
  const bool subsampled = full.method != MethodKind::PathTracer && level.cheap;
  return pixels(level) * (subsampled ? 1.0 / std::max(1, full.aa_samples) : 1.0);
}

std::string level_name(const PreviewLevel& level) {
  if (!level.cheap && level.divisor == 1) return "full";
  if (level.divisor == 1 && level.light > 1) return "preview light 1/" + std::to_string(level.light);
  return "preview 1/" + std::to_string(level.divisor);
}

FrameBudget::FrameBudget(int width, int height, double budget_ms, bool sharp) : budget_ms_(budget_ms), sharp_(sharp) {
  levels_.push_back({1, false});
  const int long_side = std::max(width, height);
  if (long_side >= kMinLongSide) {  // (a smaller image has the full frame alone)
    levels_.push_back({1, true});
    if (sharp)
      for (int l : kLightDivisors)
        if (long_side / l >= 8) levels_.push_back({1, true, l});
  }
  for (int d = 2; long_side / d >= kMinLongSide; ++d)
    if (width % d == 0 && height % d == 0) levels_.push_back({d, true});
  cost_.assign(levels_.size(), 0.0);
}

void FrameBudget::pin(std::optional<int> level) {
  if (level && (*level < 0 || *level >= int(levels_.size()))) level.reset();
  pinned_ = level;
}

double FrameBudget::predicted(int level) const {
  if (cost_[size_t(level)] > 0.0) return cost_[size_t(level)];
  // The nearest level measured, scaled by pixels (a cheap level is taken to cost what a full one does a pixel).
  for (int step = 1; step < int(levels_.size()); ++step)
    for (int other : {level - step, level + step})
      if (other >= 0 && other < int(levels_.size()) && cost_[size_t(other)] > 0.0)
        return cost_[size_t(other)] * pixels(levels_[size_t(level)]) / pixels(levels_[size_t(other)]);
  return 0.0;
}

int FrameBudget::refine(int from) {
  // The finest level at full resolution finer than `from` that is predicted to fit this step's budget ...
  const double budget = budget_ms_ * 1e-3 * double(1 << std::min(refine_step_, 16));
  for (int l = 0; l < from; ++l)
    if (levels_[size_t(l)].divisor == 1 && predicted(l) > 0.0 && predicted(l) <= budget) return l;
  // ... else, from fewer pixels, the cheapest level at full resolution; from there the full frame.
  if (levels_[size_t(from)].divisor > 1)
    for (int l = from - 1; l > 0; --l)
      if (levels_[size_t(l)].divisor == 1) return l;
  return 0;
}

int FrameBudget::pick(bool moving) {
  if (pinned_) return *pinned_;
  if (!moving && refine_ > 0) {  // the move ended: each frame finer than the one before, up to the full frame
    refine_ = refine(refine_);
    ++refine_step_;
    return refine_;
  }
  if (!moving || budget_ms_ <= 0.0 || levels_.size() == 1) return 0;
  if (sharp_) {  // where refining starts when the move ends
    refine_ = pick_moving();
    refine_step_ = 0;
    return refine_;
  }
  return pick_moving();
}

int FrameBudget::pick_moving() {
  const double budget = budget_ms_ * 1e-3;
  const int coarsest = int(levels_.size()) - 1;
  if (moving_ == 0 && sharp_) {  // the first move: the cheapest sharp preview, and from there by measurement
    moving_ = 1;
    while (moving_ < coarsest && levels_[size_t(moving_ + 1)].divisor == 1) ++moving_;
    return moving_;
  }
  if (moving_ == 0) {  // the first move: the finest preview the full frames' cost predicts to fit, else the coarsest
    moving_ = coarsest;
    for (int l = 1; l < coarsest; ++l)
      if (predicted(l) > 0.0 && predicted(l) <= budget) {
        moving_ = l;
        break;
      }
    return moving_;
  }
  const double cost = cost_[size_t(moving_)];
  if (cost > 2.0 * budget && moving_ < coarsest) {
    // Far over: straight to the first coarser level whose frame, scaled by its pixels, would fit (camera rays
    // at every pixel are what a heavy scene's sharp previews pay: Sponza at light 1/8 cost 4 times its 1/5).
    const double d = levels_[size_t(moving_)].divisor;
    while (moving_ < coarsest && cost * (d * d) / double(levels_[size_t(moving_)].divisor * levels_[size_t(moving_)].divisor) > budget)
      ++moving_;
  } else if (cost > budget && moving_ < coarsest) ++moving_;
  else if (cost > 0.0 && cost <= kStepUp * budget && moving_ > 1 && cost_[size_t(moving_ - 1)] <= budget)
    --moving_;  // room to spare, and the finer level fits or was never tried
  return moving_;
}

void FrameBudget::measured(int level, double seconds) {
  double& c = cost_.at(size_t(level));
  c = c > 0.0 ? 0.5 * (c + seconds) : seconds;
}

}  // namespace igi
