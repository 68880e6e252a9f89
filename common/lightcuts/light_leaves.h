#pragma once
// The lights a light tree clusters: every Surface, Area and Directional VPL of a frame,
// all N x N sets together, plus every point, spot and directional light of
// the scene, exact, each once.
//
// Scale. ir sums all S sets and divides by S, since each set alone estimates
// the whole light. Lightcuts estimates that same sum, so a VPL leaf carries
// its flux divided by S; punctual lights carry their own intensity (W/sr;
// directional W/m^2). Directional VPLs (the environment's, core/vpl.h) are
// leaves with their irradiance divided by S; VPL kinds Point and Spot, if a
// VplSets holds them, are skipped: those lights come from the scene.
//
// A leaf's light at a gather point x, seen from wo, with wi the unit
// direction from x to the light, r its distance, G = min(|cos_x| cos_y / r^2, b)
// the clamped geometry term (lightcuts/light_contribution.h), f_x the BSDF at x:
//   Cosine       f_x I G                    Area VPL (I = flux/S), Lambertian surface VPL (I = albedo/pi flux/S)
//   Glossy       f_x f_y(incident, -wi) I G  surface VPL on a GGX conductor (I = flux/S)
//   Punctual     f_x I |cos_x| / r^2 spot(-wi)   point and spot lights, never clamped
//   Directional  f_x E |cos_x|                  from direction `position` (unit), at infinity
// `weight` is a scalar w with (light leaving the leaf per unit of its
// class's directional factor) <= w in every channel:
//   Cosine: max(I) (factor cos_y); Glossy: max(I F) D_max / (4 cos_incident)
//   (factor 1 on the hemisphere: f_y cos_y = F D G2 / (4 cos_incident), G2 <= 1);
//   Punctual, Directional: max(I) (factor spot(-wi) <= 1, or 1).
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "core/vpl.h"
#include "scene/scene.h"

namespace igi::lightcuts {

enum class LightClass : uint8_t { Cosine, Glossy, Punctual, Directional };
inline constexpr int kLightClasses = 4;

struct LightLeaf {
  glm::vec3 position{0.0f};   // Directional: unit direction towards the light
  glm::vec3 normal{0.0f};     // Cosine, Glossy: front normal; spot: axis; else 0
  glm::vec3 intensity{0.0f};  // I (or E), see above; already divided by S for VPLs
  float weight = 0.0f;        // w > 0, see above
  float spread = 0.0f;        // Glossy: pi/2; spot: outer cone; point: pi (emission around `normal`)
  uint32_t source = 0;        // VplSets::vpls index (every VPL leaf), Scene::lights index (the scene's lights)
  LightClass light_class = LightClass::Cosine;
  bool scene_light = false;   // one of the scene's lights (source: a Scene::lights index), not a VPL
};

// Leaves with zero weight (black VPLs, black lights) are left out: they add
// nothing. Without `scene_lights`, the VPLs' leaves alone (igi's VPL draws,
// which add the scene's lights exactly elsewhere).
std::vector<LightLeaf> make_light_leaves(const Scene& scene, const VplSets& vpls, bool scene_lights = true);

}  // namespace igi::lightcuts
