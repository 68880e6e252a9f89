#include "photons/caustic_map.h"

#include <algorithm>
#include <cmath>
#include <thread>

#include "core/vpl_contribution.h"
#include "photons/photon_paths.h"
#include "sampling/content_hash.h"
#include "sampling/warp.h"

namespace igi {

uint64_t hash_photons(const std::vector<Photon>& photons) {
  static_assert(sizeof(Photon) == 13 * 4, "four vec3 and a uint32: no padding for the hash to read");
  return content_hash(photons.data(), photons.size() * sizeof(Photon));
}

void split_by_density(const std::vector<Photon>& photons, float radius, glm::vec3 origin, int min_neighbours,
                      std::vector<Photon>& dense, std::vector<Photon>& sparse) {
  const PhotonGrid all(photons, radius, origin);
  dense.clear();
  sparse.clear();
  for (const Photon& p : photons) {
    int count = 0;
    all.for_each_within(p.position, [&](const Photon&, float) { ++count; });
    (count >= min_neighbours ? dense : sparse).push_back(p);
  }
}

CausticMap::CausticMap(const SceneContext& context, const RenderSettings& settings)
    : context_(context), settings_(settings),
      radius_(settings.caustic_radius * context.scene.bounds().diagonal()),
      paths_(uint32_t(settings.caustic_photons)) {}

float ppm_radius_scale(uint32_t pass) {
  // The product in double, factor by factor: plain IEEE arithmetic, so every
  // peer gets the same radius (lgamma's last bits depend on the libm).
  double area = 1.0;
  for (uint32_t j = 1; j <= pass; ++j) area *= (j + CausticMap::kPpmAlpha) / (j + 1.0);
  return float(std::sqrt(area));
}

float sparse_radius_scale(uint32_t pass) {
  return std::max(CausticMap::kBouncedRadiusScale,
                  CausticMap::kSparseRadiusScale / std::sqrt(std::sqrt(float(pass) + 1.0f)));
}

void CausticMap::build(uint32_t frame_seed, int threads, uint32_t pass) {
  if (threads <= 0) threads = int(std::max(1u, std::thread::hardware_concurrency()));
  rays_ = RayCounts{};
  const std::vector<Photon> photons = trace_photon_paths(context_, settings_, frame_seed, paths_, threads, rays_);
  hash_ = hash_photons(photons);
  std::vector<Photon> focused, bounced;
  for (const Photon& p : photons) (p.bounced ? bounced : focused).push_back(p);
  const glm::vec3 origin = context_.scene.bounds().lower;
  const float r = ppm_radius_scale(pass) * radius_;
  // Sparse photons of both sets share one wide grid: one lookup, not two.
  std::vector<Photon> dense_focused, dense_bounced, sparse, sparse_bounced;
  split_by_density(focused, r, origin, kDenseNeighbours, dense_focused, sparse);
  split_by_density(bounced, kBouncedRadiusScale * r, origin, kDenseNeighbours, dense_bounced, sparse_bounced);
  sparse.insert(sparse.end(), sparse_bounced.begin(), sparse_bounced.end());
  focused_ = PhotonGrid(dense_focused, r, origin);
  bounced_ = PhotonGrid(dense_bounced, kBouncedRadiusScale * r, origin);
  sparse_ = PhotonGrid(sparse, sparse_radius_scale(pass) * r, origin);
}

glm::vec3 CausticMap::radiance(const GSample& g) const {
  const SurfacePoint& sp = g.surface;
  const glm::vec3 n = sp.geometric_normal_facing(g.wo);
  // A Lambertian receiver's demodulated BSDF is 1 / pi for every photon that
  // passes the normal test (it arrived on the viewer's side): summed once.
  const bool lambert = sp.material->type == MaterialType::Diffuse;
  // The lobes VPL light reaches: a sharp GGX lobe gathers its own (with caustics where its rays land).
  const Lobes lobes = vpl_lobes(sp, settings_.glossy_threshold);
  auto estimate = [&](const PhotonGrid& grid) {
    const float inv_r2 = 1.0f / (grid.radius() * grid.radius());
    glm::vec3 sum(0.0f);
    grid.for_each_within(sp.position, [&](const Photon& p, float d2) {
      if (glm::dot(p.normal, n) < kNormalCos) return;
      const float t = 1.0f - d2 * inv_r2;
      sum += (lambert ? p.flux : demodulated_bsdf(sp, g.wo, p.incident, lobes) * p.flux) * (t * t);
    });
    return sum * (3.0f * kInvPi * inv_r2);
  };
  const glm::vec3 sum = estimate(focused_) + estimate(bounced_) + estimate(sparse_);
  return lambert ? sum * kInvPi : sum;
}

}  // namespace igi
