#include "methods/glossy_gather.h"

#include "material/bsdf.h"
#include "sampling/hash.h"
#include "sampling/sobol.h"

namespace igi {
namespace {

void gather_at(const Accel& accel, const GSample& g, uint32_t owner, uint32_t seed, const RenderSettings& settings,
               GlossyHits& out, RayCounts& rays) {
  SurfacePoint white = g.surface;
  white.albedo = glm::vec3(1.0f);
  const float inv_rays = 1.0f / float(settings.glossy_rays);
  for (int j = 0; j < settings.glossy_rays; ++j) {
    const glm::vec2 u = sample_2d(uint32_t(j), 0, seed);
    auto bs = bsdf_sample(white, g.wo, u, 0.0f);
    if (!bs || bs->weight == glm::vec3(0.0f)) continue;
    const Ray ray{offset_origin(g.surface, bs->wi), bs->wi};
    ++rays.secondary;
    Hit hit;
    GSample y;
    if (accel.intersect(ray, hit))
      follow_specular_chain(accel, ray, hit, hash(seed, uint32_t(j)), depth_limit(settings.specular_depth), y, rays);
    else
      y.emitted = accel.scene().sky(ray.direction);  // the sky in the lobe (none: nothing is kept)
    if (!y.valid() && y.emitted == glm::vec3(0.0f)) continue;
    out.points.push_back(y);
    out.owner.push_back(owner);
    out.weight.push_back(bs->weight * inv_rays);
  }
}

}  // namespace

void trace_glossy_gather(const Accel& accel, const GBuffer& gbuffer, const RenderSettings& settings,
                         uint32_t frame_seed, GlossyHits& out, RayCounts& rays) {
  out.clear();
  const Region& r = gbuffer.region;
  // Layer l (sub-sample l mod S, glass branch l div S): layers of branch 0 keep the sub-sample's numbers.
  for (int l = 0; l < gbuffer.layer_count(); ++l)
    for (int j = 0; j < r.height; ++j)
      for (int i = 0; i < r.width; ++i) {
        const size_t pixel = size_t(j) * r.width + i;
        const GSample& g = gbuffer.at(l, pixel);
        if (!g.valid() || !is_gathered_glossy(*g.surface.material, settings.glossy_threshold)) continue;
        const uint32_t seed = hash(hash(uint32_t(r.x0 + i), uint32_t(r.y0 + j), frame_seed), uint32_t(l), 0x676c6f73u);
        gather_at(accel, g, uint32_t(size_t(l) * r.pixels() + pixel), seed, settings, out, rays);
      }
}

}  // namespace igi
