#include "methods/bias_compensation.h"

#include <algorithm>
#include <cmath>

#include "core/subpixel.h"
#include "core/vpl_contribution.h"
#include "sampling/hash.h"
#include "sampling/sobol.h"
#include "sampling/warp.h"
#include "scene/surface.h"

namespace igi {

void BiasCompensation::add(const GBuffer& gbuffer, uint32_t frame_seed, std::vector<glm::vec3>& irradiance,
                           RayCounts& rays) const {
  if (!enabled()) return;
  const Region& region = gbuffer.region;
  for (int l = 0; l < gbuffer.layer_count(); ++l)
    for (int j = 0; j < region.height; ++j)
      for (int i = 0; i < region.width; ++i) {
        const size_t index = size_t(l) * region.pixels() + size_t(j) * region.width + i;
        if (gbuffer.layers[index].valid())
          irradiance[index] += at_sample(gbuffer.layers[index], region.x0 + i, region.y0 + j, l,
                                         gbuffer.subsample_of_layer(l), frame_seed, rays);
      }
}

// Demodulated compensation at layer l (sub-sample k) of pixel (x, y) (global
// coordinates). Layers of glass branch 0 (l = k) keep the sub-sample's numbers.
glm::vec3 BiasCompensation::at_sample(const GSample& g, int x, int y, int l, int k, uint32_t frame_seed,
                                      RayCounts& rays) const {
  // The pixel's n rays are one stratified sequence shared out over its S
  // sub-samples (at least one each): sub-sample k takes indices [k r, (k+1) r);
  // each glass branch b = l / S of the pixel has a sequence of its own.
  const int per_sample = std::max(1, samples_ / vpls_.groups);
  const uint32_t seed = hash(hash(uint32_t(x), uint32_t(y), frame_seed), uint32_t(l / vpls_.groups));
  const int set = interleaved_ ? vpls_.set_of_pixel(x, y) : -1;
  const int group = group_of_subsample(x, y, k, vpls_.groups);
  glm::vec3 sum(0.0f);
  for (int i = 0; i < per_sample; ++i)
    sum += hop(g.surface, g.wo, uint32_t(k * per_sample + i), seed, set, group, 1, rays);
  return sum / float(per_sample);
}

// One short hop from sp, seen from wo, with the sample index's dimension
// `level` - 1: the share of the light at its hit that the clamp cut, and at
// level 1 the hit's own cut share one hop further (kLevels).
glm::vec3 BiasCompensation::hop(const SurfacePoint& sp, glm::vec3 wo, uint32_t index, uint32_t seed, int set,
                                int group, int level, RayCounts& rays) const {
  // Only what VPLs shade was clamped: not mirrors, glass or the sharp GGX lobes that gather theirs.
  const bool lambert = sp.material->type == MaterialType::Diffuse;
  if (!lambert && (sp.material->type != MaterialType::Conductor ||
                   !receives_vpls(*sp.material, shading_.min_emitter_alpha)))
    return glm::vec3(0.0f);
  // The hemisphere on the viewer's side, as VPL shading uses it.
  const glm::vec3 n = sp.shading_normal_facing(wo), ng = sp.geometric_normal_facing(wo);
  const glm::vec2 u = sample_2d(index, uint32_t(level - 1), seed);
  // Lambert: wi with density cos_x / pi, so f cos / pdf = 1 and the lobe
  // value f = 1 / pi. GGX: wi drawn from the lobe, weight f cos / pdf.
  glm::vec3 wi, weight(1.0f);
  float f_white = kInvPi;
  if (lambert) {
    wi = Onb(n).to_world(cosine_hemisphere(u));
  } else {
    SurfacePoint white = sp;  // demodulated: the lobe with albedo 1
    white.albedo = glm::vec3(1.0f);
    const auto bs = bsdf_sample(white, wo, u, 0.0f);
    if (!bs) return glm::vec3(0.0f);
    wi = bs->wi;
    weight = bs->weight;
    f_white = max_component(VplShading::demodulated_bsdf(sp, wo, wi));
  }
  const float cos_x = glm::dot(wi, n);
  if (cos_x <= 0.0f || glm::dot(wi, ng) <= 0.0f || !(f_white > 0.0f)) return glm::vec3(0.0f);  // no light from below
  // The clamp scales f G down to b / pi (core/clamp.h; for a Lambertian,
  // G to b). Past this distance f G <= f cos_x / d^2 <= b / pi: it cut
  // nothing there.
  const float reach = lambert ? std::sqrt(cos_x / bound_) : std::sqrt(kPi * f_white * cos_x / bound_);
  const Ray ray{offset_origin(sp, wi), wi, 0.0f, reach};
  Hit hit;
  ++rays.secondary;
  if (!accel_.intersect(ray, hit)) return glm::vec3(0.0f);
  GSample hit_sample;
  hit_sample.surface = surface_at(accel_.scene(), hit, wi);
  // A surface that takes no VPL light (a mirror, glass, a sharp glossy
  // lobe: methods/glossy_gather.h) holds no VPL the clamp cut. Shading one
  // here with VPLs would put them in its sharp lobe: on `glossy` that drew
  // a row of specks along every crease between a wall and the floor.
  if (!receives_vpls(*hit_sample.surface.material, shading_.min_emitter_alpha)) return glm::vec3(0.0f);
  hit_sample.wo = -wi;
  hit_sample.has_surface = true;  // no camera path leads here: depth stays unset
  const float d2 = glm::dot(hit_sample.surface.position - sp.position, hit_sample.surface.position - sp.position);
  const float cos_y = std::abs(glm::dot(wi, hit_sample.surface.shading_normal));
  const float geometry_term = cos_x * cos_y / d2;
  // The share the clamp cut: 1 - (b / pi) / (f G), for a Lambertian (G - b) / G.
  const float cut = lambert ? (geometry_term - bound_) / geometry_term
                            : 1.0f - bound_ * kInvPi / (f_white * geometry_term);
  if (!(cut > 0.0f)) return glm::vec3(0.0f);
  // Le(y) too: the clamp cut the same share of the area VPLs' direct light (see the header).
  glm::vec3 radiance = hit_sample.surface.emitted() + radiance_towards(hit_sample, set, group, rays);
  if (level < kLevels)
    radiance += hit_sample.surface.albedo * hop(hit_sample.surface, hit_sample.wo, index, seed, set, group, level + 1, rays);
  return weight * radiance * cut;
}

// L(y -> x), x along y.wo: the clamped VPL estimate of the sample's own
// group of its set (igi) or of all sets (ir), scaled like the sample's VPL
// sum, plus the exact lights, times the albedo at y (contributions are
// demodulated). Emission is the caller's: see the header.
glm::vec3 BiasCompensation::radiance_towards(const GSample& y, int set, int group, RayCounts& rays) const {
  auto unoccluded = [&](const Vpl& v) {
    ShadowQuery q;
    const glm::vec3 c = shading_.contribution(y, v, q);
    if (c == glm::vec3(0.0f)) return c;
    ++rays.shadow;
    return accel_.occluded(Ray{q.origin, q.direction, 0.0f, q.tfar}) ? glm::vec3(0.0f) : c;
  };
  glm::vec3 sum(0.0f);
  for (int s = set >= 0 ? set : 0; s < (set >= 0 ? set + 1 : vpls_.set_count()); ++s)
    for (uint32_t v = vpls_.group_first(s, group); v < vpls_.group_end(s, group); ++v) sum += unoccluded(vpls_.vpls[v]);
  // Each set alone estimates the full light (ir averages all S), and each
  // group 1 / G of it.
  sum *= float(vpls_.groups) / (set >= 0 ? 1.0f : float(vpls_.set_count()));
  for (const Vpl& v : exact_) sum += unoccluded(v);
  return y.surface.albedo * sum;
}

}  // namespace igi
