// Where IGI used to fail a new user's eye, each with an answer known in
// closed form or from the path tracer:
//   a. exact point lights: one shadow ray per light, hard shadows unfiltered;
//   b. anti-aliasing by VPL groups: same mean, edges converge to coverage;
//   c. glossy receivers: no VPL specks in a sharp GGX lobe;
//   d. single-sided faces: culled for the camera, opaque to light;
//   e. unbounded light paths: the VPL methods in a furnace of albedo 0.9;
//   f. options out of range get errors naming the option.
#include <algorithm>
#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>

#include "image/metrics.h"
#include "material/bsdf.h"
#include "scene/builtin_scenes.h"
#include "scene/load_scene.h"
#include "scene/suite_scenes.h"
#include "support/image_compare.h"
#include "support/process.h"
#include "support/render_fixture.h"
#include "sampling/sobol.h"
#include "sampling/warp.h"

namespace igi {
namespace {

using test::luminance;
using test::vpl_settings;

Camera look_at(glm::vec3 from, glm::vec3 to, float vfov) {
  Camera c;
  c.position = from;
  c.forward = glm::normalize(to - from);
  c.up = std::abs(c.forward.y) > 0.99f ? glm::vec3(0, 0, 1) : glm::vec3(0, 1, 0);
  c.vfov = vfov;
  return c;
}

// ---- a. Exact point lights.

// A plane of albedo 0.5 under a point light, and a black blocker between:
// direct light only (the blocker reflects nothing, the plane cannot light
// itself), so igi must give the closed form at every pixel, shadow included.
Scene shadowed_plane() {
  Scene s;
  Material plane;
  plane.base_color = glm::vec3(0.5f);
  add_material(s, plane);
  Material black;
  black.base_color = glm::vec3(0.0f);
  add_material(s, black);
  add_quad(s, {-10, 0, -10}, {-10, 0, 10}, {10, 0, 10}, {10, 0, -10}, 0);
  add_quad(s, {0.2f, 1, -0.5f}, {0.2f, 1, 0.5f}, {0.8f, 1, 0.5f}, {0.8f, 1, -0.5f}, 1);
  PunctualLight light;
  light.position = {0.0f, 2.0f, 0.0f};
  light.intensity = glm::vec3(8.0f);
  s.lights.push_back(light);
  s.camera = look_at({-0.5f, 2.5f, -2.0f}, {1.0f, 0.0f, 0.0f}, 1.0f);
  return s;
}

TEST(ExactLights, PointLightIsOneRayPerPixelAndItsShadowStaysHard) {
  const test::Prepared p(shadowed_plane());
  const int w = 64, h = 48;
  const std::vector<GSample> visible = p.visible_points(w, h);
  const PunctualLight& light = p.scene.lights[0];
  Image expected(w, h);
  size_t lit_pixels = 0, shadowed_pixels = 0, valid_pixels = 0;
  for (size_t i = 0; i < visible.size(); ++i) {
    const GSample& g = visible[i];
    if (!g.valid()) continue;
    ++valid_pixels;
    const glm::vec3 d = light.position - g.surface.position;
    const float r = glm::length(d);
    const glm::vec3 wi = d / r;
    if (p.accel->occluded(Ray{offset_origin(g.surface, wi), wi, 0.0f, r * (1.0f - kShadowEpsilon)})) {
      shadowed_pixels += g.surface.albedo.x > 0.0f;
      continue;
    }
    lit_pixels += g.surface.albedo.x > 0.0f;
    expected.pixels[i] = g.surface.albedo * kInvPi * light.intensity * std::abs(glm::dot(wi, g.surface.shading_normal)) / (r * r);
  }
  ASSERT_GT(shadowed_pixels, 100u) << "the view must hold a shadow";
  ASSERT_GT(lit_pixels, 1000u);
  for (bool filter : {true, false}) {
    RenderSettings s = vpl_settings(MethodKind::Igi, 16, 0.0f, filter);
    RayCounts rays;
    FrameOptions options;
    options.threads = 1;
    const Image image = render_offline(p.context(), s, p.frame(w, h), 1, options).image;
    for (size_t i = 0; i < image.pixels.size(); ++i)
      for (int c = 0; c < 3; ++c)
        ASSERT_NEAR(image.pixels[i][c], expected.pixels[i][c], 1e-4f * expected.pixels[i][c] + 1e-7f)
            << "pixel " << i % w << ", " << i / w << (filter ? " (filtered)" : " (no filter)");
  }
  // One shadow ray per visible point for the light; the VPLs (on the plane
  // and the blocker's top, facing away from every visible point) cast none.
  RayCounts rays;
  auto method = make_method(p.context(), vpl_settings(MethodKind::Igi, 16));
  method->begin_frame(p.frame(w, h));
  FrameOptions options;
  render_frame(*method, p.frame(w, h), tile_border(vpl_settings(MethodKind::Igi, 16)), options, rays);
  EXPECT_EQ(rays.shadow, valid_pixels) << "a point light is evaluated once per pixel, not once per VPL copy";
}

// ---- b. Anti-aliasing by VPL groups.

// S sub-samples each take 1/S of the set's paths, scaled by S: the mean
// does not move. Compared on open surfaces only (pixels whose neighbours see
// the same flat surface), where sub-pixel position changes nothing but the
// VPL noise; pooled over three seeds.
TEST(Antialiasing, GroupsKeepTheMeanOfOneSample) {
  const test::Prepared p(make_cornell_box());
  const int w = 64, h = 48;
  const std::vector<GSample> visible = p.visible_points(w, h);
  std::vector<bool> open(visible.size(), false);
  for (int y = 1; y < h - 1; ++y)
    for (int x = 1; x < w - 1; ++x) {
      const GSample& c = visible[size_t(y) * w + x];
      bool same = c.valid() && !c.surface.material->is_emissive();
      for (int j = -1; j <= 1; ++j)
        for (int i = -1; i <= 1; ++i) {
          const GSample& n = visible[size_t(y + j) * w + x + i];
          same = same && n.valid() && n.surface.material == c.surface.material &&
                 glm::dot(n.surface.shading_normal, c.surface.shading_normal) > 0.999f;
        }
      open[size_t(y) * w + x] = same;
    }
  auto mean = [&](int aa) {
    double sum = 0.0;
    for (uint32_t seed : {1u, 7u, 13u}) {
      RenderSettings s = vpl_settings(MethodKind::Igi, 16, 0.05f);
      s.aa_samples = aa;
      const Image image = p.render(s, w, h, 1, seed);
      for (size_t i = 0; i < open.size(); ++i)
        if (open[i]) sum += luminance(image.pixels[i]);
    }
    return sum;
  };
  const double one = mean(1), four = mean(4), nine = mean(9);
  std::printf("[aa] open surfaces, pooled over 3 seeds: S=4 %+.2f %%, S=9 %+.2f %% against S=1\n",
              100 * (four / one - 1), 100 * (nine / one - 1));
  EXPECT_NEAR(four, one, 0.015 * one);
  EXPECT_NEAR(nine, one, 0.015 * one);
}

// An emitter (radiance 1, black) in front of nothing, its edge a line
// across the view: a pixel's right value is the share of its square the
// emitter covers. The camera looks down -z at the plane z = -1 with one
// pixel = 1/32 m there.
constexpr int kEdgeSize = 32;
Scene edge_scene() {
  Scene s;
  Material emitter;
  emitter.base_color = glm::vec3(0.0f);
  emitter.emission = glm::vec3(1.0f);
  add_material(s, emitter);
  // Below the line Y = 0.37 X + 0.11; wound to face the camera.
  auto on_line = [](float x, float below) { return glm::vec3(x, 0.37f * x + 0.11f - below, -1.0f); };
  s.positions = {on_line(-5, 0), on_line(0, 20), on_line(5, 0)};
  s.triangles = {{0, 1, 2}};
  s.triangle_material = {0};
  Camera c;
  c.forward = {0, 0, -1};
  c.vfov = 2.0f * std::atan(0.5f);
  s.camera = c;
  return s;
}

// The exact covered share of each pixel, integrated row by row.
Image edge_coverage() {
  Image image(kEdgeSize, kEdgeSize);
  const float pixel = 1.0f / kEdgeSize;
  for (int j = 0; j < kEdgeSize; ++j)
    for (int i = 0; i < kEdgeSize; ++i) {
      double covered = 0.0;
      const int rows = 1024;
      for (int r = 0; r < rows; ++r) {
        const double y = j + (r + 0.5) / rows;
        const double world_y = -(y - 0.5 * kEdgeSize) * pixel;
        // Covered where world_y < 0.37 X + 0.11, X = (x - 16) * pixel.
        const double x_edge = (world_y - 0.11) / 0.37 / pixel + 0.5 * kEdgeSize;
        covered += std::clamp(double(i + 1) - std::max(x_edge, double(i)), 0.0, 1.0);
      }
      image.at(i, j) = glm::vec3(float(covered / rows));
    }
  return image;
}

TEST(Antialiasing, EdgeConvergesToItsBoxFilteredCoverage) {
  const test::Prepared p(edge_scene());
  const Image coverage = edge_coverage();
  auto edge_error = [&](int aa, int passes) {
    RenderSettings s = vpl_settings(MethodKind::Igi, 16);
    s.aa_samples = aa;
    const Image image = p.render(s, kEdgeSize, kEdgeSize, passes);
    double sum = 0.0;
    int n = 0;
    for (size_t i = 0; i < image.pixels.size(); ++i) {
      const float c = coverage.pixels[i].x;
      if (c <= 0.0f || c >= 1.0f) continue;  // edge pixels only
      sum += std::abs(image.pixels[i].x - c);
      ++n;
    }
    return sum / n;
  };
  const double one = edge_error(1, 1), four = edge_error(4, 1), sixteen = edge_error(16, 1),
               progressive = edge_error(4, 16);
  std::printf("[aa] edge pixels, mean |pixel - coverage|: S=1 %.4f, S=4 %.4f, S=16 %.4f, S=4 x 16 passes %.4f\n",
              one, four, sixteen, progressive);
  EXPECT_GT(one, 0.15) << "one centred sample per pixel is all or nothing";
  EXPECT_LT(four, 0.6 * one);
  EXPECT_LT(sixteen, 0.6 * four);
  EXPECT_LT(sixteen, 0.05);
  EXPECT_LT(progressive, 0.03) << "jittered passes converge to the coverage";
}

// ---- c. Glossy receivers.

// Whether the light is reflected at g: any of 64 directions drawn from its
// GGX lobe reaches an emitter. There a bright pixel is a highlight, not a speck.
bool reflects_the_light(const test::Prepared& p, const GSample& g) {
  SurfacePoint white = g.surface;
  white.albedo = glm::vec3(1.0f);
  for (uint32_t k = 0; k < 64; ++k) {
    auto bs = bsdf_sample(white, g.wo, sample_2d(k, 0, 1234u), 0.0f);
    if (!bs) continue;
    Hit hit;
    if (p.accel->intersect(Ray{offset_origin(g.surface, bs->wi), bs->wi}, hit) &&
        p.scene.materials[p.scene.triangle_material[hit.triangle]].is_emissive())
      return true;
  }
  return false;
}

// Specks: floor pixels, away from the light's reflection, brighter than 5x
// the median of their 5 x 5 neighbourhood and than 5 % of the image's mean
// (no near-black noise).
int count_specks(const Image& image, const std::vector<bool>& judged) {
  const double floor_level = 0.05 * luminance(image.mean());
  int specks = 0;
  for (int y = 2; y < image.height - 2; ++y)
    for (int x = 2; x < image.width - 2; ++x) {
      if (!judged[size_t(y) * image.width + x]) continue;
      std::vector<double> around;
      for (int j = -2; j <= 2; ++j)
        for (int i = -2; i <= 2; ++i) around.push_back(luminance(image.at(x + i, y + j)));
      std::nth_element(around.begin(), around.begin() + 12, around.end());
      const double v = luminance(image.at(x, y));
      specks += v > 5.0 * around[12] && v > floor_level;
    }
  return specks;
}

// A VPL seen in a sharp lobe is a highlight of its own, and more VPLs give
// more (each dimmer). Gathered, what is left is the reflection of the walls' own
// blotches (VPLs close to a crease, where even the clamped 1/r^2 is large)
// seen at grazing angles, which the VPL budget sets, not the floor. Pooled
// over three seeds.
TEST(Glossy, SharpFloorShowsNoVplSpecks) {
  const test::Prepared p(load_scene("glossy"));
  const int w = 96, h = 72;
  const std::vector<GSample> visible = p.visible_points(w, h);
  std::vector<bool> judged(visible.size());
  int floor = 0;
  for (size_t i = 0; i < visible.size(); ++i) {
    const GSample& g = visible[i];
    judged[i] = g.valid() && g.surface.material->type == MaterialType::Conductor && !reflects_the_light(p, g);
    floor += judged[i];
  }
  auto specks = [&](float threshold, int paths, int rays) {
    // Clamped: else the walls' own blotches (VPLs near creases) show in the reflection.
    RenderSettings s = vpl_settings(MethodKind::Igi, paths, 0.05f);
    s.glossy_threshold = threshold;
    s.glossy_rays = rays;
    int n = 0;
    for (uint32_t seed : {1u, 2u, 3u}) n += count_specks(p.render(s, w, h, 1, seed), judged);
    return n;
  };
  const int vpls = specks(0.0f, 16, 1), more_vpls = specks(0.0f, 64, 1);  // the old way: VPLs shade the floor
  const int gathered = specks(0.2f, 16, 1);
  std::printf("[glossy] speck pixels on %d floor pixels away from the light's reflection (3 seeds): VPLs %d (M=64: %d), "
              "gathered %d\n", floor, vpls, more_vpls, gathered);
  EXPECT_GT(vpls, 30) << "VPLs in a sharp lobe must show as specks, or this test proves nothing";
  // Four times the VPLs left about as many specks under the box filter (57
  // and 68); the tent (filter_tent) spreads each over 11 x 11 pixels, so at
  // M = 64 most fall under the 5x-the-median mark (36 -> 11): what remains
  // is gathering's gain at equal VPLs, which the tent does not change.
  EXPECT_LT(more_vpls, vpls) << "more VPLs, each a dimmer speck, under the tent";
  EXPECT_LE(2 * gathered, vpls);
}

// relMSE of luminance over the GGX floor's pixels against `mean` (1e-4
// keeps near-black pixels from ruling it).
double floor_rel_mse(const std::vector<GSample>& visible, const Image& image, const Image& mean) {
  double sum = 0.0;
  int n = 0;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      const GSample& g = visible[size_t(y) * image.width + x];
      if (!g.valid() || g.surface.material->type != MaterialType::Conductor) continue;
      const double r = luminance(mean.at(x, y)), d = luminance(image.at(x, y)) - r;
      sum += d * d / (r * r + 1e-4);
      ++n;
    }
  return sum / n;
}

// One pass at the defaults (the glossy gather, compensation, 4x AA) against
// the mean of many, on the floor and on the walls beside it. Three causes of
// squares (one sub-sample's speck spread over the discontinuity buffer's
// 3 x 3 neighbours), each fixed at its root, are judged here: gather rays
// that found the small light by chance (no light samples), gather hits
// shaded by a quarter of a set's VPLs, and compensation rays from a wall that
// landed on the sharp floor and shaded it with VPLs through its sharp lobe
// (a row of specks along each crease). Measured at 128x96 over three seeds,
// before the fixes and after: the floor's relMSE against the mean of 64
// passes 2.85 and 0.35; the largest share compensation added to a crease
// pixel 8.0 (a speck nine times the pixel) and 0.24.
TEST(Glossy, OnePassAtTheDefaultsShowsNoSquares) {
  const test::Prepared p(load_scene("glossy"));
  const int w = 128, h = 96;
  const std::vector<GSample> visible = p.visible_points(w, h);
  const RenderSettings defaults;
  const Image mean = p.render(defaults, w, h, 64, 100);
  auto is_floor = [&](int x, int y) {
    const GSample& g = visible[size_t(y) * w + x];
    return g.valid() && g.surface.material->type == MaterialType::Conductor;
  };
  // Diffuse pixels within 3 pixels of the floor: the creases.
  auto near_floor = [&](int x, int y) {
    for (int j = std::max(0, y - 3); j <= std::min(h - 1, y + 3); ++j)
      for (int i = std::max(0, x - 3); i <= std::min(w - 1, x + 3); ++i)
        if (is_floor(i, j)) return true;
    return false;
  };
  // What compensation adds at the creases, relative to the pixel without it: the largest of them.
  RenderSettings uncompensated = defaults;
  uncompensated.compensation_samples = 0;
  auto largest_gain = [&](const Image& with, const Image& without) {
    double largest = 0.0;
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x)
        if (visible[size_t(y) * w + x].valid() && !is_floor(x, y) && near_floor(x, y))
          largest = std::max(largest, (luminance(with.at(x, y)) - luminance(without.at(x, y))) /
                                          (luminance(without.at(x, y)) + 1e-3));
    return largest;
  };
  double floor = 0.0, gain = 0.0;
  for (uint32_t seed : {1u, 2u, 3u}) {
    const Image one_pass = p.render(defaults, w, h, 1, seed);
    const double f = floor_rel_mse(visible, one_pass, mean), g = largest_gain(one_pass, p.render(uncompensated, w, h, 1, seed));
    floor += f / 3.0;
    gain = std::max(gain, g);
    if (f > 1.0 || g > 1.0) test::write_failure_images("glossy-one-pass-seed" + std::to_string(seed), one_pass, mean);
  }
  std::printf("[glossy] one pass at the defaults: relMSE of the floor against the mean of 64 %.3f, compensation's "
              "largest gain at a crease %.2f\n", floor, gain);
  EXPECT_LT(floor, 1.0);
  EXPECT_LT(gain, 1.0);
}

// ---- d. Single-sided faces.

// A single-sided sheet facing a point light hangs over the floor, so shadow
// rays from the floor below meet its back; between the camera and that floor
// stands a single-sided wall facing away from the camera. The camera must
// see through the wall (its back is culled for camera rays) onto the floor
// in the sheet's shadow (the sheet's back is opaque to shadow rays and light
// paths; culling it for every ray would leak the light through).
TEST(SingleSided, CulledForTheCameraOpaqueToLight) {
  Scene s;
  Material floor;
  floor.base_color = glm::vec3(0.5f);
  add_material(s, floor);
  Material sheet = floor;
  sheet.double_sided = false;
  add_material(s, sheet);
  add_quad(s, {-10, 0, -10}, {-10, 0, 10}, {10, 0, 10}, {10, 0, -10}, 0);
  add_quad(s, {-1, 1, -1}, {-1, 1, 1}, {1, 1, 1}, {1, 1, -1}, 1);      // front face up, towards the light
  add_quad(s, {-2, 0, -2}, {-2, 2, -2}, {-2, 2, 2}, {-2, 0, 2}, 1);   // front face +x, away from the camera
  PunctualLight light;
  light.position = {0.0f, 3.0f, 0.0f};
  light.intensity = glm::vec3(20.0f);
  s.lights.push_back(light);
  s.camera = look_at({-2.5f, 0.9f, 0.0f}, {0.0f, 0.0f, 0.0f}, 0.2f);
  const test::Prepared p(std::move(s));
  const std::vector<GSample> visible = p.visible_points(16, 16);
  for (const GSample& g : visible)
    ASSERT_TRUE(g.valid() && g.surface.position.y < 0.01f && std::abs(g.surface.position.x) < 1.4f)
        << "the camera sees the floor under the sheet through the wall";
  // Unshadowed, the floor below the light would show 0.5/pi * 20 / 9 = 0.354.
  for (MethodKind kind : {MethodKind::PathTracer, MethodKind::Igi}) {
    RenderSettings settings = vpl_settings(kind, 16);
    const Image image = p.render(settings, 16, 16, kind == MethodKind::PathTracer ? 16 : 1);
    const double mean = luminance(image.mean());
    std::printf("[single-sided] %s: floor under the sheet %.4f (unshadowed 0.354)\n", method_name(kind), mean);
    EXPECT_LT(mean, 0.06) << method_name(kind) << ": light leaks through the back of a single-sided face";
  }
}

// Glass refracts on the way out as on the way in, whatever doubleSided says
// (issue 47): exporters write single-sided glass, and a camera ray that
// refracted into a sphere whose back faces it skipped left it unbent, a milky
// disc. With every glass material single-sided the glass scene renders as
// with every one double-sided, bit for bit, in every method.
TEST(SingleSided, GlassRefractsOutOfASingleSidedSphereAsOutOfADoubleSidedOne) {
  Scene single = make_glass_cornell(), twofold = make_glass_cornell();
  int glass = 0;
  for (Material& m : single.materials)
    if (m.type == MaterialType::Glass) m.double_sided = false, ++glass;
  for (Material& m : twofold.materials)
    if (m.type == MaterialType::Glass) m.double_sided = true;
  ASSERT_GT(glass, 0);
  const test::Prepared a(std::move(single)), b(std::move(twofold));
  for (MethodKind kind : {MethodKind::PathTracer, MethodKind::Igi, MethodKind::Lightcuts}) {
    RenderSettings settings = vpl_settings(kind, 8);
    const int samples = kind == MethodKind::PathTracer ? 4 : 1;
    const Image one = a.render(settings, 40, 40, samples), two = b.render(settings, 40, 40, samples);
    EXPECT_TRUE(test::images_identical(std::string("glass-single-sided-") + method_name(kind), one, two))
        << method_name(kind) << ": single-sided glass renders otherwise than double-sided";
  }
}

// A camera ray through a single-sided glass ball (ior 1.5, smooth normals)
// leaves it deviated by the closed form 2 (theta_i - theta_t) towards the
// axis, sin theta_i = b / R, sin theta_t = sin theta_i / 1.5: it refracted
// on the way out too. Through the centre it passes straight.
TEST(SingleSided, ARayThroughASingleSidedGlassBallBendsAsTheClosedFormSays) {
  Scene s;
  Material wall;
  const uint32_t wall_id = add_material(s, wall);
  Material glass;
  glass.type = MaterialType::Glass;
  glass.ior = 1.5f;
  glass.base_color = glm::vec3(1.0f);
  glass.double_sided = false;
  const uint32_t glass_id = add_material(s, glass);
  add_quad(s, {-20, -20, -6}, {20, -20, -6}, {20, 20, -6}, {-20, 20, -6}, wall_id);  // facing +z, the ball
  const uint32_t first_sphere_vertex = uint32_t(s.positions.size());
  add_bumpy_sphere(s, glm::vec3(0.0f), 1.0f, 96, [](float, float) { return 1.0f; }, glass_id);
  s.normals.assign(s.positions.size(), glm::vec3(0.0f, 0.0f, 1.0f));
  for (uint32_t v = first_sphere_vertex; v < s.positions.size(); ++v) s.normals[v] = glm::normalize(s.positions[v]);
  const test::Prepared p(std::move(s));
  for (float b : {0.0f, 0.3f, 0.6f}) {
    const Ray ray{{b, 0.0001f, 5.0f}, {0.0f, 0.0f, -1.0f}, 0.0f, 1e30f, kCameraRayMask};
    Hit hit;
    ASSERT_TRUE(p.accel->intersect(ray, hit));
    GSample out[kMaxGlassBranches];
    GSample* branches[kMaxGlassBranches];
    for (int i = 0; i < kMaxGlassBranches; ++i) branches[i] = &out[i];
    RayCounts rays;
    follow_specular_tree(*p.accel, ray, hit, 1, 16, kMaxGlassBranches, branches, rays);
    const GSample& refracted = out[0];  // branch 0 refracts at every split
    ASSERT_TRUE(refracted.valid()) << "b = " << b;
    ASSERT_LT(refracted.surface.position.z, -5.9f) << "b = " << b << ": the chain ends on the wall";
    const double theta_i = std::asin(double(b)), theta_t = std::asin(double(b) / 1.5);
    const double expected = 2.0 * (theta_i - theta_t);
    const glm::vec3 out_dir = -refracted.wo;
    const double deviation = std::atan2(-double(out_dir.x), -double(out_dir.z));
    std::printf("[glass ball] b = %.1f: deviation %.5f rad, closed form %.5f\n", b, deviation, expected);
    EXPECT_NEAR(deviation, expected, 2e-3) << "b = " << b;
  }
}

// ---- e. Unbounded light paths.

// Inside a closed sphere of emission Le and albedo a, radiance is
// Le / (1 - a) everywhere. At a = 0.9 a light path of 16 bounces would lose
// 18.5 % of it; the default (roulette only) loses nothing.
TEST(VplFurnace, DefaultLightPathsReachTheClosedFormAtAlbedo09) {
  const test::Prepared p(make_furnace(0.9f, 1.0f));
  for (MethodKind kind : {MethodKind::InstantRadiosity, MethodKind::Igi}) {
    const double mean = luminance(p.render(vpl_settings(kind, 32), 24, 24, 4).mean());
    std::printf("[furnace] %s, albedo 0.9: mean %.4f (closed form 10)\n", method_name(kind), mean);
    EXPECT_NEAR(mean, 10.0, 0.3) << method_name(kind);
  }
}

// ---- f. Options.

TEST(QualityOptions, OutOfRangeValuesNameTheOption) {
  const struct {
    const char* args;
    const char* message;
  } cases[] = {
      {"--aa 3", "--aa: expected a square number"},
      {"--aa 0", "--aa: expected"},
      {"--aa 81", "--aa: expected a square number"},
      {"--aa 16 --vpl-paths 8", "--aa 16 needs --vpl-paths >= 16"},
      {"--glossy-threshold 1.5", "--glossy-threshold: expected a GGX alpha in [0, 1]"},
      {"--glossy-threshold -0.1", "--glossy-threshold"},
      {"--glossy-threshold nan", "--glossy-threshold"},
      {"--glossy-rays 0", "--glossy-rays"},
      {"--wavelet 6", "--wavelet"},
      {"--wavelet -1", "--wavelet"},
      {"--light-depth -1", "--light-depth"},
      {"--max-depth 8", "--max-depth was split"},
  };
  for (const auto& c : cases) {
    const test::RunResult r = test::run(std::string(IGI_RENDER_BINARY) + " --quiet -o /dev/null " + c.args);
    EXPECT_EQ(r.exit_code, 1) << c.args;
    EXPECT_NE(r.output.find(c.message), std::string::npos) << c.args << ": " << r.output;
  }
}

}  // namespace
}  // namespace igi
