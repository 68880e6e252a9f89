#include "vpl/light_path.h"

#include <cmath>

#include "material/bsdf.h"
#include "sampling/warp.h"

namespace igi {

LightPathStart start_light_path(const LightSet& lights, const Scene& scene, SampleStream& u,
                                const Distribution1D* selection, const StartGuide* guide) {
  const float u_select = u.next_1d();
  StartNumbers numbers;
  numbers.point = u.next_2d();
  numbers.direction = u.next_2d();
  const Distribution1D& choice = selection ? *selection : lights.power_distribution();
  const uint32_t light = choice.sample(u_select);
  float density = 1.0f;
  if (guide) numbers = guide->warp(light, numbers, density);
  LightPathStart start = start_light_path_at(lights, scene, light, choice.probability(light), numbers);
  if (density != 1.0f) {
    start.flux /= density;
    start.power /= density;
    start.irradiance /= density;
  }
  return start;
}

LightPathStart start_light_path_at(const LightSet& lights, const Scene& scene, uint32_t light, float select,
                                   StartNumbers numbers) {
  const glm::vec2 u_point = numbers.point, u_dir = numbers.direction;
  const EmissionSample e = lights.sample_emission_at(light, select, u_point);
  LightPathStart start;
  start.light = e.light;
  switch (e.kind) {
    case LightKind::Area: {
      start.on_area_light = true;
      start.position = e.position;
      start.normal = e.normal;
      start.power = e.power;
      Onb frame(e.normal);
      glm::vec3 d = frame.to_world(cosine_hemisphere(u_dir));
      start.ray = Ray{e.position + 1e-5f * lights.scene_radius() * e.normal, d};
      start.flux = e.power * kPi;  // Le A cos / (pdf = cos / pi)
      break;
    }
    case LightKind::Directional:
      start.ray = Ray{e.position, e.normal};
      start.flux = e.power;
      break;
    case LightKind::Environment: {
      // Into the scene against a direction towards the sky (uniform, or by
      // the map's luminance), from the disc across it.
      const LightSet::SkySample sky = lights.sample_sky(u_dir);
      const glm::vec3 d = -sky.direction;
      start.ray = Ray{lights.disc_origin(d, u_point), d};
      start.from_environment = true;
      start.irradiance = sky.pdf > 0.0f ? e.power * sky.radiance / sky.pdf : glm::vec3(0.0f);
      start.flux = start.irradiance * (kPi * lights.scene_radius() * lights.scene_radius());
      break;
    }
    default: {
      const PunctualLight& pl = scene.lights[lights.lights()[e.light].index];
      glm::vec3 d;
      if (e.kind == LightKind::Spot) {
        float cos_max = std::cos(pl.outer_cone);
        d = Onb(glm::normalize(pl.direction)).to_world(uniform_cone(u_dir, cos_max));
        float pdf = 1.0f / (2.0f * kPi * (1.0f - cos_max));
        start.flux = e.power * (spot_attenuation(pl, d) / pdf);
      } else {
        d = uniform_sphere(u_dir);
        start.flux = e.power * (4.0f * kPi);
      }
      start.ray = Ray{e.position, d};
    }
  }
  return start;
}

std::optional<Ray> bounce_light_path(const SurfacePoint& sp, glm::vec3 wo, glm::vec3& flux, SampleStream u,
                                     BounceDraws draws) {
  const glm::vec2 u_dir = u.next_2d();
  glm::vec2 u_lobe_roulette;
  if (draws == BounceDraws::OnePair) {
    u_lobe_roulette = u.next_2d();
  } else {
    u_lobe_roulette.x = u.next_1d();
    u_lobe_roulette.y = u.next_1d();
  }
  const auto bs = bsdf_sample(sp, wo, u_dir, u_lobe_roulette.x);
  if (!bs) return std::nullopt;
  // Russian roulette by albedo: survivors carry the lost share.
  const float q = std::min(1.0f, max_component(bs->weight));
  if (!(u_lobe_roulette.y < q)) return std::nullopt;
  flux *= bs->weight / q;
  return Ray{offset_origin(sp, bs->wi), bs->wi};
}

}  // namespace igi
