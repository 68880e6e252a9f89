#include "lightcuts/light_contribution.h"

#include <algorithm>

#include "core/vpl_contribution.h"

namespace igi::lightcuts {

glm::vec3 light_contribution(const LightingContext& context, const GatherPoint& g, const LightLeaf& leaf,
                             Ray& shadow) {
  const Vpl& light = leaf.scene_light ? context.scene_lights[leaf.source] : context.vpls.vpls[leaf.source];
  const VplShading shading{context.scene, context.clamp_bound, context.glossy_threshold};
  ShadowQuery q{};
  const glm::vec3 light_in = shading.contribution(g.surface, g.wo, light, q);
  if (light_in == glm::vec3(0.0f)) return glm::vec3(0.0f);
  shadow = Ray{q.origin, q.direction, 0.0f, q.tfar};
  const float share = leaf.scene_light ? 1.0f : 1.0f / float(std::max(1, context.vpls.set_count()));
  return modulation(g.surface, g.wo) * light_in * share;
}

}  // namespace igi::lightcuts
