// Dynamic scenes: glTF animation sampled as the specification says, a posed
// scene equal bit for bit to the same pose loaded static, posing that touches
// only what moves, and master + workers equal to one process over an
// animated sequence with a worker killed.
#include <bit>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "render/scene_state.h"
#include "scene/builtin_scenes.h"
#include "scene/gltf_loader.h"
#include "image/metrics.h"
#include "support/animated_gltf.h"
#include "support/image_compare.h"
#include "support/process.h"
#include "support/render_fixture.h"
#include "support/stats_file.h"
#include "support/xvfb.h"

namespace igi {
namespace {

namespace fs = std::filesystem;

AnimationChannel channel(AnimationPath path, Interpolation interpolation, std::vector<double> times,
                         std::vector<glm::dvec4> values) {
  AnimationChannel c;
  c.path = path;
  c.interpolation = interpolation;
  c.times = std::move(times);
  c.values = std::move(values);
  return c;
}

TEST(Animation, SamplersInterpolateAsTheGltfSpecificationSays) {
  const AnimationChannel linear = channel(AnimationPath::Translation, Interpolation::Linear, {1.0, 3.0},
                                          {glm::dvec4(0.0), glm::dvec4(4.0, -2.0, 0.0, 0.0)});
  EXPECT_EQ(linear.sample(2.5), glm::dvec4(3.0, -1.5, 0.0, 0.0));
  EXPECT_EQ(linear.sample(0.0), glm::dvec4(0.0)) << "held before the first key";
  EXPECT_EQ(linear.sample(9.0), glm::dvec4(4.0, -2.0, 0.0, 0.0)) << "held after the last key";

  AnimationChannel step = linear;
  step.interpolation = Interpolation::Step;
  EXPECT_EQ(step.sample(2.9), glm::dvec4(0.0));
  EXPECT_EQ(step.sample(3.0), glm::dvec4(4.0, -2.0, 0.0, 0.0));

  // Hermite with zero tangents: smoothstep between the values.
  const AnimationChannel cubic =
      channel(AnimationPath::Translation, Interpolation::CubicSpline, {0.0, 2.0},
              {glm::dvec4(0.0), glm::dvec4(0.0), glm::dvec4(0.0), glm::dvec4(0.0), glm::dvec4(8.0, 0, 0, 0), glm::dvec4(0.0)});
  EXPECT_DOUBLE_EQ(cubic.sample(1.0).x, 4.0);
  EXPECT_DOUBLE_EQ(cubic.sample(0.5).x, 8.0 * (3 * 0.0625 - 2 * 0.015625));
  // An out-tangent bends the curve: slope at the key is the tangent.
  AnimationChannel bent = cubic;
  bent.values[2] = glm::dvec4(4.0, 0, 0, 0);
  EXPECT_NEAR((bent.sample(1e-6).x - bent.sample(0.0).x) / 1e-6, 4.0, 1e-4);

  // Rotation slerps: halfway from identity to 90 degrees about y is 45 degrees.
  const double h = std::sqrt(0.5);
  const AnimationChannel turn = channel(AnimationPath::Rotation, Interpolation::Linear, {0.0, 1.0},
                                        {glm::dvec4(0, 0, 0, 1), glm::dvec4(0, h, 0, h)});
  const glm::dvec4 q = turn.sample(0.5);
  EXPECT_NEAR(q.y, std::sin(M_PI / 8), 1e-12);
  EXPECT_NEAR(q.w, std::cos(M_PI / 8), 1e-12);
}

LoadedScene load_json(const nlohmann::json& doc, const std::string& name) {
  const std::string text = doc.dump();
  return load_gltf_memory({reinterpret_cast<const uint8_t*>(text.data()), text.size()}, name);
}

template <typename T>
bool same_bits(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0;
}

Image render(const SceneState& state, double time, uint32_t seed = 1) {
  FrameSetup f = test::camera_frame(state.scene(), 96, 72, seed);
  f.pose.time = time;
  RenderSettings s;
  s.method = MethodKind::Igi;
  s.paths_per_set = 8;
  return render_offline(state.context(), s, f, 1, FrameOptions{}).image;
}

TEST(Animation, SceneAnimatedToATimeEqualsTheSamePoseLoadedStaticBitForBit) {
  const nlohmann::json doc = test::animated_document();
  LoadedScene animated = load_json(doc, "animated.gltf");
  EXPECT_TRUE(animated.warnings.empty()) << animated.warnings.front();
  ASSERT_TRUE(animated.scene.animation);
  EXPECT_EQ(animated.scene.animation->nodes.size(), 3u) << "mover, its child and the lamp move";
  EXPECT_EQ(animated.scene.animation->duration, 2.0);
  for (const double t : {0.0, 0.7, 1.6, 2.5}) {
    SCOPED_TRACE("t = " + std::to_string(t));
    SceneState moving(animated.scene);
    moving.set_pose(ScenePose{t, glm::vec3(0.0f)});
    SceneState still(load_json(test::posed_copy(doc, *animated.scene.animation, t), "posed.gltf").scene);
    still.set_pose(ScenePose{});
    const Scene& a = moving.scene();
    const Scene& b = still.scene();
    EXPECT_TRUE(same_bits(a.positions, b.positions));
    EXPECT_TRUE(same_bits(a.normals, b.normals)) << "normals follow their nodes";
    EXPECT_TRUE(same_bits(a.triangles, b.triangles));
    ASSERT_EQ(a.lights.size(), 1u);
    EXPECT_EQ(a.lights[0].position, b.lights[0].position) << "the lamp rides on the mover";
    EXPECT_TRUE(test::images_identical("animated-vs-posed-" + std::to_string(int(10 * t)), render(moving, t),
                                       render(still, 0.0)));
  }
  // And the animation does move things: two times, two images.
  SceneState state(animated.scene);
  const Image early = render(state, 0.2);
  state.set_pose(ScenePose{1.2, glm::vec3(0.0f)});
  EXPECT_FALSE(test::images_identical("animated-moves", early, render(state, 1.2)));
}

// The mean chord (the clamp's length scale) after pose after pose on one BVH,
// whose update re-sums areas from the first moving triangle only and traces
// its rays on TBB's threads, equals that of each pose loaded static.
TEST(Animation, MeanChordOfAPoseSequenceEqualsEachPoseLoadedStatic) {
  const nlohmann::json doc = test::animated_document();
  LoadedScene animated = load_json(doc, "animated.gltf");
  ASSERT_TRUE(animated.scene.animation);
  SceneState moving(animated.scene);
  std::vector<float> chords;
  for (const double t : {0.7, 1.6, 0.0, 2.5, 0.7}) {
    SCOPED_TRACE("t = " + std::to_string(t));
    moving.set_pose(ScenePose{t, glm::vec3(0.0f)});
    SceneState still(load_json(test::posed_copy(doc, *animated.scene.animation, t), "posed.gltf").scene);
    still.set_pose(ScenePose{});
    EXPECT_EQ(std::bit_cast<uint32_t>(moving.accel().mean_chord()), std::bit_cast<uint32_t>(still.accel().mean_chord()));
    chords.push_back(moving.accel().mean_chord());
  }
  EXPECT_NE(chords[0], chords[1]) << "the chord follows the pose";
  EXPECT_EQ(chords[0], chords[4]);
}

bool same_camera(const Camera& a, const Camera& b) {
  return std::memcmp(&a.position, &b.position, sizeof a.position) == 0 &&
         std::memcmp(&a.forward, &b.forward, sizeof a.forward) == 0 && std::memcmp(&a.up, &b.up, sizeof a.up) == 0 &&
         a.vfov == b.vfov;
}

// An animated camera stands, at each time, where the statically posed file
// puts it (the loader's arithmetic), keeps its field of view, and moves; a
// camera the user places (a bookmark) is not moved by the animation.
TEST(Animation, AnimatedCameraStandsWhereThePosedFilePutsIt) {
  const nlohmann::json doc = test::animated_document(true);
  LoadedScene animated = load_json(doc, "camera.gltf");
  ASSERT_TRUE(animated.scene.animation && animated.scene.camera);
  EXPECT_TRUE(animated.warnings.empty()) << animated.warnings.front();
  EXPECT_GE(animated.scene.animation->camera_node, 0);
  for (const double t : {0.0, 0.45, 1.3, 2.0, 5.0}) {
    SCOPED_TRACE("t = " + std::to_string(t));
    const LoadedScene still = load_json(test::posed_copy(doc, *animated.scene.animation, t), "posed-camera.gltf");
    ASSERT_TRUE(still.scene.camera);
    EXPECT_TRUE(same_camera(scene_camera(animated.scene, t), *still.scene.camera));
    EXPECT_EQ(scene_camera(animated.scene, t).vfov, 0.9f);
  }
  const Camera early = scene_camera(animated.scene, 0.2), late = scene_camera(animated.scene, 1.7);
  EXPECT_GT(glm::length(late.position - early.position), 0.5f) << "the camera flies";
  EXPECT_GT(glm::length(late.forward - early.forward), 0.1f) << "and turns";
  // The mover's camera-less document: its camera stays.
  const LoadedScene fixed = load_json(test::animated_document(), "fixed.gltf");
  EXPECT_TRUE(same_camera(scene_camera(fixed.scene, 0.0), scene_camera(fixed.scene, 1.7)));
  Scene placed = animated.scene;
  place_camera(placed, early);
  EXPECT_TRUE(same_camera(scene_camera(placed, 1.7), early)) << "a placed camera does not follow the animation";
  EXPECT_TRUE(same_camera(scene_camera(animated.scene, 1.7), late)) << "the loaded scene's animation is not changed";
}

TEST(Animation, PosingTouchesOnlyWhatMovesAndComesBack) {
  SceneState state(make_cornell_blob_moving(2000));
  const std::vector<glm::vec3> rest = state.scene().positions;
  const Image at_rest = render(state, 0.0);
  state.set_pose(ScenePose{0.5, glm::vec3(0.0f)});
  std::vector<bool> moving(rest.size(), false);
  for (const DynamicPart& part : state.scene().animation->parts)
    for (uint32_t v : part.vertices) moving[v] = true;
  size_t moved = 0;
  for (size_t v = 0; v < rest.size(); ++v) {
    if (!moving[v]) {
      EXPECT_EQ(state.scene().positions[v], rest[v]) << "static vertex " << v << " moved";
    }
    moved += state.scene().positions[v] != rest[v];
  }
  EXPECT_GT(moved, 1000u) << "the blob moved";
  state.set_pose(ScenePose{0.0, glm::vec3(0.0f)});
  EXPECT_TRUE(test::images_identical("posed-back", render(state, 0.0), at_rest)) << "posing is a function of the pose";
}

TEST(Animation, MovedLightsLightTheSceneFromTheirNewPlace) {
  SceneState state(make_cornell_box());
  const Image home = render(state, 0.0);
  ASSERT_TRUE(state.scene().animation) << "the area light is a group the window can move";
  const glm::vec3 light_before = state.scene().positions[state.scene().animation->parts[0].vertices[0]];
  state.set_pose(ScenePose{0.0, glm::vec3(0.2f, -0.1f, 0.0f)});
  const glm::vec3 light_after = state.scene().positions[state.scene().animation->parts[0].vertices[0]];
  EXPECT_NEAR(light_after.x - light_before.x, 0.2f, 1e-6f);
  FrameSetup f = test::camera_frame(state.scene(), 96, 72, 1);
  f.pose = *state.pose();
  RenderSettings s;
  s.method = MethodKind::Igi;
  s.paths_per_set = 8;
  const Image moved = render_offline(state.context(), s, f, 1, FrameOptions{}).image;
  // Moved towards +x (the red wall) and down: the left half brightens.
  double left_home = 0, left_moved = 0;
  for (int y = 0; y < 72; ++y)
    for (int x = 0; x < 30; ++x) {
      left_home += test::luminance(home.at(x, y));
      left_moved += test::luminance(moved.at(x, y));
    }
  EXPECT_GT(left_moved, 1.1 * left_home);
}

// One process renders frame i at time i / 30 (igi-master's default step).
TEST(Distributed, AnimatedSequenceMatchesOneProcessWithAWorkerKilled) {
  const fs::path file = fs::path(test::output_path("dist-animated.gltf"));
  const nlohmann::json doc = test::animated_document();
  std::ofstream(file) << doc.dump();
  const std::string out = test::output_path("dist-anim.exr"), stats = test::output_path("dist-anim.jsonl");
  const int frames = 8;
  auto r = test::run(std::string(IGI_MASTER_BINARY) + " --scene " + file.string() +
                     " --method igi --vpl-paths 8 --size 96x72 --tile 16 --worker-threads 2 --workers 2 --min-workers 2 --frames " +
                     std::to_string(frames) + " --heartbeat-ms 50 --timeout-ms 300 --test-kill-worker-after 12 -o " +
                     out + " --stats " + stats);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const nlohmann::json last = test::read_stats(stats)["frames"][frames - 1];
  int rendering = 0;  // the killed worker may still be listed, with no tiles
  for (const auto& [name, w] : last["workers"].items())
    rendering += w["tiles"].get<int>() > 0;
  EXPECT_EQ(rendering, 1) << "one worker was killed";
  SceneState state(load_gltf(file.string()).scene);
  Image previous;
  for (int i = 0; i < frames; ++i) {
    char name[64];
    std::snprintf(name, sizeof name, "dist-anim-%04d.exr", i);
    FrameSetup f = test::camera_frame(state.scene(), 96, 72, 1);
    f.pose.time = i / 30.0;
    state.set_pose(f.pose);
    RenderSettings s;
    s.method = MethodKind::Igi;
    s.paths_per_set = 8;
    const Image one = render_offline(state.context(), s, f, 1, FrameOptions{}).image;
    EXPECT_TRUE(test::images_identical(name, read_image(test::output_path(name)), one));
    if (i > 0) {
      EXPECT_FALSE(test::images_identical(std::string("moves-") + name, previous, one));
    }
    previous = one;
  }
}

// --time, --time-step and --loop place the frames; --move-lights moves the
// lights; igi-render --time renders one frame at a time. All as one process.
TEST(Distributed, SceneTimesAndMovedLightsReachTheWorkers) {
  const std::string file = test::output_path("dist-times.gltf");
  std::ofstream(file) << test::animated_document(true).dump();  // the camera flies too
  const std::string out = test::output_path("dist-times.exr"), one = test::output_path("render-at-time.exr");
  const std::string common = " --scene " + file + " --method igi --vpl-paths 8 --size 96x72 --move-lights 0.2,-0.3,0.1";
  auto r = test::run(std::string(IGI_MASTER_BINARY) + common +
                     " --tile 16 --worker-threads 2 --workers 2 --frames 3 --time 1.9 --time-step 0.1 --loop -o " + out);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  r = test::run(std::string(IGI_RENDER_BINARY) + common + " --quiet --time 1.9 -o " + one);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  SceneState state(load_gltf(file).scene);
  const double times[] = {1.9, 0.0, 0.1};  // 2.0 and 2.1 wrapped into the 2 s animation
  for (int i = 0; i < 3; ++i) {
    FrameSetup f = test::camera_frame(state.scene(), 96, 72, 1);
    f.pose = ScenePose{scene_time(1.9, 0.1, uint64_t(i), true, 2.0), glm::vec3(0.2f, -0.3f, 0.1f)};
    EXPECT_NEAR(f.pose.time, times[i], 1e-12);
    f.camera = scene_camera(state.scene(), f.pose.time);
    state.set_pose(f.pose);
    RenderSettings s;
    s.method = MethodKind::Igi;
    s.paths_per_set = 8;
    const Image expected = render_offline(state.context(), s, f, 1, FrameOptions{}).image;
    char name[64];
    std::snprintf(name, sizeof name, "dist-times-%04d.exr", i);
    EXPECT_TRUE(test::images_identical(name, read_image(test::output_path(name)), expected));
    if (i == 0) {
      EXPECT_TRUE(test::images_identical("render-at-time", read_image(one), expected));
    }
  }
}

// Under Xvfb: the window shows an animation frame by frame, each frame the
// very frame a headless run writes at that time, from where the flying
// camera stands then (the user has not moved it). Which frame is third on
// screen depends on timing (frames planned before a view change are
// dropped, and the animation's clock runs on), so the screenshot is looked
// up among the headless frames: it is one of them, and at least frame 2.
TEST(Window, AnAnimatedSceneIsShownFrameByFrameAsAHeadlessRunWritesIt) {
  IGI_NEED_XVFB();
  const std::string file = test::output_path("window-animated.gltf");
  std::ofstream(file) << test::animated_document(true).dump();  // the window follows the flying camera
  const std::string common = " --workers 2 --worker-threads 1 --scene " + file +
                             " --method igi --vpl-paths 8 --size 160x120 --quiet --ev 0";  // the window would meter
  const std::string shot = test::output_path("window-animated.png");
  fs::remove(shot);
  const std::string window = std::string("timeout -s KILL 60 xvfb-run -a -s '-screen 0 640x480x24' ") +
                             IGI_MASTER_BINARY + common + " --panel off --screenshot " + shot +
                             " --screenshot-after 3 >/dev/null 2>&1";
  ASSERT_EQ(std::system(window.c_str()), 0) << window;
  const int frames = 16;
  const std::string headless = std::string(IGI_MASTER_BINARY) + common + " --frames " + std::to_string(frames) +
                               " -o " + test::output_path("window-animated-headless.png") + " >/dev/null 2>&1";
  ASSERT_EQ(std::system(headless.c_str()), 0) << headless;
  const Image shown = read_image(shot);
  int best = -1;
  double best_error = 1e30;
  for (int k = 0; k < frames; ++k) {
    char name[64];
    std::snprintf(name, sizeof name, "window-animated-headless-%04d.png", k);
    const double error = max_abs_error(shown, read_image(test::output_path(name)));
    if (error < best_error) best = k, best_error = error;
  }
  EXPECT_LT(best_error, 0.01) << "the window shows frame " << best << " of the headless run, or none";
  EXPECT_GE(best, 2) << "the third frame shown stands at least two frames into the animation";
}

}  // namespace
}  // namespace igi
