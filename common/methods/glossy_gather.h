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
//   L(y) = Le(y) + the same clamped VPL estimate the sample's own group uses
//          + exact punctual lights,
// so the reflection shows the light sources, the lit walls and their
// indirect light. Its error is the one-bounce final gather's: smooth where
// the reflected radiance is smooth. Light paths likewise pass through these
// surfaces without leaving VPLs (vpl_generator.cpp), so nothing is counted
// twice. The gathered value joins the sample's demodulated irradiance before
// the discontinuity buffer (see VplMethod::render_tile for why).
//
// Gather rays are not camera rays: the back of a single-sided face is opaque
// to them, as to a path tracer's glossy bounce. Random numbers: Sobol sample
// index j = ray, scrambled by the sub-sample's hash of (global x, y, k, frame
// seed), so a pixel gathers alike in any tile, thread or process.
#include <vector>

#include <glm/glm.hpp>

#include "methods/gbuffer.h"
#include "methods/settings.h"

namespace igi {

struct GlossyHits {
  std::vector<GSample> points;   // where each ray's chain ended (maybe invalid: escaped)
  std::vector<uint32_t> owner;   // the layer sample it was traced from: layer * region pixels + pixel
  std::vector<glm::vec3> weight; // demodulated f cos / pdf, divided by the ray count

  void clear() { points.clear(); owner.clear(); weight.clear(); }
};

// Traces the gather rays of every gathered-glossy sub-sample of `gbuffer`.
void trace_glossy_gather(const Accel& accel, const GBuffer& gbuffer, const RenderSettings& settings,
                         uint32_t frame_seed, GlossyHits& out, RayCounts& rays);

}  // namespace igi
