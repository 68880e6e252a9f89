#pragma once
// Glossy receivers sharper than the glossy threshold (RenderSettings).
//
// A VPL seen in a sharp GGX lobe shows as a highlight of its own: D(h) peaks
// at 1 / (pi alpha^2), 39 at alpha 0.09, so K VPLs give K specks and never
// the blurred reflection of the walls. Such surfaces therefore take no light
// from VPLs. Their lobe is gathered instead: per sub-sample, `rays` GGX
// visible-normal samples wi with weight f cos / pdf (albedo 1: demodulated,
// like the VPL sums), each followed through mirrors and glass to a surface y
// whose radiance towards the sample is shaded by the caller:
//   L(y) = Le(y) + the clamped VPL estimate of every group of the sample's
//          set (igi; of every set, ir) + exact punctual lights,
// so the reflection shows the light sources, the lit walls and their
// indirect light. Its error is the one-bounce final gather's: smooth where
// the reflected radiance is smooth. A hit takes its whole set, not the
// sub-sample's group alone (VplMethod::shade_vpls says why). Light paths do
// leave VPLs on these surfaces (vpl_generator.cpp): they light the rest of
// the scene through the lobe widened to the threshold (VplShading::vpl_bsdf),
// never the sharp surface itself, so nothing is counted twice. The gathered
// value joins the sample's demodulated irradiance before the discontinuity
// buffer (see VplMethod::render_tile for why).
//
// The light sources themselves (emissive triangles and the sky) are sampled
// too, as the path tracer does: each gather ray comes with one light sample
// (LightSet::sample; punctual lights are skipped, they are exact already),
// and both are weighted by the power heuristic. A ray that finds an emitter
// or the sky directly keeps that share of its emission; through a mirror or
// glass first, all of it (no light sample can follow that chain). Without
// the light samples a small light's reflection was a scatter of single
// gather rays that hit it: one pass of `glossy` showed it as bright squares
// (one ray's hit spread over the discontinuity buffer's 3 x 3).
//
// Gather rays are not camera rays: the back of a single-sided face is opaque
// to them, as to a path tracer's glossy bounce. Random numbers: Sobol sample
// index j = ray (dimensions 0-1 the direction, 2-3 the light's point, 4 the
// light's choice), scrambled by the sub-sample's hash of (global x, y, k,
// frame seed), so a pixel gathers alike in any tile, thread or process.
#include <vector>

#include <glm/glm.hpp>

#include "core/gbuffer.h"
#include "core/settings.h"
#include "lighting/lights.h"

namespace igi {

struct GlossyHits {
  std::vector<GSample> points;   // where each ray's chain ended (maybe invalid: escaped)
  std::vector<uint32_t> owner;   // the layer sample it was traced from: layer * region pixels + pixel
  std::vector<glm::vec3> weight; // demodulated f cos / pdf, divided by the ray count
  // The light samples' demodulated, weighted estimates, by layer sample (same numbering as owner).
  std::vector<uint32_t> light_owner;
  std::vector<glm::vec3> light_value;

  void clear() {
    points.clear(); owner.clear(); weight.clear();
    light_owner.clear(); light_value.clear();
  }
};

// Traces the gather rays and light samples of every gathered-glossy
// sub-sample of `gbuffer`.
void trace_glossy_gather(const Accel& accel, const LightSet& lights, const GBuffer& gbuffer,
                         const RenderSettings& settings, uint32_t frame_seed, GlossyHits& out, RayCounts& rays);

}  // namespace igi
