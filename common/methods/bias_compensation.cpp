#include "methods/bias_compensation.h"

#include <algorithm>
#include <cmath>

#include "core/subpixel.h"
#include "core/vpl_contribution.h"
#include "methods/shadow_batch.h"
#include "sampling/hash.h"
#include "sampling/sobol.h"
#include "sampling/warp.h"
#include "scene/surface.h"
#include "sampling/pixel_samples.h"

namespace igi {

// Per-thread buffers, kept between tiles.
struct BiasCompensation::Scratch {
  std::vector<Hop> first, second;  // levels 1 and 2
  std::vector<uint32_t> index;     // level 1: the hop's sample index
  std::vector<uint32_t> seed;      // and its sequence's seed
  std::vector<glm::vec3> radiance_first;
  std::vector<const Hop*> all;
  std::vector<glm::vec3> radiance_all;
};

// Every layer sample's hops first (level 1, then level 2 from each hit),
// then the light at all the hits in packets, then the sums. The arithmetic is
// the one-hop-at-a-time rule's, in its order: a pixel's compensation is a
// function of the pixel alone, and the same bits as when each hop was shaded
// on its own (2026-12-07).
void BiasCompensation::add(const GBuffer& gbuffer, uint32_t frame_seed, std::vector<glm::vec3>& irradiance,
                           RayCounts& rays) const {
  if (!enabled()) return;
  thread_local Scratch scratch;
  auto& [first, second, index, seeds, radiance_first, all, radiance_all] = scratch;
  first.clear();
  second.clear();
  index.clear();
  seeds.clear();
  const Region& region = gbuffer.region;
  // The pixel's n rays are one stratified sequence shared out over its S
  // sub-samples (at least one each): sub-sample k takes indices [k r, (k+1) r);
  // each glass branch b = l / S of the pixel has a sequence of its own.
  const int per_sample = std::max(1, samples_ / vpls_.groups);
  for (int l = 0; l < gbuffer.layer_count(); ++l) {
    const int k = gbuffer.subsample_of_layer(l);
    for (int j = 0; j < region.height; ++j)
      for (int i = 0; i < region.width; ++i) {
        const size_t sample = size_t(l) * region.pixels() + size_t(j) * region.width + i;
        const GSample& g = gbuffer.layers[sample];
        if (!g.valid()) continue;
        const int x = region.x0 + i, y = region.y0 + j;
        const uint32_t seed = PixelSamples{frame_seed}.sequence(x, y, uint32_t(l / vpls_.groups));
        const int set = interleaved_ ? vpls_.set_of_pixel(x, y) : -1;
        const int group = group_of_subsample(x, y, k, vpls_.groups);
        for (int n = 0; n < per_sample; ++n) {
          Hop h;
          const uint32_t at = uint32_t(k * per_sample + n);
          if (!hop(g.surface, g.wo, at, seed, 1, h, rays)) continue;
          h.owner = uint32_t(sample);
          h.set = set;
          h.group = group;
          first.push_back(h);
          index.push_back(at);
          seeds.push_back(seed);
        }
      }
  }
  // Level 2: the hit's own cut share, one hop further (kLevels).
  static_assert(kLevels == 2, "two levels of hops");
  for (size_t h = 0; h < first.size(); ++h) {
    Hop next;
    if (!hop(first[h].y.surface, first[h].y.wo, index[h], seeds[h], 2, next, rays)) continue;
    next.owner = uint32_t(h);
    next.set = first[h].set;
    next.group = first[h].group;
    second.push_back(next);
  }
  all.clear();
  for (const Hop& h : first) all.push_back(&h);
  for (const Hop& h : second) all.push_back(&h);
  radiance_towards(all, radiance_all, rays);
  // Le(y) too: the clamp cut the same share of the area VPLs' direct light (see the header).
  radiance_first.resize(first.size());
  for (size_t h = 0; h < first.size(); ++h) radiance_first[h] = first[h].y.surface.emitted() + radiance_all[h];
  for (size_t h = 0; h < second.size(); ++h) {
    const Hop& s = second[h];
    const glm::vec3 light = s.y.surface.emitted() + radiance_all[first.size() + h];
    radiance_first[s.owner] += first[s.owner].y.surface.albedo * (s.weight * light * s.cut);
  }
  // Each sample's hops are consecutive, in index order.
  for (size_t h = 0; h < first.size();) {
    const uint32_t owner = first[h].owner;
    glm::vec3 sum(0.0f);
    for (; h < first.size() && first[h].owner == owner; ++h) sum += first[h].weight * radiance_first[h] * first[h].cut;
    irradiance[owner] += sum / float(per_sample);
  }
}

// One short hop from sp, seen from wo, with the sample index's dimension
// `level` - 1.
bool BiasCompensation::hop(const SurfacePoint& sp, glm::vec3 wo, uint32_t index, uint32_t seed, int level, Hop& out,
                           RayCounts& rays) const {
  // Only what VPLs shade was clamped: not mirrors, glass or the sharp GGX lobes that gather theirs.
  const bool lambert = sp.material->type == MaterialType::Diffuse;
  if (!lambert && (sp.material->type != MaterialType::Conductor ||
                   !receives_vpls(*sp.material, shading_.min_emitter_alpha)))
    return false;
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
    if (!bs) return false;
    wi = bs->wi;
    weight = bs->weight;
    f_white = max_component(VplShading::demodulated_bsdf(sp, wo, wi));
  }
  const float cos_x = glm::dot(wi, n);
  if (cos_x <= 0.0f || glm::dot(wi, ng) <= 0.0f || !(f_white > 0.0f)) return false;  // no light from below
  // The clamp scales f G down to b / pi (core/clamp.h; for a Lambertian,
  // G to b). Past this distance f G <= f cos_x / d^2 <= b / pi: it cut
  // nothing there.
  const float reach = lambert ? std::sqrt(cos_x / bound_) : std::sqrt(kPi * f_white * cos_x / bound_);
  const Ray ray{offset_origin(sp, wi), wi, 0.0f, reach};
  Hit hit;
  ++rays.secondary;
  if (!accel_.intersect(ray, hit)) return false;
  GSample& y = out.y;
  y = GSample{};
  y.surface = surface_at(accel_.scene(), hit, wi);
  // A surface that takes no VPL light (a mirror, glass, a sharp glossy
  // lobe: methods/glossy_gather.h) holds no VPL the clamp cut. Shading one
  // here with VPLs would put them in its sharp lobe: on `glossy` that drew
  // a row of specks along every crease between a wall and the floor.
  if (!receives_vpls(*y.surface.material, shading_.min_emitter_alpha)) return false;
  y.wo = -wi;
  y.has_surface = true;  // no camera path leads here: depth stays unset
  const float d2 = glm::dot(y.surface.position - sp.position, y.surface.position - sp.position);
  const float cos_y = std::abs(glm::dot(wi, y.surface.shading_normal));
  const float geometry_term = cos_x * cos_y / d2;
  // The share the clamp cut: 1 - (b / pi) / (f G), for a Lambertian (G - b) / G.
  const float cut = lambert ? (geometry_term - bound_) / geometry_term
                            : 1.0f - bound_ * kInvPi / (f_white * geometry_term);
  if (!(cut > 0.0f)) return false;
  out.weight = weight;
  out.cut = cut;
  return true;
}

// L(y -> x), x along y.wo, at every hop: the clamped VPL estimate of the
// hop's own group of its set (igi) or of all sets (ir), scaled like the
// sample's VPL sum, plus the exact lights, times the albedo at y
// (contributions are demodulated). Emission is the caller's: see the header.
// Hops of one (set, group) share their VPLs: 16 hops to one VPL make a
// packet, each lane summing its VPLs in their order as one hop alone would.
void BiasCompensation::radiance_towards(std::span<const Hop* const> hops, std::vector<glm::vec3>& radiance,
                                        RayCounts& rays) const {
  radiance.assign(hops.size(), glm::vec3(0.0f));
  const int sets = interleaved_ ? vpls_.set_count() : 1;
  thread_local std::vector<std::vector<uint32_t>> by_group;
  by_group.resize(size_t(sets) * vpls_.groups);
  for (auto& list : by_group) list.clear();
  for (uint32_t h = 0; h < hops.size(); ++h)
    by_group[size_t(std::max(hops[h]->set, 0)) * vpls_.groups + hops[h]->group].push_back(h);
  thread_local PixelBatch batch;
  // Each set alone estimates the full light (ir averages all S), and each group 1 / G of it.
  const float scale = float(vpls_.groups) / (interleaved_ ? 1.0f : float(vpls_.set_count()));
  for (int s = 0; s < sets; ++s)
    for (int group = 0; group < vpls_.groups; ++group) {
      const std::vector<uint32_t>& list = by_group[size_t(s) * vpls_.groups + group];
      if (list.empty()) continue;
      batch.clear();
      for (uint32_t h : list) batch.add(h, hops[h]->y);
      batch.pad();
      for (int v = interleaved_ ? s : 0; v < (interleaved_ ? s + 1 : vpls_.set_count()); ++v) {
        const auto begin = vpls_.vpls.begin() + vpls_.group_first(v, group);
        const auto end = vpls_.vpls.begin() + vpls_.group_end(v, group);
        shade_batch(batch, std::span<const Vpl>(begin, end), shading_, accel_, rays, log_);
      }
      for (size_t i = 0; i < batch.count; ++i)
        radiance[batch.index[i]] = glm::vec3(batch.sum_r[i], batch.sum_g[i], batch.sum_b[i]) * scale;
    }
  for (size_t h = 0; h < hops.size(); ++h) {
    glm::vec3& sum = radiance[h];
    for (const Vpl& v : exact_) {
      ShadowQuery q;
      const glm::vec3 c = shading_.contribution(hops[h]->y, v, q);
      if (c == glm::vec3(0.0f)) continue;
      ++rays.shadow;
      if (!accel_.occluded(Ray{q.origin, q.direction, 0.0f, q.tfar})) sum += c;
    }
    sum = hops[h]->y.surface.albedo * sum;
  }
}

}  // namespace igi
