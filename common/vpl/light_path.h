#pragma once
// A light path, walked alike by the VPL generator and the photon tracer
// (photons/photon_paths.h): its start at a light, then its bounces, each
// BSDF-sampled with Russian roulette by albedo.
//
// Random numbers: a path is SampleStream(path index, seed) over its
// dimensions; its start takes the first kStartDims, bounce d the next
// kDimsPerBounce from kStartDims + d kDimsPerBounce (SampleStream gives
// every draw a pair of dimensions).
#include <cstdint>

#include <glm/glm.hpp>

#include "core/settings.h"
#include "lighting/lights.h"
#include "sampling/sobol.h"
#include "scene/accel.h"
#include "scene/surface.h"
#include "vpl/start_guide.h"

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
// lights and the environment, inside a spot's cone), from the stream's next
// kStartDims dimensions. With a `guide` that holds the chosen light, the
// point and direction are drawn by its density instead, and the path's power
// divided by it (vpl/start_guide.h).
LightPathStart start_light_path(const LightSet& lights, const Scene& scene, SampleStream& u,
                                const Distribution1D* selection = nullptr, const StartGuide* guide = nullptr);
// The start from light `light`, chosen with probability `select`, at numbers `u`.
LightPathStart start_light_path_at(const LightSet& lights, const Scene& scene, uint32_t light, float select,
                                   StartNumbers u);

// How a bounce draws its lobe and roulette numbers from its dimensions after
// the direction's pair: VPL paths as two single draws, photon paths as one
// pair (a single draw costs a whole Sobol pair; the photons were written
// later). Each layout is kept, so that neither set of paths changes.
enum class BounceDraws { TwoSingles, OnePair };

// What a walk shows its caller at each surface the path reaches.
struct LightPathVertex {
  const Hit& hit;
  const SurfacePoint& sp;
  glm::vec3 wo;    // towards where the light came from
  glm::vec3 flux;  // power the path carries to this surface (W, per path)
  int depth;       // surfaces before this one
};

// The path's next ray from `sp`, BSDF-sampled, with `flux` scaled by the
// sample's weight and Russian roulette; nothing where the path ends.
std::optional<Ray> bounce_light_path(const SurfacePoint& sp, glm::vec3 wo, glm::vec3& flux, SampleStream u,
                                     BounceDraws draws);

// Walks path `path` of stream `seed` from `start` through at most
// depth_limit(light_depth) surfaces, calling visit(const LightPathVertex&) at
// each; visit returns false to end the path there. Returns the rays traced.
template <class Visit>
int walk_light_path(const Accel& accel, const Scene& scene, const LightPathStart& start, int light_depth,
                    uint32_t path, uint32_t seed, BounceDraws draws, Visit&& visit) {
  Ray ray = start.ray;
  glm::vec3 flux = start.flux;
  const int max_depth = depth_limit(light_depth);
  int rays = 0;
  for (int depth = 0; depth < max_depth; ++depth) {
    Hit hit;
    ++rays;
    if (!accel.intersect(ray, hit)) return rays;
    const SurfacePoint sp = surface_at(scene, hit, ray.direction);
    const glm::vec3 wo = -ray.direction;
    if (!visit(LightPathVertex{hit, sp, wo, flux, depth})) return rays;
    const SampleStream u(path, seed, kStartDims + kDimsPerBounce * uint32_t(depth));
    const std::optional<Ray> next = bounce_light_path(sp, wo, flux, u, draws);
    if (!next) return rays;
    ray = *next;
  }
  return rays;
}

}  // namespace igi
