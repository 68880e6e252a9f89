#pragma once
// --frame-budget-ms: what a frame renders at while the view changes, so that
// a moving camera still gets a frame every budget or so, and how frames step
// up to the full frame after it stops.
//
// Levels, finest first: the full frame (level 0), then previews with cheaper
// settings (one sub-sample a pixel, shaded by the light paths one sub-sample
// of a full frame has, no bias compensation and no caustic photons): first at every pixel, then
// sharp previews (--previews sharp, the default): camera rays, textures and
// edges at every pixel, light on a lattice of one pixel in L x L upsampled
// along the surfaces (--light-divisor L, methods/light_upsample.h), L = 2,
// 3, 4, 6, 8; then, for when even those cost more than the budget, the same
// camera over fewer pixels (the image over a whole divisor of both sides,
// the long side never under kMinLongSide pixels, as Cycles' viewport),
// whose blocks cover textures and silhouettes alike (light at L = 2 of such
// a frame cost as much and showed more error: Sponza, FLIP 0.145 moving
// against 0.112). The first moving frame takes the cheapest sharp
// preview (coarse previews only: the finest preview that the full frames'
// measured cost, scaled by pixels, predicts to fit the budget). Then the level steps coarser
// when its frames take more than the budget, and finer when they take at
// most kStepUp of it and the finer level was never measured over the
// budget: measuring is the only sure prediction (a frame's fixed costs do
// not scale with pixels), and a level once over the budget is not tried
// again, so the level does not flicker between two.
//
// After the stop (sharp previews): frames refine, each finer than the one
// before: frame k after the stop takes the finest level at full resolution
// predicted to cost at most 2^k budgets; where none is, the cheapest level
// at full resolution after a preview of fewer pixels, else the full frame.
// So a full frame that takes seconds comes after a few frames that each
// show more (at most about log2(its cost / the budget)), never straight
// after the blocks of a coarse preview.
//
// Pure bookkeeping: the caller measures and says so (tests feed a cost model).
#include <optional>
#include <string>
#include <vector>

#include "core/settings.h"

namespace igi {

struct PreviewLevel {
  int divisor = 1;     // the frame is width / divisor x height / divisor
  bool cheap = false;  // preview settings (preview_settings())
  int light = 1;       // light on a lattice of one pixel in light x light (--light-divisor)
  bool operator==(const PreviewLevel&) const = default;
};

// The settings a preview level renders with.
RenderSettings preview_settings(RenderSettings settings, const PreviewLevel& level);
// What a frame of the level counts for in an accumulated image, against a
// full frame's 1: its share of a full frame's samples (pixels over
// divisor^2, sub-samples one of aa_samples), so previews seen while moving
// hardly weigh once full frames come.
double level_weight(const RenderSettings& full, const PreviewLevel& level);
// "full", "preview 1/2", "light 1/3", ...: what the read-out names.
std::string level_name(const PreviewLevel& level);

class FrameBudget {
 public:
  static constexpr int kMinLongSide = 128;
  static constexpr double kStepUp = 0.7;

  static constexpr int kLightDivisors[] = {2, 3, 4, 6, 8};

  // budget_ms 0: no budget, every frame full. `sharp`: sharp previews and
  // the refinement after the stop (--previews sharp); else previews over fewer pixels only.
  FrameBudget(int width, int height, double budget_ms, bool sharp = true);
  const std::vector<PreviewLevel>& levels() const { return levels_; }
  double budget_ms() const { return budget_ms_; }
  void set_budget_ms(double ms) { budget_ms_ = ms; }
  // The panel's pin: this level index for every frame, moving or not (nullopt: the budget decides).
  void pin(std::optional<int> level);
  std::optional<int> pinned() const { return pinned_; }

  // The level of the next frame: full while still (or without a budget),
  // but for the refinement after a move.
  int pick(bool moving);
  // A frame of level index `level` took `seconds`, first job out to last result in.
  void measured(int level, double seconds);
  // The cost the budget expects of a level (seconds; 0 when nothing is measured yet).
  double predicted(int level) const;

 private:
  std::vector<PreviewLevel> levels_;
  std::vector<double> cost_;  // measured seconds, smoothed; 0: not yet
  double budget_ms_;
  std::optional<int> pinned_;
  int moving_ = 0;  // the level moving frames take now (0: none chosen yet)
  bool sharp_;
  int refine_ = 0;        // after a move: the level of the last refining frame (0: none under way)
  int refine_step_ = 0;   // refining frames so far
  int refine(int from);   // the next refining level after `from`
  int pick_moving();      // the level of a moving frame
};

}  // namespace igi
