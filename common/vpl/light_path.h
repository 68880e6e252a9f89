#pragma once
// The start of a light path, shared by the VPL generator and the photon
// tracer (photons/photon_paths.h) so both carry light alike.
//
// Random numbers: a path is SampleStream(path index, seed) over its
// dimensions; its start takes the first kStartDims, bounce d the next
// kDimsPerBounce from kStartDims + d kDimsPerBounce (SampleStream gives
// every draw a pair of dimensions).
#include <cstdint>

#include <glm/glm.hpp>

#include "lighting/lights.h"
#include "sampling/sobol.h"
#include "scene/accel.h"

namespace igi {

inline constexpr uint32_t kStartDims = 6;
inline constexpr uint32_t kDimsPerBounce = 8;

struct LightPathStart {
  Ray ray;               // the first ray leaving the light
  glm::vec3 flux{0.0f};  // power carried along it, per path (W)
  uint32_t light = 0;    // the LightSet entry it leaves
  // Area lights: the point on the light, its normal and power / pdf of the
  // point (what an Area VPL carries). Point, spot and directional lights
  // leave no such vertex.
  bool on_area_light = false;
  glm::vec3 position{0.0f}, normal{0.0f}, power{0.0f};
  // The environment: the path's direction (ray.direction) as a directional
  // light of this irradiance (W/m^2 per path, L 4 pi / the choice's
  // probability): what the Directional VPL it leaves carries.
  bool from_environment = false;
  glm::vec3 irradiance{0.0f};
};

// Picks a light in proportion to its power (or by `selection`, a
// distribution over the LightSet's entries: light importance), a point on it
// and a direction (cosine-distributed for area lights, uniform for point
// lights and the environment, inside a spot's cone), from the stream's next kStartDims dimensions.
LightPathStart start_light_path(const LightSet& lights, const Scene& scene, SampleStream& u,
                                const Distribution1D* selection = nullptr);

}  // namespace igi
