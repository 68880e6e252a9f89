#pragma once
// The VPL clamp: one bound on the geometry term G = cos_x cos_y / r^2 for
// every VPL method (ir, igi, lightcuts, bidirectional IR, compensation).
//
// Scale-free: the clamp distance is a fraction C (--clamp) of the scene's
// mean chord L, the mean free path between its surfaces (scene/accel.h:
// Accel::mean_chord). In a box L is about the box; in a building of rooms it
// is about a room, however many rooms there are, so a building keeps its
// light where a bound relative to the scene's diagonal darkened it.
//
// Consistent: progressive pass k (0-based) clamps at distance
// d_k = C L / (k + 1)^(1/4), that is G <= sqrt(k + 1) / (C L)^2. The bias of
// the average of K passes (about the mean of d_k) falls like K^(-1/4) while
// the variance the relaxing bound lets in (about the mean of 1/d_k^2 over K)
// falls like K^(-1/2): the balance of the two, so the accumulated image
// converges to the unclamped estimator, as progressive photon mapping
// shrinks its radius pass by pass. Pass 0 is the clamp one frame shows.
#include <cstdint>

#include "core/settings.h"  // kMaxClamp
#include "sampling/warp.h"

namespace igi {

// Infinity when clamp <= 0 (off).
float clamp_bound(float clamp, float mean_chord, uint32_t pass);

// The clamp on a glossy (GGX) lobe at either end of a VPL's light. Bounding
// G alone lets a lobe multiply a close VPL's light again: at alpha 0.3 a
// receiver's peak is about ten times a white Lambertian's 1 / pi, so a VPL a
// hand's width from a crease lit a rough metal floor as a hot splotch; a VPL
// on a sharp metal surface (its lobe widened to the glossy threshold) lit the
// wall beside it as a spot. So the lobe's BSDF with albedo 1 (f_white, its
// largest channel) times G is bounded by b / pi, what a white Lambertian
// takes or gives at most under the bound on G; returns the factor (at most
// 1) that scales the contribution. A Lambertian (f_white = 1 / pi) is never
// scaled: for it this is the bound on G itself.
inline float glossy_lobe_clamp(float f_white, float g_term, float bound) {
  const float limit = bound * kInvPi;
  const float fg = f_white * g_term;
  return fg > limit ? limit / fg : 1.0f;
}

}  // namespace igi
