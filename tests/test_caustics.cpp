// Glass as the VPL methods see it (exact Fresnel, branches) and the caustic
// photon map: determinism, the grid's lookups, energy in a furnace, and the
// caustic against the path tracer.
#include <algorithm>
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "material/bsdf.h"
#include "methods/path_tracer.h"
#include "methods/vpl_method.h"
#include "photons/caustic_map.h"
#include "photons/photon_grid.h"
#include "photons/photon_paths.h"
#include "scene/builtin_scenes.h"
#include "scene/load_scene.h"
#include "scene/suite_scenes.h"
#include "support/image_compare.h"
#include "support/render_fixture.h"

namespace igi {
namespace {

using test::luminance;

// --- Glass: exact dielectric Fresnel on both sides.

SurfacePoint glass_point(const Material& glass) {
  SurfacePoint sp;
  sp.position = glm::vec3(0.0f);
  sp.geometric_normal = sp.shading_normal = {0.0f, 0.0f, 1.0f};
  sp.material = &glass;
  sp.albedo = glass.base_color;
  return sp;
}

Material clear_glass() {
  Material m;
  m.type = MaterialType::Glass;
  m.base_color = glm::vec3(1.0f);
  m.ior = 1.5f;
  return m;
}

TEST(Glass, FresnelAtNormalIncidenceIsTheTextbookFourPercentFromEitherSide) {
  EXPECT_NEAR(fresnel_dielectric(1.0f, 1.5f), 0.04f, 1e-6f);
  EXPECT_NEAR(fresnel_dielectric(-1.0f, 1.5f), 0.04f, 1e-6f);
  EXPECT_NEAR(fresnel_dielectric(1.0f, 1.0f), 0.0f, 1e-7f) << "index-matched: no reflection";
}

TEST(Glass, BranchesObeySnellReciprocityAndTotalInternalReflection) {
  const Material glass = clear_glass();
  const SurfacePoint sp = glass_point(glass);
  const float critical = std::asin(1.0f / 1.5f);
  for (float degrees : {0.0f, 20.0f, 40.0f, 41.5f, 42.0f, 60.0f, 85.0f})
    for (bool outside : {true, false}) {
      const float theta = glm::radians(degrees);
      const glm::vec3 wo(std::sin(theta), 0.0f, outside ? std::cos(theta) : -std::cos(theta));
      const DielectricBranches b = dielectric_branches(sp, wo);
      const float n_o = outside ? 1.0f : 1.5f, n_t = outside ? 1.5f : 1.0f;
      EXPECT_NEAR(glm::dot(b.reflected, glm::vec3(0, 0, 1)), wo.z, 1e-6f) << "mirror direction";
      if (!outside && theta > critical) {
        EXPECT_EQ(b.reflectance, 1.0f) << degrees << " degrees inside: total internal reflection";
        EXPECT_EQ(b.transmittance, glm::vec3(0.0f));
        continue;
      }
      ASSERT_LT(b.reflectance, 1.0f) << degrees;
      // Snell: n_o sin(theta_o) = n_t sin(theta_t), on the far side, in the plane of incidence.
      const float sin_t = std::sqrt(b.refracted.x * b.refracted.x + b.refracted.y * b.refracted.y);
      EXPECT_NEAR(n_o * std::sin(theta), n_t * sin_t, 1e-5f) << degrees;
      EXPECT_LT(b.refracted.z * wo.z, 0.0f) << "through the surface";
      EXPECT_NEAR(b.reflectance + b.transmittance.x, 1.0f, 1e-6f) << "clear glass loses nothing";
      // Reciprocity: light travelling back along the refracted ray meets the
      // same reflectance on the other side, and refracts out along wo.
      const DielectricBranches back = dielectric_branches(sp, b.refracted);
      EXPECT_NEAR(back.reflectance, b.reflectance, 2e-5f) << degrees;
      EXPECT_NEAR(glm::dot(back.refracted, wo), 1.0f, 1e-5f) << degrees;
    }
}

TEST(Glass, SamplingPicksReflectionWithTheFresnelProbability) {
  const Material glass = clear_glass();
  const SurfacePoint sp = glass_point(glass);
  const glm::vec3 wo = glm::normalize(glm::vec3(0.8f, 0.0f, 0.3f));
  const float f = dielectric_branches(sp, wo).reflectance;
  int reflected = 0;
  const int n = 10000;
  for (int i = 0; i < n; ++i) reflected += bsdf_sample(sp, wo, glm::vec2(0.5f), (i + 0.5f) / n)->wi.z > 0.0f;
  EXPECT_NEAR(double(reflected) / n, f, 1.0 / n);
}

// --- The photon grid: exactly the photons a brute-force scan finds.

TEST(PhotonGrid, FindsExactlyThePhotonsWithinTheRadius) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  for (size_t count : {size_t(0), size_t(1), size_t(7), size_t(3000)}) {
    std::vector<Photon> photons(count);
    for (Photon& p : photons) p.position = {u(rng), u(rng) * 0.1f, u(rng)};  // crowded: buckets collide
    for (float radius : {0.003f, 0.05f, 0.3f}) {
      const PhotonGrid grid(photons, radius, glm::vec3(0.0f));
      for (int q = 0; q < 200; ++q) {
        const glm::vec3 x(u(rng) * 1.2f - 0.1f, u(rng) * 0.12f - 0.01f, u(rng) * 1.2f - 0.1f);
        std::vector<glm::vec3> found, expected;
        grid.for_each_within(x, [&](const Photon& p, float d2) {
          found.push_back(p.position);
          EXPECT_FLOAT_EQ(d2, glm::dot(p.position - x, p.position - x));
        });
        for (const Photon& p : photons)
          if (glm::dot(p.position - x, p.position - x) < radius * radius) expected.push_back(p.position);
        auto order = [](glm::vec3 a, glm::vec3 b) { return std::tie(a.x, a.y, a.z) < std::tie(b.x, b.y, b.z); };
        std::sort(found.begin(), found.end(), order);
        std::sort(expected.begin(), expected.end(), order);
        ASSERT_EQ(found, expected) << count << " photons, radius " << radius;
      }
    }
  }
}

// --- The map: a pure function of scene, settings and seed.

const test::Prepared& glass_scene() {
  static test::Prepared p(make_glass_cornell());
  return p;
}

RenderSettings caustic_settings(int photons, MethodKind method = MethodKind::Igi) {
  RenderSettings s;
  s.method = method;
  s.caustics = true;
  s.caustic_photons = photons;
  return s;
}

TEST(CausticMap, IsTheSameOnAnyThreadCountAndChangesWithTheSeed) {
  const test::Prepared& p = glass_scene();
  const RenderSettings s = caustic_settings(5000);
  RayCounts rays;
  const std::vector<Photon> one = trace_photon_paths(p.context(), s, 3, 5000, 1, rays);
  const std::vector<Photon> four = trace_photon_paths(p.context(), s, 3, 5000, 4, rays);
  ASSERT_GT(one.size(), 100u) << "the sphere and the mirror catch some of the light";
  EXPECT_EQ(hash_photons(one), hash_photons(four));
  CausticMap a(p.context(), s), b(p.context(), s);
  a.build(3, 1);
  b.build(3, 3);
  EXPECT_EQ(a.hash(), b.hash());
  EXPECT_EQ(a.hash(), hash_photons(one));
  b.build(4, 3);
  EXPECT_NE(a.hash(), b.hash()) << "a new frame seed shoots fresh photons";
  // The method reports it: a worker with another map is caught like one with other VPLs.
  VplMethod with(p.context(), s);
  RenderSettings off = s;
  off.caustics = false;
  VplMethod without(p.context(), off);
  FrameSetup frame = p.frame(16, 16, 3);
  with.begin_frame(frame);
  without.begin_frame(frame);
  EXPECT_EQ(with.vpls().hash, without.vpls().hash);
  EXPECT_NE(with.frame_state_hash(), without.frame_state_hash());
}

TEST(CausticMap, PhotonsArriveThroughMirrorsAndGlassOnly) {
  // The Cornell box has no mirror or glass: no photon at all.
  const test::Prepared cornell(make_cornell_box());
  RayCounts rays;
  EXPECT_TRUE(trace_photon_paths(cornell.context(), caustic_settings(2000), 1, 2000, 2, rays).empty());
  // In the glass scene every photon lies on a diffuse surface.
  const test::Prepared& p = glass_scene();
  const std::vector<Photon> photons = trace_photon_paths(p.context(), caustic_settings(2000), 1, 2000, 2, rays);
  ASSERT_FALSE(photons.empty());
  for (const Photon& ph : photons) {
    EXPECT_NEAR(glm::length(ph.incident), 1.0f, 1e-4f);
    EXPECT_GT(glm::dot(ph.incident, ph.normal), 0.0f) << "light arrives on the side it is stored for";
  }
}

}  // namespace
}  // namespace igi
