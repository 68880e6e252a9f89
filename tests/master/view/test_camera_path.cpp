// --camera-path (issue 26.3): orbit turns once over the run about a pivot the
// camera keeps looking at, swing turns to either side and back, and no frame
// of the README's example leaves the scene (the old orbit wrote 32 black
// frames of 100: it turned 0.02 rad a frame out of the Cornell box).
#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>

#include "cli/option_checks.h"
#include "view/frame_plan.h"
#include "image/image.h"
#include "options/master_options.h"
#include "scene/load_scene.h"
#include "support/image_compare.h"
#include "support/process.h"

namespace igi {
namespace {

constexpr double kPi = 3.14159265358979323846;

CameraPath path(CameraPath::Kind kind, int frames) {
  CameraPath p;
  p.kind = kind;
  p.frames = frames;
  return p;
}

// Where the line of sight passes nearest to `point`, and how far from it.
float miss_distance(const Camera& c, glm::vec3 point) {
  const glm::vec3 f = glm::normalize(c.forward);
  const glm::vec3 to = point - c.position;
  return glm::length(to - glm::dot(to, f) * f);
}

TEST(CameraPath, OrbitTurnsOnceOverTheRunAboutAPivotItKeepsLookingAt) {
  const Scene scene = load_scene("cornell");
  const RenderOptions render;
  const CameraPath orbit = path(CameraPath::Kind::Orbit, 100);
  const Camera start = plan_frame(render, orbit, scene, 0, false).camera;
  const Camera home = scene.camera_or_auto();
  EXPECT_EQ(start.position, home.position) << "frame 0 is the scene's camera";
  // The pivot: on the line of sight, level with the scene's centre along it.
  const glm::vec3 f = glm::normalize(home.forward);
  const glm::vec3 pivot = home.position + glm::dot(scene.bounds().center() - home.position, f) * f;
  const float radius = glm::length(home.position - pivot);
  for (int i : {13, 25, 50, 77}) {
    const Camera c = plan_frame(render, orbit, scene, i, false).camera;
    EXPECT_NEAR(glm::length(c.position - pivot), radius, 1e-4f) << "frame " << i;
    EXPECT_NEAR(c.position.y, home.position.y, 1e-5f) << "about the vertical axis";
    EXPECT_LT(miss_distance(c, pivot), 1e-4f) << "frame " << i << " looks at the pivot";
  }
  EXPECT_NEAR(camera_path_angle(orbit, 25), kPi / 2, 1e-9) << "a quarter turn at a quarter of the run";
  const Camera full = plan_frame(render, orbit, scene, 100, false).camera;
  EXPECT_LT(glm::length(full.position - home.position), 1e-4f) << "a full turn over the run";
  CameraPath stepped = orbit;
  stepped.orbit_step_degrees = 3.0;
  EXPECT_NEAR(camera_path_angle(stepped, 10), 30.0 * kPi / 180.0, 1e-9) << "--orbit-step 3: degrees a frame";
}

TEST(CameraPath, SwingStaysWithinItsAngleAndComesBack) {
  CameraPath swing = path(CameraPath::Kind::Swing, 40);
  swing.swing_degrees = 15.0;
  double widest = 0.0;
  for (int i = 0; i <= 40; ++i) widest = std::max(widest, std::abs(camera_path_angle(swing, i)));
  EXPECT_NEAR(widest, 15.0 * kPi / 180.0, 1e-9);
  EXPECT_NEAR(camera_path_angle(swing, 10), 15.0 * kPi / 180.0, 1e-9) << "the widest at a quarter of the run";
  EXPECT_NEAR(camera_path_angle(swing, 30), -15.0 * kPi / 180.0, 1e-9) << "then the other side";
  EXPECT_NEAR(camera_path_angle(swing, 40), 0.0, 1e-9) << "and back";
  EXPECT_EQ(camera_path_angle(path(CameraPath::Kind::None, 40), 17), 0.0);
}

TEST(CameraPath, OptionsNeedAPathAndFramesAndResumeWhereTheFullRunStood) {
  const MasterOptions resumed = parse_master_options(
      {"--workers", "0", "--frames", "40", "--first-frame", "60", "--camera-path", "orbit", "--orbit-step", "2"});
  EXPECT_EQ(resumed.camera_path.kind, CameraPath::Kind::Orbit);
  EXPECT_EQ(resumed.camera_path.frames, 100) << "a full turn over --first-frame + --frames";
  EXPECT_EQ(resumed.camera_path.orbit_step_degrees, 2.0);
  auto error_of = [](std::vector<std::string> args) {
    try {
      parse_master_options(args);
    } catch (const cli::OptionError& e) {
      return std::string(e.what());
    }
    return std::string("(accepted)");
  };
  EXPECT_NE(error_of({"--workers", "0", "--frames", "4", "--orbit-step", "2"}).find("--orbit-step: needs --camera-path orbit"),
            std::string::npos);
  EXPECT_NE(error_of({"--workers", "0", "--frames", "4", "--camera-path", "orbit", "--swing", "9"})
                .find("--swing: needs --camera-path swing"), std::string::npos);
  EXPECT_NE(error_of({"--workers", "0", "--camera-path", "swing"}).find("--camera-path: headless only"),
            std::string::npos);
  EXPECT_NE(error_of({"--workers", "0", "--frames", "4", "--camera-path", "spiral"}).find("spiral"), std::string::npos);
}

// The README's example, at a small size: every frame keeps most of the first frame's light.
TEST(CameraPath, NoFrameOfTheReadmeExampleIsBlack) {
  const std::string out = test::output_path("swing.exr");
  const test::RunResult r = test::run(std::string(IGI_MASTER_BINARY) + " --workers 1 --worker-threads 2 --frames 100 "
                                      "--camera-path swing --size 32x24 --vpl-paths 4 --aa 1 --quiet -o " + out, 180);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  auto luminance = [](int i) {
    char name[32];
    std::snprintf(name, sizeof name, "swing-%04d.exr", i);
    const glm::vec3 m = read_image(test::output_path(name)).mean();
    return (m.x + m.y + m.z) / 3.0f;
  };
  const float first = luminance(0);
  ASSERT_GT(first, 0.05f);
  float darkest = first;
  for (int i = 1; i < 100; ++i) darkest = std::min(darkest, luminance(i));
  EXPECT_GT(darkest, 0.5f * first) << "a frame along the path lost half the light of the first";
}

}  // namespace
}  // namespace igi
