#pragma once
// The exact, unoccluded light of one leaf at one gather point, and the
// shadow ray that decides its visibility. The formula is that of ir's
// core/vpl_contribution.h term for term (same clamp, same |cos_x|, same
// offsets and shadow-ray length), so lightcuts and ir over the same VPLs
// estimate the same sum, with one difference: here the BSDF at the gather
// point is the full one, albedo included (ir multiplies the albedo in after
// filtering; for Lambertian and GGX surfaces the two agree).
#include <glm/glm.hpp>

#include "core/vpl.h"
#include "lightcuts/gather_points.h"
#include "lightcuts/light_leaves.h"
#include "scene/accel.h"
#include "scene/scene.h"

namespace igi::lightcuts {

struct LightingContext {
  const Scene& scene;
  const std::vector<Vpl>& vpls;  // Glossy leaves read their VPL (incident direction, material)
  float clamp_bound;             // on G = |cos_x| cos_y / r^2; infinity when off
};

// Returns the contribution (zero when there is none, then `shadow` is unset).
glm::vec3 light_contribution(const LightingContext& context, const GatherPoint& g, const LightLeaf& leaf,
                             Ray& shadow);

}  // namespace igi::lightcuts
