#include "methods/glossy_gather.h"

#include <cmath>

#include "material/bsdf.h"
#include "sampling/hash.h"
#include "sampling/sobol.h"
#include "sampling/warp.h"
#include "scene/surface.h"
#include "sampling/pixel_samples.h"

namespace igi {
namespace {

// One light sample of the area lights and the sky at g, weighted against the
// BSDF's samples; nothing for punctual lights (exact already).
glm::vec3 light_sample(const Accel& accel, const LightSet& lights, const GSample& g, const SurfacePoint& white,
                       float u_select, glm::vec2 u, RayCounts& rays) {
  const LightSample ls = lights.sample(white.position, u_select, u);
  if (ls.delta || !(ls.pdf > 0.0f)) return glm::vec3(0.0f);
  const glm::vec3 f = bsdf_eval(white, g.wo, ls.direction);
  if (f == glm::vec3(0.0f)) return glm::vec3(0.0f);
  ++rays.shadow;
  if (accel.occluded(shadow_ray(white, ls.direction, ls.position, ls.distance))) return glm::vec3(0.0f);
  const float cos_i = std::abs(glm::dot(ls.direction, white.shading_normal));
  const float w = power_heuristic(ls.pdf, bsdf_pdf(white, g.wo, ls.direction));
  return f * ls.radiance * (cos_i * w / ls.pdf);
}

void gather_at(const Accel& accel, const LightSet& lights, const GSample& g, uint32_t owner, uint32_t seed,
               const RenderSettings& settings, GlossyHits& out, RayCounts& rays) {
  SurfacePoint white = g.surface;
  white.albedo = glm::vec3(1.0f);
  const float inv_rays = 1.0f / float(settings.glossy_rays);
  glm::vec3 sampled(0.0f);
  for (int j = 0; j < settings.glossy_rays; ++j) {
    if (!lights.empty()) {
      const glm::vec2 u_light = sample_2d(uint32_t(j), 2, seed);
      sampled += light_sample(accel, lights, g, white, sample_1d(uint32_t(j), 4, seed), u_light, rays);
    }
    const glm::vec2 u = sample_2d(uint32_t(j), 0, seed);
    auto bs = bsdf_sample(white, g.wo, u, 0.0f);
    if (!bs || bs->weight == glm::vec3(0.0f)) continue;
    const Ray ray{offset_origin(g.surface, bs->wi), bs->wi};
    ++rays.secondary;
    Hit hit;
    GSample y;
    if (accel.intersect(ray, hit)) {
      const SurfacePoint first = surface_at(accel.scene(), hit, ray.direction);
      follow_specular_chain(accel, ray, hit, hash(seed, uint32_t(j)), depth_limit(settings.specular_depth), y, rays);
      // An emitter found directly: the light samples could have found it too.
      if (!first.material->is_specular() && first.emitted() != glm::vec3(0.0f))
        y.emitted *= power_heuristic(bs->pdf, lights.pdf_area(hit.triangle, white.position, first.position));
    } else {
      // The sky in the lobe (none: nothing is kept).
      y.emitted = accel.scene().sky(ray.direction) *
                  power_heuristic(bs->pdf, lights.pdf_environment(ray.direction));
    }
    if (!y.valid() && y.emitted == glm::vec3(0.0f)) continue;
    out.points.push_back(y);
    out.owner.push_back(owner);
    out.weight.push_back(bs->weight * inv_rays);
  }
  if (sampled != glm::vec3(0.0f)) {
    out.light_owner.push_back(owner);
    out.light_value.push_back(sampled * inv_rays);
  }
}

}  // namespace

void trace_glossy_gather(const Accel& accel, const LightSet& lights, const GBuffer& gbuffer,
                         const RenderSettings& settings, uint32_t frame_seed, GlossyHits& out, RayCounts& rays) {
  out.clear();
  const Region& r = gbuffer.region;
  // Layer l (sub-sample l mod S, glass branch l div S): layers of branch 0 keep the sub-sample's numbers.
  for (int l = 0; l < gbuffer.layer_count(); ++l)
    for (int j = 0; j < r.height; ++j)
      for (int i = 0; i < r.width; ++i) {
        const size_t pixel = size_t(j) * r.width + i;
        const GSample& g = gbuffer.at(l, pixel);
        if (!g.valid() || !is_gathered_glossy(*g.surface.material, settings.glossy_threshold)) continue;
        const uint32_t seed = PixelSamples{frame_seed}.sequence(r.x0 + i, r.y0 + j, uint32_t(l), 0x676c6f73u /* "glos" */);
        gather_at(accel, lights, g, uint32_t(size_t(l) * r.pixels() + pixel), seed, settings, out, rays);
      }
}

}  // namespace igi
