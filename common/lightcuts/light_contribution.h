#pragma once
// The exact, unoccluded light of one leaf at one gather point, and the
// shadow ray that decides its visibility: the one VPL shading rule
// (core/vpl_contribution.h, VplShading) that ir and igi shade with, on the
// leaf's VPL or the scene light it stands for, so lightcuts and ir over the
// same VPLs estimate the same sum term for term. Two differences of form: the
// rule shades with albedo 1 and lightcuts multiplies the gather point's
// albedo into each term (ir after filtering), and a VPL's leaf carries 1/S of
// its light, S the number of VPL sets (lightcuts/light_leaves.h).
#include <vector>

#include <glm/glm.hpp>

#include "core/vpl.h"
#include "lightcuts/gather_points.h"
#include "lightcuts/light_leaves.h"
#include "scene/accel.h"
#include "scene/scene.h"

namespace igi::lightcuts {

struct LightingContext {
  const Scene& scene;
  const VplSets& vpls;                   // a VPL leaf's source
  const std::vector<Vpl>& scene_lights;  // exact_lights(scene): a scene light's leaf's source
  float clamp_bound;                     // on G = |cos_x| cos_y / r^2; infinity when off
  float glossy_threshold = 0.0f;         // VPL lobes widened to it (VplShading::min_emitter_alpha)
};

// Returns the contribution (zero when there is none, then `shadow` is unset).
glm::vec3 light_contribution(const LightingContext& context, const GatherPoint& g, const LightLeaf& leaf,
                             Ray& shadow);

}  // namespace igi::lightcuts
