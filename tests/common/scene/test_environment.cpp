// A constant sky (Scene::environment, --environment): an open diffuse quad
// of albedo a under a sky of radiance L sees the whole hemisphere unoccluded,
// so it reflects exactly a L (a white furnace for one convex surface), and
// where camera rays leave the scene they see L itself. pt (light samples and
// escaping BSDF samples, weighted), igi (the sky's Directional VPLs) and
// lightcuts (the same VPLs as leaves) must all find it.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <regex>
#include <memory>

#include "lighting/lights.h"
#include "sampling/hash.h"
#include "sampling/warp.h"
#include "render/offline_render.h"
#include "scene/accel.h"
#include "scene/gltf_writer.h"
#include "scene/load_scene.h"
#include "support/image_compare.h"

namespace igi {
namespace {

constexpr float kAlbedo = 0.5f;
constexpr int kSize = 48;

Scene quad_under_sky(glm::vec3 sky, std::shared_ptr<const EnvironmentMap> map = nullptr) {
  Scene s;
  s.name = "quad-under-sky";
  s.positions = {{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}};  // facing +z, where the camera is
  s.triangles = {{0, 1, 2}, {0, 2, 3}};
  s.triangle_material = {0, 0};
  Material m;
  m.base_color = glm::vec3(kAlbedo);
  s.materials = {m};
  s.environment = sky;
  s.environment_map = std::move(map);
  s.camera = Camera{{0.0f, 0.0f, 4.0f}, {0.0f, 0.0f, -1.0f}};  // the quad fills the middle 70 % of the view
  s.validate();
  return s;
}

Image render(const Scene& scene, MethodKind method, int samples) {
  Accel accel(scene);
  LightSet lights(scene);
  RenderSettings settings;
  settings.method = method;
  settings.paths_per_set = 32;
  FrameSetup frame;
  frame.camera = scene.camera_or_auto();
  frame.width = frame.height = kSize;
  frame.seed = 3;
  return render_offline({scene, accel, lights}, settings, frame, samples, FrameOptions{}).image;
}

// Mean of the central half of the image (all on the quad), per channel averaged.
double central_mean(const Image& image) {
  double sum = 0.0;
  int n = 0;
  for (int y = kSize / 4; y < 3 * kSize / 4; ++y)
    for (int x = kSize / 4; x < 3 * kSize / 4; ++x, ++n) {
      const glm::vec3 c = image.pixels[size_t(y) * kSize + x];
      sum += (c.x + c.y + c.z) / 3.0;
    }
  return sum / n;
}

// A method, its passes and its relative tolerance on a mean.
struct Case {
  MethodKind method;
  int samples;
  double tolerance;
};

TEST(Environment, AnOpenQuadReflectsAlbedoTimesTheSkyAndTheSkyIsSeenWhereRaysLeave) {
  const Scene scene = quad_under_sky(glm::vec3(1.0f));
  for (const Case& c : {Case{MethodKind::PathTracer, 64, 0.02}, Case{MethodKind::Igi, 16, 0.03},
                        Case{MethodKind::Lightcuts, 4, 0.04}}) {
    SCOPED_TRACE(method_name(c.method));
    const Image image = render(scene, c.method, c.samples);
    EXPECT_NEAR(central_mean(image), kAlbedo, c.tolerance * kAlbedo);
    // The top row's middle lies beyond the quad (the auto camera frames its bounding sphere).
    const glm::vec3 sky = image.pixels[size_t(kSize / 2)];
    EXPECT_NEAR(sky.x, 1.0f, 1e-5f);
    EXPECT_NEAR(sky.z, 1.0f, 1e-5f);
  }
}

TEST(Environment, TheSkyScalesTheLightAndItsColourStaysInItsChannel) {
  const Image image = render(quad_under_sky(glm::vec3(2.0f, 0.0f, 0.5f)), MethodKind::Igi, 16);
  double r = 0.0, g = 0.0, b = 0.0;
  for (const glm::vec3& p : image.pixels) r += p.x, g += p.y, b += p.z;
  EXPECT_EQ(g, 0.0);
  EXPECT_NEAR(r / b, 4.0, 1e-3);  // every path carries the sky's colour unchanged: the same ratio
}

TEST(Environment, ASceneWithoutLightOrSkyNamesTheOptionAndABadSkyIsRefused) {
  try {
    quad_under_sky(glm::vec3(0.0f));
    FAIL() << "a lightless scene was accepted";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("--environment"), std::string::npos) << e.what();
  }
  EXPECT_THROW(quad_under_sky(glm::vec3(1.0f, -1.0f, 1.0f)), SceneError);
  EXPECT_THROW(quad_under_sky(glm::vec3(NAN, 1.0f, 1.0f)), SceneError);
  // The command line's sky replaces a built-in scene's (none) and lights it.
  EXPECT_EQ(load_scene("cornell", {SkyChoice{glm::vec3(0.25f)}}).environment, glm::vec3(0.25f));
  EXPECT_EQ(load_scene("cornell").environment, glm::vec3(0.0f));
}

// ---- Environment maps (scene/environment_map.h).

// 32 x 16 texels of a smooth sky and one sun texel far brighter than the rest.
Image sun_and_sky() {
  Image map(32, 16);
  for (int y = 0; y < map.height; ++y)
    for (int x = 0; x < map.width; ++x) map.at(x, y) = glm::vec3(0.3f + 0.02f * x, 0.4f, 0.3f + 0.05f * y);
  map.at(4, 5) = glm::vec3(200.0f, 180.0f, 150.0f);
  return map;
}

// Each sample's radiance and density are the map's at its direction, and
// luminance / pdf is the same for every sample (the map's integral): the
// density is luminance x solid angle, exactly. The sun is drawn as often as
// its share of that integral.
TEST(EnvironmentMap, SamplesFollowLuminanceTimesSolidAngleExactly) {
  const EnvironmentMap map(sun_and_sky(), 37.0f);
  const float integral = map.luminance_integral();
  const glm::vec3 sun = map.image().at(4, 5);
  int suns = 0;
  const int n = 20000;
  for (int i = 0; i < n; ++i) {
    const glm::vec2 u(float(hash(uint32_t(i), 1u) >> 8) * 0x1p-24f, float(hash(uint32_t(i), 2u) >> 8) * 0x1p-24f);
    const EnvironmentMap::Sample s = map.sample(u);
    ASSERT_GT(s.pdf, 0.0f);
    ASSERT_NEAR(glm::length(s.direction), 1.0f, 1e-5f);
    ASSERT_EQ(map.radiance(s.direction), s.radiance) << "sample " << i;
    ASSERT_NEAR(map.pdf(s.direction), s.pdf, 1e-4f * s.pdf) << "sample " << i;
    ASSERT_NEAR(luminance(s.radiance) / s.pdf, integral, 1e-3f * integral) << "sample " << i;
    suns += s.radiance == sun;
  }
  const double solid_angle = 2.0 * kPi / 32 * (std::cos(5 * kPi / 16) - std::cos(6 * kPi / 16));
  const double share = luminance(sun) * solid_angle / integral;
  EXPECT_NEAR(double(suns) / n, share, 4.0 * std::sqrt(share * (1 - share) / n));
}

// The map's middle column looks along -z; turned by 90 degrees about +y it looks along -x.
TEST(EnvironmentMap, TheMiddleLooksAlongMinusZAndRotationTurnsItAboutUp) {
  Image image(8, 4);
  image.at(4, 1) = image.at(4, 2) = glm::vec3(1.0f);  // either side of the horizon, just right of the middle
  const glm::vec3 ahead = glm::normalize(glm::vec3(0.05f, 0.0f, -1.0f));
  EXPECT_EQ(EnvironmentMap(image, 0.0f).radiance(ahead), glm::vec3(1.0f));
  EXPECT_EQ(EnvironmentMap(image, 0.0f).radiance(-ahead), glm::vec3(0.0f));
  EXPECT_EQ(EnvironmentMap(image, 90.0f).radiance(glm::vec3(-1.0f, 0.0f, -0.05f)), glm::vec3(1.0f));
  EXPECT_EQ(EnvironmentMap(image, 90.0f).radiance(ahead), glm::vec3(0.0f));
  EXPECT_EQ(EnvironmentMap(image, 0.0f).radiance(glm::vec3(0.05f, 3.0f, -1.0f)), glm::vec3(0.0f)) << "row 0 is up";
  EXPECT_THROW(EnvironmentMap(Image(1, 1), 0.0f), std::runtime_error);
  image.at(0, 0) = glm::vec3(-1.0f);
  EXPECT_THROW(EnvironmentMap(image, 0.0f), std::runtime_error);
}

// The quad (normal +z) under the sun-and-sky map: its irradiance sums each
// texel's radiance x the integral of cos over the texel's patch (the columns
// split at the quad's horizon, so no patch straddles it), and it reflects
// albedo / pi of that. pt (map-sampled light samples, MIS with BSDF samples
// that escape), igi (Directional VPLs drawn from the map) and lightcuts find it.
TEST(Environment, UnderAnEnvironmentMapTheQuadReflectsTheIrradianceOfItsTexels) {
  const Image texels = sun_and_sky();
  double expected = 0.0;
  for (int y = 0; y < texels.height; ++y)
    for (int x = 0; x < texels.width; ++x) {
      // Longitude phi = 2 pi (u - 1/2), polar angle theta from +y; +z is -sin(theta) cos(phi).
      const double phi0 = 2 * kPi * (double(x) / texels.width - 0.5), phi1 = phi0 + 2 * kPi / texels.width;
      const double t0 = kPi * y / texels.height, t1 = kPi * (y + 1) / texels.height;
      const double cos_integral = -(std::sin(phi1) - std::sin(phi0)) *
                                  ((t1 - t0) / 2 - (std::sin(2 * t1) - std::sin(2 * t0)) / 4);
      if (cos_integral <= 0.0) continue;  // below the quad's horizon
      const glm::vec3 c = texels.at(x, y);
      expected += (c.x + c.y + c.z) / 3.0 * cos_integral;
    }
  expected *= kAlbedo / kPi;
  const Scene scene = quad_under_sky(glm::vec3(1.0f), std::make_shared<const EnvironmentMap>(texels, 0.0f));
  for (const Case& c : {Case{MethodKind::PathTracer, 64, 0.02}, Case{MethodKind::Igi, 16, 0.03},
                        Case{MethodKind::Lightcuts, 4, 0.05}}) {
    SCOPED_TRACE(method_name(c.method));
    EXPECT_NEAR(central_mean(render(scene, c.method, c.samples)), expected, c.tolerance * expected);
  }
}

// A glTF scene may name its own map in its extras ({"environment": "sky.exr",
// "environment_rotation": 30}, beside the file): it loads as the same sky as
// --environment sky.exr --environment-rotation 30, and a map outside the
// scene's folder is refused.
TEST(Environment, AGltfSceneNamesItsOwnMapInItsExtras) {
  const std::string dir = test::output_path("extras-sky");
  std::filesystem::create_directories(dir);
  write_image(sun_and_sky(), dir + "/sky.exr");
  write_gltf(quad_under_sky(glm::vec3(1.0f)), dir + "/quad.gltf");
  std::ifstream in(dir + "/quad.gltf");
  const std::string json((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::regex sky("\"environment\"\\s*:\\s*\\[[^\\]]*\\]");
  ASSERT_TRUE(std::regex_search(json, sky)) << json;
  std::ofstream(dir + "/map.gltf") << std::regex_replace(json, sky, "\"environment\": \"sky.exr\", \"environment_rotation\": 30");
  std::ofstream(dir + "/outside.gltf") << std::regex_replace(json, sky, "\"environment\": \"../sky.exr\"");
  const Scene from_extras = load_scene(dir + "/map.gltf");
  ASSERT_TRUE(from_extras.environment_map);
  EXPECT_EQ(from_extras.environment, glm::vec3(1.0f));
  EXPECT_EQ(from_extras.environment_map->rotation(), 30.0f);
  const Scene from_options = load_scene(dir + "/quad.gltf", {SkyChoice{glm::vec3(1.0f), dir + "/sky.exr", 30.0f}});
  for (const glm::vec3 d : {glm::vec3(0, 0, -1), glm::vec3(0.3f, 0.5f, 0.8f), glm::vec3(-1, -0.2f, 0)})
    EXPECT_EQ(from_extras.sky(d), from_options.sky(d));
  write_image(sun_and_sky(), test::output_path("sky.exr"));
  EXPECT_THROW(load_scene(dir + "/outside.gltf"), SceneError);
}

// A map of ones is the constant sky of the same radiance, and a black map lights nothing.
TEST(Environment, AMapOfOnesIsTheConstantSkyAndABlackMapIsNoLight) {
  Image ones(16, 8);
  for (glm::vec3& p : ones.pixels) p = glm::vec3(1.0f);
  const EnvironmentMap map(ones, 12.0f);
  EXPECT_NEAR(map.integral().x, 4.0f * kPi, 1e-4f);
  const Image image = render(quad_under_sky(glm::vec3(0.5f), std::make_shared<const EnvironmentMap>(ones, 12.0f)),
                             MethodKind::PathTracer, 64);
  EXPECT_NEAR(central_mean(image), 0.5 * kAlbedo, 0.02 * kAlbedo);
  EXPECT_THROW(quad_under_sky(glm::vec3(1.0f), std::make_shared<const EnvironmentMap>(Image(16, 8), 0.0f)),
               SceneError);
}

}  // namespace
}  // namespace igi
