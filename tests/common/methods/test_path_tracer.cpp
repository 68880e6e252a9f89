// The reference path tracer against answers known in closed form.
#include <cmath>

#include <gtest/gtest.h>

#include "image/metrics.h"
#include "render/offline_render.h"
#include "methods/path_tracer.h"
#include "scene/builtin_scenes.h"
#include "scene/suite_scenes.h"
#include "support/image_compare.h"

namespace igi {
namespace {

struct Rendered {
  Image image;
  RayCounts rays;
};

// path_depth 0: the default, unbounded paths ended by Russian roulette.
Rendered render_pt(const Scene& scene, int size, int spp, uint32_t seed = 1, int path_depth = 0) {
  Accel accel(scene);
  LightSet lights(scene);
  RenderSettings settings;
  settings.method = MethodKind::PathTracer;
  settings.path_depth = path_depth;
  FrameSetup frame;
  frame.camera = scene.camera_or_auto();
  frame.width = frame.height = size;
  frame.seed = seed;
  OfflineResult r = render_offline({scene, accel, lights}, settings, frame, spp, FrameOptions{});
  return {r.image, r.rays};
}

// Mean over pixels and channels with the standard error of that mean.
std::pair<double, double> mean_and_error(const Image& image) {
  double sum = 0, sum2 = 0;
  const double n = double(image.pixels.size());
  for (const glm::vec3& p : image.pixels) {
    double v = (p.x + p.y + p.z) / 3.0;
    sum += v; sum2 += v * v;
  }
  double mean = sum / n;
  return {mean, std::sqrt(std::max(0.0, sum2 / n - mean * mean) / n)};
}

class WhiteFurnace : public ::testing::TestWithParam<float> {};

TEST_P(WhiteFurnace, ClosedSphereGivesEmissionOverOneMinusAlbedo) {
  const float albedo = GetParam(), emission = 1.0f;
  Rendered r = render_pt(make_furnace(albedo, emission), 24, 32);  // the default path length
  auto [mean, error] = mean_and_error(r.image);
  const double expected = emission / (1.0 - albedo);
  // Statistical tolerance: five standard errors, plus 0.5 % for the sphere's facets.
  EXPECT_NEAR(mean, expected, 5.0 * error + 0.005 * expected) << "standard error " << error;
}

// 0.9 and 0.95: paths of tens of bounces, where a fixed cap of 16 would lose
// 0.9^16 = 18.5 % and 0.95^16 = 44 % of the answer.
INSTANTIATE_TEST_SUITE_P(PathTracer, WhiteFurnace, ::testing::Values(0.0f, 0.5f, 0.8f, 0.9f, 0.95f));

// The same at a fixed cap: the test above can fail. Paths of at most D
// surfaces sum the first D terms of the series: Le (1 - a^D) / (1 - a).
TEST(PathTracer, CappedPathsLoseTheTailOfTheSeries) {
  const float albedo = 0.9f;
  Rendered r = render_pt(make_furnace(albedo, 1.0f), 24, 32, 1, 16);
  auto [mean, error] = mean_and_error(r.image);
  const double expected = (1.0 - std::pow(albedo, 16.0)) / (1.0 - albedo);
  EXPECT_NEAR(mean, expected, 5.0 * error + 0.005 * expected) << "standard error " << error;
  EXPECT_LT(mean, 0.9 * 10.0) << "a cap of 16 must lose ~18 % of Le / (1 - a) = 10";
}

TEST(PathTracer, DiffusePlaneUnderPointLightMatchesInverseSquareLaw) {
  // Lambertian plane y = 0 of albedo a, point light of intensity I at height h:
  // radiance below the light is a/pi * I / h^2, whatever the view direction.
  Scene s;
  Material m;
  m.base_color = glm::vec3(0.5f);
  add_material(s, m);
  add_quad(s, {-10, 0, -10}, {-10, 0, 10}, {10, 0, 10}, {10, 0, -10}, 0);
  PunctualLight light;
  light.position = {0.0f, 2.0f, 0.0f};
  light.intensity = glm::vec3(8.0f);
  s.lights.push_back(light);
  Camera cam;
  cam.position = {0.0f, 1.0f, 0.0f};
  cam.forward = {0.0f, -1.0f, 0.0f};
  cam.up = {0.0f, 0.0f, 1.0f};
  cam.vfov = 0.02f;  // a narrow view of the point straight below the light
  s.camera = cam;
  Rendered r = render_pt(s, 4, 4);
  const float expected = 0.5f / 3.14159265f * 8.0f / 4.0f;
  for (const glm::vec3& p : r.image.pixels) EXPECT_NEAR(p.x, expected, 2e-3f * expected);
}

TEST(PathTracer, SameSeedIsBitIdenticalAndThreadCountDoesNotMatter) {
  Scene scene = make_cornell_box();
  Accel accel(scene);
  LightSet lights(scene);
  RenderSettings settings;
  settings.method = MethodKind::PathTracer;
  FrameSetup frame;
  frame.camera = scene.camera_or_auto();
  frame.width = 48;
  frame.height = 40;
  FrameOptions one, two;
  one.threads = 1; one.tile_size = 7;
  two.threads = 2; two.tile_size = 16;
  Image a = render_offline({scene, accel, lights}, settings, frame, 4, one).image;
  Image b = render_offline({scene, accel, lights}, settings, frame, 4, two).image;
  EXPECT_TRUE(test::images_identical("pt-threads", a, b));
}

TEST(PathTracer, CornellMeanMatchesHighSampleRunAndErrorFallsWithSamples) {
  Scene scene = make_cornell_box();
  Image reference = render_pt(scene, 32, 1024, 7).image;
  Image low = render_pt(scene, 32, 16, 1).image;
  Image mid = render_pt(scene, 32, 128, 1).image;
  glm::vec3 mr = reference.mean(), ml = low.mean();
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(ml[c], mr[c], 0.03 * mr[c]) << "channel " << c;
  double e_low = rel_mse(low, reference), e_mid = rel_mse(mid, reference);
  EXPECT_LT(e_mid, 0.5 * e_low) << "relMSE 16 spp " << e_low << ", 128 spp " << e_mid;
  // The Cornell box is lit: the image is neither black nor blown out.
  EXPECT_GT(mr.x, 0.05f);
  EXPECT_LT(mr.x, 2.0f);
}


// Outgoing radiance at a diffuse point p (normal n, albedo a) from the
// tilted-light scene's quad by the midpoint rule over a 400 x 400 grid:
// a / pi x Le x integral of cos_p cos_light / r^2 over the quad.
double tilted_quad_direct(glm::dvec3 p, glm::dvec3 n, double albedo, double le) {
  const glm::dvec3 q0(3.168, 2.650, 3.310), e1 = glm::dvec3(3.310, 2.650, 3.168) - q0,
      e2 = glm::dvec3(3.290, 2.750, 3.432) - q0;
  const glm::dvec3 cross = glm::cross(e1, e2);
  const glm::dvec3 nl = glm::normalize(cross);
  const int k = 400;
  const double da = glm::length(cross) / (double(k) * k);
  double sum = 0.0;
  for (int i = 0; i < k; ++i)
    for (int j = 0; j < k; ++j) {
      const glm::dvec3 q = q0 + (i + 0.5) / k * e1 + (j + 0.5) / k * e2;
      const glm::dvec3 d = q - p;
      const double r2 = glm::dot(d, d), r = std::sqrt(r2);
      sum += std::max(0.0, glm::dot(n, d) / r) * std::max(0.0, -glm::dot(nl, d) / r) / r2 * da;
    }
  return albedo / M_PI * le * sum;
}

// pt with direct light only (path depth 1) at wall points that see the quad
// near its axis and at 75-80 degrees from its normal, where a sampler that
// loses grazing light shows nothing.
TEST(PathTracer, DirectLightFromTiltedQuadMatchesNumericalIntegration) {
  const Scene scene = make_tilted_light_scene();
  Accel accel(scene);
  LightSet lights(scene);
  RenderSettings settings;
  settings.method = MethodKind::PathTracer;
  settings.path_depth = 1;
  PathTracer pt({scene, accel, lights}, settings);
  const glm::dvec3 room_centre(2.0, 1.5, 2.0);
  struct Point { glm::dvec3 p, n; };
  for (const Point& w : {Point{{4.0, 2.26, 2.16}, {-1, 0, 0}}, Point{{2.06, 2.18, 4.0}, {0, 0, -1}},
                         Point{{4.0, 2.27, 2.57}, {-1, 0, 0}}}) {
    const double expected = tilted_quad_direct(w.p, w.n, 0.8, 100.0);
    const glm::vec3 dir = glm::normalize(glm::vec3(w.p - room_centre));
    const uint32_t n = 1 << 14;
    double sum = 0.0, sum2 = 0.0;
    RayCounts rays;
    for (uint32_t i = 0; i < n; ++i) {
      const double v = pt.radiance(Ray{glm::vec3(room_centre), dir}, i, 7u, rays).x;
      sum += v; sum2 += v * v;
    }
    const double mean = sum / n, error = std::sqrt(std::max(0.0, sum2 / n - mean * mean) / n);
    EXPECT_NEAR(mean, expected, 5.0 * error + 0.01 * expected)
        << "at (" << w.p.x << ", " << w.p.y << ", " << w.p.z << "), standard error " << error;
  }
}

}  // namespace
}  // namespace igi
