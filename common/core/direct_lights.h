#pragma once
// Point, spot and directional lights, evaluated exactly: one shadow ray per
// light and shading point, with the receiver's full BSDF (a point light's
// highlight on a glossy floor is real, not a VPL artefact). VPL sets carry
// none of them (core/vpl.h), and their direct light is added after the
// discontinuity buffer, so hard shadows stay hard.
//
// Each light becomes a Vpl of its kind with flux = its intensity (W/sr) or
// irradiance (W/m^2), so VplShading::contribution() and the shadow packets
// (methods/shadow_batch.h) evaluate it like any other VPL. A scene with many
// punctual lights pays a shadow ray per light per point.
#include <vector>

#include "core/vpl.h"
#include "scene/scene.h"

namespace igi {

inline std::vector<Vpl> exact_lights(const Scene& scene) {
  std::vector<Vpl> out;
  for (uint32_t i = 0; i < scene.lights.size(); ++i) {
    const PunctualLight& l = scene.lights[i];
    Vpl v;
    v.position = l.position;
    v.normal = glm::normalize(l.direction);
    v.flux = l.intensity;
    v.light = i;
    v.kind = l.type == LightType::Point ? VplKind::Point
             : l.type == LightType::Spot ? VplKind::Spot
                                         : VplKind::Directional;
    out.push_back(v);
  }
  return out;
}

}  // namespace igi
