#include "importance/view_vpls.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include "core/direct_lights.h"
#include "core/vpl_contribution.h"
#include "importance/bidirectional.h"
#include "importance/camera_points.h"
#include "importance/light_importance.h"
#include "importance/view_guide.h"
#include "sampling/content_hash.h"
#include "vpl/vpl_generator.h"

namespace igi::importance {

float light_path_reach(const SceneContext& context, const RenderSettings& settings, const FrameSetup& frame,
                       const LightPathOptions& light_paths, RayCounts& rays) {
  constexpr uint32_t kProbeSeed = 0x62646972u;  // "bdir": the same probe for every pass of a view
  RenderSettings one_set = settings;
  one_set.interleave = 1;
  one_set.paths_per_set = kProbePaths;
  one_set.aa_samples = 1;
  LightPathOptions options;
  options.selection = light_paths.selection;
  options.guide = light_paths.guide;
  std::vector<Vpl> lights = generate_vpls(context, one_set, kProbeSeed, options).vpls;
  for (const Vpl& v : exact_lights(context.scene)) lights.push_back(v);
  const VplShading shading{context.scene, INFINITY};
  const CameraFrontEnd camera(frame);
  uint32_t surfaces = 0;
  double seen = 0.0;  // sum over the points of the share of `lights` each sees
  for (uint32_t i = 0; i < kViewProbes; ++i) {
    const GSample g = trace_camera_point(context.accel, camera, i, kProbeSeed, depth_limit(settings.specular_depth), rays);
    if (!g.valid()) continue;
    ++surfaces;
    uint32_t visible = 0;
    for (const Vpl& v : lights) {
      ShadowQuery q;
      if (shading.contribution(g, v, q) == glm::vec3(0.0f)) continue;
      ++rays.shadow;
      if (!context.accel.occluded(Ray{q.origin, q.direction, 0.0f, q.tfar})) ++visible;
    }
    seen += double(visible) / double(std::max<size_t>(1, lights.size()));
  }
  return surfaces > 0 ? float(seen / surfaces) : 1.0f;
}

RenderSettings choose_bidir(const SceneContext& context, const RenderSettings& settings, const FrameSetup& frame,
                            const LightPathOptions& light_paths, RayCounts& rays) {
  RenderSettings chosen = settings;
  if (settings.bidir_vpls != kBidirAuto) return chosen;
  chosen.bidir_vpls = 0;
  const bool vpl_method = settings.method == MethodKind::InstantRadiosity || settings.method == MethodKind::Igi;
  if (!vpl_method || settings.paths_per_set > kMaxAutoBidirPaths) return chosen;
  if (light_path_reach(context, settings, frame, light_paths, rays) >= kBidirReach) return chosen;
  chosen.paths_per_set = 2 * settings.paths_per_set;
  chosen.bidir_vpls = std::max(chosen.paths_per_set, settings.aa_samples);
  return chosen;
}

VplSets generate_view_vpls(const SceneContext& context, const RenderSettings& settings, const FrameSetup& frame,
                           RayCounts& rays) {
  std::optional<LightSelection> selection;
  LightPathOptions options;
  // With one light there is nothing to choose: its probability is 1 either way.
  if (settings.importance_paths > 0 && context.lights.lights().size() > 1) {
    selection = estimate_light_importance(context, settings, frame, rays);
    options.selection = &selection->distribution;
  }
  StartGuide guide;
  if (settings.light_guide) {
    guide = build_view_guide(context, settings, frame, rays);
    if (!guide.empty()) options.guide = &guide;
  }
  const RenderSettings chosen = choose_bidir(context, settings, frame, options, rays);
  VplSets sets = chosen.bidir_vpls > 0 ? generate_bidirectional(context, chosen, frame, options, rays)
                                       : generate_vpls(context, chosen, frame.seed, options);
  if (selection) sets.hash = combine_content_hashes(sets.hash, selection->hash);
  if (options.guide) sets.hash = combine_content_hashes(sets.hash, guide.hash());
  return sets;
}

}  // namespace igi::importance
