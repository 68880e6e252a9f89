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
#include "photons/caustic_settings.h"
#include "photons/photon_grid.h"
#include "photons/photon_paths.h"
#include "scene/builtin_scenes.h"
#include "scene/camera_rays.h"
#include "scene/load_scene.h"
#include "scene/surface.h"
#include "scene/suite_scenes.h"
#include "vpl/vpl_generator.h"
#include "support/image_compare.h"
#include "support/process.h"
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

// Light spread thin (a lamp reflected off a ball over a whole ceiling) is a
// few photons a square metre; at the focused radius each shows as a speckle.
// The split sends a photon with fewer than K photons within r (itself
// included) to the wide grid, whatever order the photons come in.
TEST(PhotonGrid, PhotonsWithFewNeighboursAreSplitOffWhateverTheirOrder) {
  const float r = 0.01f;
  std::vector<Photon> photons;
  for (int i = 0; i < 12; ++i) photons.push_back({.position = {0.5f + 0.001f * float(i), 0.2f, 0.5f}});  // a focus
  for (int i = 0; i < 5; ++i) photons.push_back({.position = {0.1f * float(i), 0.9f, 0.1f}});  // 10 cm apart
  photons.push_back({.position = {0.5155f, 0.2f, 0.5f}});  // 4.5 mm past the focus: 7 within r
  auto x_of = [](const std::vector<Photon>& set) {
    std::vector<float> x;
    for (const Photon& p : set) x.push_back(p.position.x);
    std::sort(x.begin(), x.end());
    return x;
  };
  std::vector<Photon> dense, sparse;
  split_by_density(photons, r, glm::vec3(0.0f), 8, dense, sparse);
  EXPECT_EQ(dense.size(), 12u);
  ASSERT_EQ(sparse.size(), 6u);
  EXPECT_FLOAT_EQ(x_of(sparse).back(), 0.5155f) << "the photon beside the focus has 7 neighbours, not 8";
  std::mt19937 rng(2);
  for (int round = 0; round < 5; ++round) {
    std::vector<Photon> shuffled = photons, d, s;
    std::shuffle(shuffled.begin(), shuffled.end(), rng);
    split_by_density(shuffled, r, glm::vec3(0.0f), 8, d, s);
    EXPECT_EQ(x_of(d), x_of(dense));
    EXPECT_EQ(x_of(s), x_of(sparse));
  }
  split_by_density(photons, r, glm::vec3(0.0f), 1, dense, sparse);
  EXPECT_EQ(dense.size(), photons.size()) << "K = 1: every photon counts itself";
}

// Sparse photons are blurred most at one pass and less as passes add up, as
// the clamp relaxes, down to the bounced photons' radius.
TEST(PhotonGrid, TheSparseRadiusRelaxesWithPassesDownToTheBouncedRadius) {
  EXPECT_FLOAT_EQ(sparse_radius_scale(0), CausticMap::kSparseRadiusScale);
  for (uint32_t pass = 1; pass < 64; ++pass) EXPECT_LE(sparse_radius_scale(pass), sparse_radius_scale(pass - 1));
  EXPECT_NEAR(sparse_radius_scale(15), 2.0f, 1e-5f);
  EXPECT_FLOAT_EQ(sparse_radius_scale(1000000), CausticMap::kBouncedRadiusScale);
}

// Progressive photon mapping's radius reduction: r_k^2 / r_(k-1)^2 = (k +
// alpha) / (k + 1), so r_k^2 falls as k^(alpha - 1) and the blur vanishes.
TEST(PhotonGrid, EveryRadiusShrinksWithPassesAsProgressivePhotonMappingsDoes) {
  EXPECT_EQ(ppm_radius_scale(0), 1.0f) << "a moving view's pass keeps --caustic-radius";
  const double alpha = CausticMap::kPpmAlpha;
  for (uint32_t k = 1; k < 300; ++k) {
    const double ratio = double(ppm_radius_scale(k)) * ppm_radius_scale(k) /
                         (double(ppm_radius_scale(k - 1)) * ppm_radius_scale(k - 1));
    EXPECT_NEAR(ratio, (k + alpha) / (k + 1.0), 1e-6) << "pass " << k;
  }
  // prod (j + alpha) / (j + 1) = Gamma(k + 1 + alpha) / (Gamma(1 + alpha) Gamma(k + 2)) ~ k^(alpha - 1) / Gamma(1 + alpha).
  for (uint32_t k : {100u, 1000u, 10000u}) {
    const double closed = std::exp(std::lgamma(k + 1.0 + alpha) - std::lgamma(1.0 + alpha) - std::lgamma(k + 2.0));
    EXPECT_NEAR(double(ppm_radius_scale(k)), std::sqrt(closed), 1e-5) << "pass " << k;
  }
  EXPECT_NEAR(ppm_radius_scale(255), 0.4176f, 1e-3f);
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

// The map at a late pass: the same photons (one seed) gathered over a
// smaller disc, so the caustic covers fewer floor points and is as bright in
// sum (each kernel integrates to 1).
TEST(CausticMap, ALatePassGathersTheSamePhotonsOverASmallerDisc) {
  const test::Prepared p(make_glass_cornell());
  const RenderSettings s = caustic_settings(20000);
  const std::vector<GSample> points = p.visible_points(160, 120);
  auto lit = [&](uint32_t pass, double& sum) {
    CausticMap map(p.context(), s);
    map.build(5, 0, pass);
    int count = 0;
    sum = 0.0;
    for (const GSample& g : points) {
      if (!g.valid() || g.surface.material->type != MaterialType::Diffuse) continue;
      const double v = luminance(map.radiance(g));
      count += v > 0.0;
      sum += v;
    }
    return count;
  };
  double first_sum = 0.0, late_sum = 0.0;
  const int first = lit(0, first_sum), late = lit(255, late_sum);
  std::printf("[ppm] points the caustic reaches: pass 0 %d, pass 255 %d; sum %.4g / %.4g\n", first, late, first_sum,
              late_sum);
  ASSERT_GT(first, 200);
  EXPECT_LT(late, 0.8 * first) << "r_255 = 0.42 r: the support shrinks";
  EXPECT_NEAR(late_sum / first_sum, 1.0, 0.15) << "a smaller disc, the same light";
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

// With caustics on, a GGX lobe sharper than the glossy threshold focuses
// light like a mirror: light paths leave no VPL on it (its VPLs lit their
// neighbours through a lobe widened to the threshold), and photon paths pass
// it, so the light it reflects onto the walls arrives as photons.
TEST(CausticMap, SharpGlossySurfacesHoldNoVplAndPassPhotonsOnWhenCausticsAreOn) {
  const test::Prepared p(make_glossy_cornell());  // a GGX floor at alpha 0.04
  RenderSettings s = caustic_settings(4000);
  auto on_the_floor = [&](const RenderSettings& settings) {
    const VplSets sets = generate_vpls(p.context(), settings, 7);
    return std::count_if(sets.vpls.begin(), sets.vpls.end(), [&](const Vpl& v) {
      return v.kind == VplKind::Surface && p.scene.materials[v.material].type == MaterialType::Conductor;
    });
  };
  RenderSettings off = s;
  off.caustics = false;
  EXPECT_GT(on_the_floor(off), 50) << "without caustics the floor holds VPLs with widened lobes";
  EXPECT_EQ(on_the_floor(s), 0);
  RayCounts rays;
  const std::vector<Photon> photons = trace_photon_paths(p.context(), s, 1, 4000, 2, rays);
  EXPECT_GT(photons.size(), 400u) << "the floor passes the lamp's light on to the walls and ceiling";
  for (const Photon& ph : photons)
    EXPECT_FALSE(ph.position.y < 1e-3f && ph.normal.y > 0.99f) << "no photon lies on the floor itself";
  RenderSettings no_gather = s;
  no_gather.glossy_threshold = 0.0f;  // VPLs shade every GGX lobe: nothing here focuses light
  EXPECT_TRUE(trace_photon_paths(p.context(), no_gather, 1, 4000, 2, rays).empty());
  EXPECT_GT(on_the_floor(no_gather), 50) << "and the floor holds VPLs again";
}

// --- The caustic against the path tracer.
//
// The glass sphere focuses the ceiling light on the floor around C (its
// centre on the line from the light's centre through the ball's, 1.5 radii
// beyond the ball's centre, at the floor: scene/suite_scenes.h). The region
// is every pixel of a tile around C whose camera ray meets the floor within
// 3 cm of C directly (not through the glass). pt renders only that tile.

struct CausticRegion {
  TileJob tile;
  std::vector<size_t> pixels;  // inside the tile, row-major
};

CausticRegion caustic_region(const test::Prepared& p, int width, int height) {
  const glm::vec3 light(0.278f, 0.5487f, 0.2795f), ball(0.185f, 0.135f, 0.17f);
  const glm::vec3 d = glm::normalize(ball - light);
  const glm::vec3 focus = ball + d * (ball.y / -d.y);  // where the axis meets the floor
  const CameraBasis camera(p.frame(width, height).camera, width, height);
  int x0 = width, y0 = height, x1 = -1, y1 = -1;
  std::vector<std::pair<int, int>> inside;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      Hit hit;
      const Ray ray = camera.ray(x + 0.5f, y + 0.5f);
      if (!p.accel->intersect(ray, hit)) continue;
      const SurfacePoint sp = surface_at(p.scene, hit, ray.direction);
      if (sp.material->type != MaterialType::Diffuse || sp.position.y > 1e-4f) continue;
      if (glm::length(sp.position - focus) > 0.03f) continue;
      inside.emplace_back(x, y);
      x0 = std::min(x0, x); y0 = std::min(y0, y); x1 = std::max(x1, x); y1 = std::max(y1, y);
    }
  CausticRegion r;
  r.tile = TileJob{x0, y0, x1 - x0 + 1, y1 - y0 + 1, 0};
  for (auto [x, y] : inside) r.pixels.push_back(size_t(y - y0) * r.tile.w + size_t(x - x0));
  return r;
}

// Mean luminance over the region's pixels of its tile, rendered by `method` (begun).
double region_mean(const Method& method, const RenderSettings& s, const CausticRegion& r) {
  TileJob job = r.tile;
  job.border = tile_border(s);
  std::vector<glm::vec3> pixels(size_t(job.w) * job.h);
  RayCounts rays;
  method.render_tile(job, pixels, rays);
  double sum = 0.0;
  for (size_t i : r.pixels) sum += luminance(pixels[i]);
  return sum / double(r.pixels.size());
}

TEST(CausticAccuracy, TheCausticsMeanConvergesToThePathTracersAsPhotonsGrow) {
  const test::Prepared& p = glass_scene();
  const int width = 320, height = 240;
  const CausticRegion region = caustic_region(p, width, height);
  ASSERT_GE(region.pixels.size(), 40u) << "the caustic is in view";
  // pt over the region's tile only, sample indices [0, 2048).
  RenderSettings pts;
  pts.method = MethodKind::PathTracer;
  PathTracer pt(p.context(), pts);
  FrameSetup frame = p.frame(width, height, 7);
  frame.sample_count = 2048;
  pt.begin_frame(frame);
  const double reference = region_mean(pt, pts, region);
  // igi with 4 passes of fresh VPLs and photons, the photon count growing.
  auto igi_mean = [&](int photons) {
    RenderSettings s = caustic_settings(std::max(photons, 1));
    s.caustics = photons > 0;
    VplMethod igi(p.context(), s);
    double sum = 0.0;
    for (uint32_t pass = 0; pass < 4; ++pass) {
      const FrameSetup f = p.frame(width, height, 11 + pass);
      igi.begin_frame(f);
      sum += region_mean(igi, s, region);
    }
    return sum / 4.0;
  };
  const double without = igi_mean(0);
  std::printf("[caustic] %zu pixels: pt %.4f; igi without caustics %.4f (%+.1f %%)\n", region.pixels.size(),
              reference, without, 100.0 * (without / reference - 1.0));
  EXPECT_LT(without, 0.5 * reference) << "the caustic is most of the region's light";
  double previous = 1e30;
  for (int photons : {1000, 10000, 100000}) {
    const double mean = igi_mean(photons);
    const double error = std::abs(mean / reference - 1.0);
    std::printf("[caustic] %6d photon paths: igi %.4f (%+.1f %%)\n", photons, mean, 100.0 * (mean / reference - 1.0));
    EXPECT_LT(error, std::max(previous, 0.02)) << photons << " photon paths: the error must not grow";
    previous = error;
  }
  EXPECT_LT(previous, 0.10) << "within 10 % of pt at 100,000 photon paths";
}

// --- Bad options: a clear error naming the option, before any work.

TEST(CausticOptions, BadValuesAreRefusedBeforeAnyWork) {
  // The checks both command lines and the wire make, in process.
  auto error = [](void (*change)(RenderSettings&)) {
    RenderSettings s = caustic_settings(20000);
    change(s);
    return settings_error(s).value_or("");
  };
  EXPECT_EQ(error([](RenderSettings&) {}), "");
  EXPECT_EQ(error([](RenderSettings& s) { s.caustic_photons = 0; }).rfind("--caustic-photons: expected 1..67108864 photon paths per frame", 0), 0u);
  EXPECT_NE(error([](RenderSettings& s) { s.caustic_photons = (1 << 26) + 1; }).find("got 67108865"), std::string::npos);
  EXPECT_EQ(error([](RenderSettings& s) { s.caustic_radius = 0; })
                .rfind("--caustic-radius: expected a fraction of the scene diagonal in [1e-05, 0.25], got 0", 0), 0u);
  EXPECT_NE(error([](RenderSettings& s) { s.caustic_radius = 0.5f; }).find("got 0.5"), std::string::npos);
  EXPECT_NE(error([](RenderSettings& s) { s.caustic_radius = NAN; }).find("got nan"), std::string::npos);
  EXPECT_EQ(error([](RenderSettings& s) { s.glass_branches = 9; }), "--glass-branches: expected 1..8, got 9");
  EXPECT_EQ(error([](RenderSettings& s) { s.glass_branches = 0; }), "--glass-branches: expected 1..8, got 0");
  // Beyond memory: 2^26 paths may store 4 photons each.
  const std::string memory = photons::memory_error(caustic_settings(1 << 26), 16ull << 30);
  EXPECT_EQ(memory.rfind("--caustic-photons: 67108864 photon paths can store up to 30.0 GiB", 0), 0u) << memory;
  EXPECT_EQ(photons::memory_error(caustic_settings(20000), 16ull << 30), "");
  RenderSettings off = caustic_settings(1 << 26);
  off.caustics = false;
  EXPECT_EQ(photons::memory_error(off, 16ull << 30), "") << "no map, no memory";
  // The command lines: exit 1 with the message, before the scene is loaded.
  struct Case {
    std::string command, expected;
  };
  const std::string render = std::string(IGI_RENDER_BINARY) + " --scene no-such-scene --quiet -o " + test::output_path("bad.exr");
  const std::vector<Case> cases = {
      {render + " --caustic-photons 0", "--caustic-photons: expected 1..67108864 photon paths per frame (leave out --caustics to turn caustics off), got 0"},
      {render + " --caustic-radius x", "--caustic-radius: expected a number, got 'x'"},
      {render + " --caustics --method pt", "--caustics: only the ir and igi methods"},
      {std::string(IGI_MASTER_BINARY) + " --workers 0 --frames 1 --caustic-radius 0 -o " + test::output_path("bad.exr"),
       "--caustic-radius: expected a fraction of the scene diagonal in [1e-05, 0.25], got 0"},
  };
  for (const Case& c : cases) {
    const test::RunResult r = test::run(c.command, 20);
    EXPECT_EQ(r.exit_code, 1) << c.command << "\n" << r.output;
    EXPECT_NE(r.output.find(c.expected), std::string::npos) << c.command << "\n" << r.output;
  }
}

// --- Energy: a glass sphere in a uniformly lit closed box.
//
// In the white furnace (every wall emits 1 and reflects half) the radiance is
// 1 / (1 - 0.5) = 2 everywhere, and a clear glass sphere, which absorbs
// nothing, cannot change that: seen through it or beside it, every pixel is
// 2. Without the photon map the walls lose what reaches them through the
// glass (shadow rays stop at it); the map must give back exactly that.

Scene furnace_with_glass_sphere() {
  Scene s = make_furnace(0.5f, 1.0f);
  const uint32_t glass = add_material(s, clear_glass());
  add_bumpy_sphere(s, {0.2f, 0.0f, 0.55f}, 0.22f, 16, [](float, float) { return 1.0f; }, glass);
  return s;
}

struct FurnaceMeans {
  double all, through_glass;
};

FurnaceMeans furnace_means(const test::Prepared& p, const RenderSettings& s, int width, int height, int passes) {
  const Image image = p.render(s, width, height, passes, 5);
  FrameSetup frame = p.frame(width, height);
  const CameraBasis camera(frame.camera, width, height);
  double all = 0.0, glass = 0.0;
  int glass_count = 0;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const double v = luminance(image.at(x, y));
      all += v;
      Hit hit;
      // Pixel centres of the passes' jitter vary; the centre decides the class.
      if (p.accel->intersect(camera.ray(x + 0.5f, y + 0.5f), hit) &&
          p.scene.materials[p.scene.triangle_material[hit.triangle]].type == MaterialType::Glass) {
        glass += v;
        ++glass_count;
      }
    }
  return {all / (width * height), glass_count ? glass / glass_count : 0.0};
}

TEST(CausticFurnace, AGlassSphereNeitherAddsNorLosesEnergy) {
  const test::Prepared p(furnace_with_glass_sphere());
  RenderSettings s = caustic_settings(40000);
  s.paths_per_set = 16;
  // Unbounded camera chains: in this faceted sphere, rays that enter near
  // the rim reflect inside it many times before leaving (Fresnel near the
  // critical angle), and the default cut at 16 surfaces loses 3 % of the
  // light seen through it (2.9 % of those pixels end inside the glass).
  s.specular_depth = 0;
  for (int branches : {1, 3}) {
    s.glass_branches = branches;
    const FurnaceMeans m = furnace_means(p, s, 48, 36, 4);
    std::printf("[furnace] glass branches %d: mean %.4f, through the glass %.4f (exact 2)\n", branches, m.all,
                m.through_glass);
    EXPECT_NEAR(m.all, 2.0, 0.02) << "branches " << branches;
    EXPECT_NEAR(m.through_glass, 2.0, 0.03) << "branches " << branches;
  }
  // The test can fail: without the map the light through the glass is lost.
  s.caustics = false;
  const FurnaceMeans off = furnace_means(p, s, 48, 36, 4);
  std::printf("[furnace] without caustics: mean %.4f, through the glass %.4f\n", off.all, off.through_glass);
  EXPECT_LT(off.all, 2.0 - 0.06);
}

}  // namespace
}  // namespace igi
