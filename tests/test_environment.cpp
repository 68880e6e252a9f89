// A constant sky (Scene::environment, --environment): an open diffuse quad
// of albedo a under a sky of radiance L sees the whole hemisphere unoccluded,
// so it reflects exactly a L (a white furnace for one convex surface), and
// where camera rays leave the scene they see L itself. pt (light samples and
// escaping BSDF samples, weighted), igi (the sky's Directional VPLs) and
// lightcuts (the same VPLs as leaves) must all find it.
#include <gtest/gtest.h>

#include "lighting/lights.h"
#include "render/offline_render.h"
#include "scene/accel.h"
#include "scene/load_scene.h"

namespace igi {
namespace {

constexpr float kAlbedo = 0.5f;
constexpr int kSize = 48;

Scene quad_under_sky(glm::vec3 sky) {
  Scene s;
  s.name = "quad-under-sky";
  s.positions = {{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}};  // facing +z, where the auto camera is
  s.triangles = {{0, 1, 2}, {0, 2, 3}};
  s.triangle_material = {0, 0};
  Material m;
  m.base_color = glm::vec3(kAlbedo);
  s.materials = {m};
  s.environment = sky;
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

TEST(Environment, AnOpenQuadReflectsAlbedoTimesTheSkyAndTheSkyIsSeenWhereRaysLeave) {
  const Scene scene = quad_under_sky(glm::vec3(1.0f));
  struct Case {
    MethodKind method;
    int samples;
    double tolerance;
  };
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
  EXPECT_EQ(load_scene("cornell", nullptr, glm::vec3(0.25f)).environment, glm::vec3(0.25f));
  EXPECT_EQ(load_scene("cornell").environment, glm::vec3(0.0f));
}

}  // namespace
}  // namespace igi
