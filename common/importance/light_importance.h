#pragma once
// Light importance for the current view (after Wald, Benthin and Slusallek,
// "Interactive Global Illumination in Complex and Highly Occluded
// Environments", EGSR 2003).
//
// In a building of many rooms most lights light rooms the camera never sees,
// yet power selection starts as many VPL light paths there as anywhere. A
// crude path-tracing pass from the camera estimates how much each light adds
// to the image, and the VPL light paths then start at light l with
//   p_l = (1 - F) c_l / sum c + F P_l / sum P
// (c: the estimate, P: emitted power, F: --importance-floor), each carrying
// its flux divided by p_l (LightSet::sample_emission), so every set stays an
// unbiased estimate of the whole light. The floor keeps every light with
// power at p_l >= F P_l / sum P: none is starved, a light the estimate missed
// costs variance, never bias, and the method stays consistent (F = 0 drops
// that guarantee). When the estimate has fewer samples n (shadow rays that
// found their light) than there are lights L, most c_l are 0 or a single
// sample by chance, so F rises to L / (L + n): a mesh of 2,300 emissive
// triangles and 256 estimate paths is sampled mostly by power.
//
// The estimate: N camera paths (settings.importance_paths) through film
// points of one low-discrepancy sequence (importance/camera_points.h), up to
// kEstimateBounces surfaces each; at every non-specular vertex one shadow ray
// to one point of one light, chosen by its unoccluded irradiance there (so a
// vertex in a room of a 100-room building asks its own and its neighbours'
// lights, not the building's), crediting that light with the luminance it
// adds to the camera. Area lights and the sky are credited at every vertex
// (their direct light reaches the image through VPLs on the light, or
// directional ones from the sky); point, spot and directional lights from
// the second vertex on only, since their direct light is evaluated exactly
// and their VPLs carry only what bounces.
//
// Determinism and stability: the estimate is a pure function of scene,
// settings, camera, image size and frame seed, computed by every worker for
// itself: no light probabilities travel on the wire, and master + workers
// equal one process bit for bit. While the camera and seed stay, the
// probabilities stay (no VPL moves). When the camera moves, the same
// sequence points move with it, so the estimate changes smoothly rather than
// being redrawn; a light path keeps its light unless a probability boundary
// crosses its selection number, and the floor bounds how far any
// probability can fall. (README, "Light importance", has the flicker
// figures and why the master-summed alternative was not taken.)
#include <cstdint>
#include <vector>

#include "core/frame.h"
#include "core/method.h"
#include "sampling/distribution.h"

namespace igi::importance {

inline constexpr int kEstimateBounces = 5;  // surfaces along each estimate path

struct LightSelection {
  std::vector<float> contribution;  // c_l: estimated luminance each LightSet entry adds to the mean pixel
  Distribution1D distribution;      // p_l, as above
  uint64_t hash = 0;                // of the probabilities (joins the VPL sets' hash)
};

// `rays` counts what the estimate traced.
LightSelection estimate_light_importance(const SceneContext& context, const RenderSettings& settings,
                                         const FrameSetup& frame, RayCounts& rays);

// p_l from contributions c_l and powers P_l with floor share F (exposed for tests).
std::vector<float> selection_weights(const std::vector<float>& contribution, const std::vector<float>& power,
                                     float floor);

}  // namespace igi::importance
