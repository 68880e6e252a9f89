#include "methods/vpl_draws.h"

#include <algorithm>

#include "lightcuts/gather_points.h"
#include "lightcuts/light_leaves.h"
#include "lightcuts/light_sampler.h"

namespace igi {

VplDraws::VplDraws(const Scene& scene, const VplSets& vpls, uint32_t frame_seed)
    : tree_(lightcuts::build_light_tree(lightcuts::make_light_leaves(scene, vpls, false), scene.bounds().diagonal(),
                                        frame_seed)),
      inv_sets_(1.0f / float(std::max(1, vpls.set_count()))) {
  // A VPL on the point itself: its importance stops growing 1e-4 diagonals away.
  const float d = 1e-4f * scene.bounds().diagonal();
  min_distance2_ = d * d;
}

glm::vec3 VplDraws::shade(const GSample& g, int draws, uint32_t seed, std::span<const Vpl> vpls,
                          const VplShading& shading, const Accel& accel, RayCounts& rays) const {
  if (tree_.nodes.empty()) return glm::vec3(0.0f);
  const lightcuts::GatherPoint point = lightcuts::gather_point(g);
  const lightcuts::LightSampler sampler(tree_, shading.clamp_bound, min_distance2_);
  glm::dvec3 sum(0.0);
  for (int j = 0; j < draws; ++j) {
    const std::optional<lightcuts::LightDraw> d = sampler.draw(point, lightcuts::LightSampler::draw_u(uint32_t(j), seed));
    if (!d) break;  // nothing can light g: no draw can
    const Vpl& v = vpls[tree_.leaves[tree_.nodes[d->node].leaf].source];
    ShadowQuery q;
    const glm::vec3 c = shading.contribution(g, v, q);
    if (!(c.x + c.y + c.z > 0.0f)) continue;
    ++rays.shadow;
    if (!accel.occluded(Ray{q.origin, q.direction, 0.0f, q.tfar, kOpaqueRayMask})) sum += glm::dvec3(c) / d->pdf;
  }
  return glm::vec3(sum * double(inv_sets_ / float(draws)));
}

}  // namespace igi
