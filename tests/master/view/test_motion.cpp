// A view that moves: the history carried through camera moves
// (common/render/view_history.h), the frame-time budget (master/view/frame_budget.h),
// what the session plans and cancels (master/view/motion_planner.h) and the
// window's frame rate. No sockets, no window.
#include <gtest/gtest.h>

#include <cstring>

#include "view/frame_budget.h"
#include "view/frame_rate.h"
#include "view/motion_planner.h"
#include "render/accumulator.h"
#include "scene/animation.h"
#include "scene/builtin_scenes.h"
#include "scene/camera_rays.h"
#include "render/view_history.h"

namespace igi {
namespace {

constexpr int kW = 64, kH = 48;

// The surfaces of a wall z = -distance (normal +z) seen from `camera`.
std::vector<PixelSurface> wall_surfaces(const Camera& camera, int width, int height, float distance) {
  const CameraBasis basis(camera, width, height);
  std::vector<PixelSurface> out(size_t(width) * height);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const glm::vec3 d = glm::normalize(basis.direction(float(x) + 0.5f, float(y) + 0.5f));
      PixelSurface& s = out[size_t(y) * width + x];
      s.depth = (camera.position.z + distance) / -d.z;
      s.normal[2] = 127;
    }
  return out;
}

// Pixel (x, y) holds (x, y, tag): exact in floats, and says where it came from.
Image tagged(int width, int height, float tag) {
  Image image(width, height);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) image.at(x, y) = glm::vec3(float(x), float(y), tag);
  return image;
}

// The camera moved sideways by `pixels` pixels' worth at the wall's distance.
Camera shifted(const Camera& c, int pixels, float distance, int height) {
  Camera moved = c;
  moved.position.x += float(pixels) * distance * 2.0f * std::tan(0.5f * c.vfov) / float(height);
  return moved;
}

TEST(ViewHistory, AStillCameraEqualsPlainAccumulationBitForBit) {
  ViewHistory history(kW, kH, 16);
  Accumulator plain(kW, kH);
  const Camera camera;
  const std::vector<PixelSurface> surfaces = wall_surfaces(camera, kW, kH, 3.0f);
  for (int frame = 0; frame < 7; ++frame) {
    Image image(kW, kH);
    for (size_t i = 0; i < image.pixels.size(); ++i)
      image.pixels[i] = glm::vec3(std::sin(float(i * 7 + frame)), 0.3f / float(frame + 1), float(i % 5) * 0.1f);
    history.add(image, surfaces, camera);
    plain.add(image, 1.0);
  }
  const Image a = history.resolve(), b = plain.resolve();
  ASSERT_EQ(a.pixels.size(), b.pixels.size());
  EXPECT_EQ(std::memcmp(a.pixels.data(), b.pixels.data(), a.pixels.size() * sizeof(glm::vec3)), 0);
  EXPECT_DOUBLE_EQ(history.weight(), 7.0);
  EXPECT_DOUBLE_EQ(history.carried(), 1.0);
}

TEST(ViewHistory, ACameraTranslatedOverAWallCarriesEveryPixelExactly) {
  constexpr float kDistance = 3.0f;
  constexpr int kShift = 5;
  const Camera before;
  const Camera after = shifted(before, kShift, kDistance, kH);
  ViewHistory history(kW, kH, 16);
  history.add(tagged(kW, kH, 1.0f), wall_surfaces(before, kW, kH, kDistance), before);
  history.add(tagged(kW, kH, 3.0f), wall_surfaces(after, kW, kH, kDistance), after);
  const Image image = history.resolve();
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      // The wall point at new pixel x stood at old pixel x + kShift: both frames average there.
      const glm::vec3 expected = x + kShift < kW ? glm::vec3(0.5f * float(2 * x + kShift), float(y), 2.0f)
                                                 : glm::vec3(float(x), float(y), 3.0f);  // off the old image
      ASSERT_EQ(image.at(x, y), expected) << "pixel " << x << ", " << y;
    }
  EXPECT_NEAR(history.carried(), double(kW - kShift) / kW, 1e-12);
}

// Surfaces may come from rays off the pixels' centres (a G-buffer's first
// sub-sample at the frame's jitter, core/pixel_surface.h): the history
// places each point on its surface's plane where the pixel's centre ray
// meets it. On a floor seen at a grazing angle the depth changes fast
// across a pixel, so a point placed along the centre's ray at the depth an
// offset ray found lies off the floor, by a share of its distance that grows
// with the pixels' angle; two frames of different jitters disagree by twice
// that: past the plane test's 1 % in an image of 16 x 12 pixels (0.07 rad a
// pixel; at 640 x 480 it would pass, the error ten times smaller).
TEST(ViewHistory, SurfacesFoundOffThePixelCentresCarryWhereTheirRaysSay) {
  constexpr int kW = 16, kH = 12;
  auto floor_surfaces = [&](const Camera& camera, glm::vec2 offset) {  // the floor y = -1, through `offset`
    const CameraBasis basis(camera, kW, kH);
    std::vector<PixelSurface> out(size_t(kW) * kH);
    for (int y = 0; y < kH; ++y)
      for (int x = 0; x < kW; ++x) {
        const glm::vec3 d = glm::normalize(basis.direction(float(x) + offset.x, float(y) + offset.y));
        if (d.y >= -1e-3f) continue;  // the sky
        PixelSurface& s = out[size_t(y) * kW + x];
        s.depth = (camera.position.y + 1.0f) / -d.y;
        s.normal[1] = 127;
      }
    return out;
  };
  Camera before;
  before.position = glm::vec3(0.0f);
  before.forward = glm::normalize(glm::vec3(0.0f, -0.3f, -1.0f));
  Camera after = before;
  after.position.x += 0.02f;
  const glm::vec2 jitter_before(0.15f, 0.9f), jitter_after(0.8f, 0.1f);
  double carried[2];
  for (int told = 0; told < 2; ++told) {
    ViewHistory history(kW, kH, 16);
    history.add(tagged(kW, kH, 1.0f), floor_surfaces(before, jitter_before), before, 1.0,
                told ? jitter_before : glm::vec2(0.5f));
    history.add(tagged(kW, kH, 3.0f), floor_surfaces(after, jitter_after), after, 1.0,
                told ? jitter_after : glm::vec2(0.5f));
    carried[told] = history.carried();
  }
  EXPECT_GT(carried[1], 0.7) << "most of the image is floor, and it carries";
  EXPECT_LT(carried[0], 0.5 * carried[1]) << "placed along the centres' rays, the points leave the floor";
}

TEST(ViewHistory, DisoccludedAndViewDependentPixelsStartOver) {
  constexpr float kDistance = 3.0f;
  const Camera before;
  const Camera after = shifted(before, 4, kDistance, kH);
  std::vector<PixelSurface> old_surfaces = wall_surfaces(before, kW, kH, kDistance);
  for (int y = 10; y < 20; ++y)  // something stood in front of the wall here: its pixels were nearer
    for (int x = 10; x < 20; ++x) old_surfaces[size_t(y) * kW + x].depth *= 0.5f;
  std::vector<PixelSurface> new_surfaces = wall_surfaces(after, kW, kH, kDistance);
  for (int x = 0; x < kW; ++x) new_surfaces[size_t(30) * kW + x].flags = PixelSurface::kViewDependent;  // glossy row
  for (int x = 0; x < kW; ++x) new_surfaces[size_t(40) * kW + x].depth = 0.0f;                          // the sky
  ViewHistory history(kW, kH, 16);
  history.add(tagged(kW, kH, 1.0f), old_surfaces, before);
  history.add(tagged(kW, kH, 3.0f), new_surfaces, after);
  const Image image = history.resolve();
  auto started_over = [&](int x, int y) { return image.at(x, y).z == 3.0f; };
  for (int y = 10; y < 20; ++y)
    for (int x = 6; x < 16; ++x) EXPECT_TRUE(started_over(x, y)) << "disoccluded pixel " << x << ", " << y;
  for (int x = 0; x < kW; ++x) {
    EXPECT_TRUE(started_over(x, 30)) << "view-dependent pixel " << x;
    EXPECT_TRUE(started_over(x, 40)) << "sky pixel " << x;
  }
  EXPECT_FALSE(started_over(30, 5)) << "a wall pixel seen before keeps its history";
}

TEST(ViewHistory, ACarriedPixelKeepsAtMostKFramesOfHistory) {
  constexpr float kDistance = 3.0f;
  const Camera before;
  const Camera after = shifted(before, 1, kDistance, kH);
  ViewHistory history(kW, kH, 4);
  for (int i = 0; i < 12; ++i) history.add(tagged(kW, kH, 0.0f), wall_surfaces(before, kW, kH, kDistance), before);
  history.add(tagged(kW, kH, 10.0f), wall_surfaces(after, kW, kH, kDistance), after);
  // 4 frames of tag 0 against one of tag 10, not 12 against one.
  EXPECT_FLOAT_EQ(history.resolve().at(20, 20).z, 2.0f);
  EXPECT_FLOAT_EQ(history.resolve().at(kW - 1, 20).z, 10.0f) << "off the old image: the new frame alone";
}

// Moving frames are carried from view to view, but the still image goes from
// where it was made to each new view in one step: back where it started, its
// every pixel is where it was, however the moves in between rounded.
TEST(ViewHistory, TheStillImageIsCarriedInOneStepSoItDoesNotDrift) {
  constexpr float kDistance = 3.0f;
  const Camera home;
  ViewHistory history(kW, kH, 16);
  for (int i = 0; i < 3; ++i) history.add(tagged(kW, kH, 1.0f), wall_surfaces(home, kW, kH, kDistance), home);
  const Image black(kW, kH);
  Camera moved = home;
  for (float shift : {0.4f, 1.3f, 2.6f, 1.7f, 0.6f}) {  // sideways by fractions of a pixel, and back
    moved.position.x = shift * kDistance * 2.0f * std::tan(0.5f * home.vfov) / float(kH);
    history.add(black, wall_surfaces(moved, kW, kH, kDistance), moved);
  }
  history.add(black, wall_surfaces(home, kW, kH, kDistance), home);
  const Image image = history.resolve();
  // 3 still frames of (x, y, 1) and 6 full moving frames of black: x / 3 where the still image came
  // back to the very pixel it was made at.
  for (int y = 0; y < kH; ++y)
    for (int x = 4; x < kW - 4; ++x) ASSERT_EQ(image.at(x, y).x, float(3.0 * x / 9.0)) << x << ", " << y;
}

// While moving, previews (weight < 1) show only where the still image cannot be carried.
TEST(ViewHistory, PreviewsFillOnlyWhatTheStillImageCannot) {
  constexpr float kDistance = 3.0f, kShift = 5;
  const Camera before;
  const Camera after = shifted(before, kShift, kDistance, kH);
  ViewHistory history(kW, kH, 16);
  history.add(tagged(kW, kH, 1.0f), wall_surfaces(before, kW, kH, kDistance), before);
  history.add(tagged(kW / 2, kH / 2, 7.0f), wall_surfaces(after, kW / 2, kH / 2, kDistance), after, 0.25);
  const Image image = history.resolve();
  EXPECT_EQ(image.at(10, 10).z, 1.0f) << "the still image, carried";
  EXPECT_EQ(image.at(kW - 1, 10).z, 7.0f) << "off the old image: the preview";
  history.add(tagged(kW, kH, 3.0f), wall_surfaces(after, kW, kH, kDistance), after);  // still again: a full frame
  EXPECT_EQ(history.resolve().at(10, 10).z, 2.0f) << "the still image of the new view is what it showed";
  EXPECT_EQ(history.resolve().at(kW - 1, 10).z, 3.0f) << "where only a preview showed, the first full frame alone";
}

TEST(ViewHistory, APreviewFillsEachFullPixelFromThePixelItLiesIn) {
  const Camera camera;
  ViewHistory history(kW, kH, 16);
  history.add(tagged(kW / 4, kH / 4, 1.0f), wall_surfaces(camera, kW / 4, kH / 4, 3.0f), camera, 0.25);
  const Image image = history.resolve();
  EXPECT_EQ(image.at(13, 9), glm::vec3(3.0f, 2.0f, 1.0f));
  EXPECT_DOUBLE_EQ(history.weight(), 0.25);
  EXPECT_THROW(history.add(tagged(kW / 3 + 1, kH / 3, 1.0f), {}, camera), std::invalid_argument);
}

TEST(FrameBudget, LevelsAreWholeDivisorsThatKeep128PixelsOnTheLongSide) {
  const FrameBudget budget(640, 480, 40.0, false);
  std::vector<int> divisors;
  for (const PreviewLevel& l : budget.levels()) divisors.push_back(l.divisor);
  EXPECT_EQ(divisors, (std::vector<int>{1, 1, 2, 4, 5}));
  EXPECT_FALSE(budget.levels()[0].cheap);
  EXPECT_TRUE(budget.levels()[1].cheap);
}

TEST(FrameBudget, SharpPreviewsComeBeforeFewerPixels) {
  const FrameBudget budget(640, 480, 40.0);
  std::vector<std::pair<int, int>> levels;  // divisor, light
  for (const PreviewLevel& l : budget.levels()) levels.emplace_back(l.divisor, l.light);
  EXPECT_EQ(levels, (std::vector<std::pair<int, int>>{{1, 1}, {1, 1}, {1, 2}, {1, 3}, {1, 4}, {1, 6}, {1, 8},
                                                      {2, 1}, {4, 1}, {5, 1}}));
  EXPECT_EQ(preview_settings(RenderSettings{}, budget.levels()[3]).light_divisor, 3);
  EXPECT_EQ(preview_settings(RenderSettings{}, budget.levels()[1]).light_divisor, 1);
  EXPECT_EQ(level_name(budget.levels()[3]), "preview light 1/3");
}

// Seconds a frame of `level` takes: a fixed 4 ms and 0.2 s for a full frame's pixels; previews' settings cost 0.6 of it.
double fake_cost(const PreviewLevel& level) {
  return 0.004 + 0.2 * (level.cheap ? 0.6 : 1.0) / double(level.divisor * level.divisor);
}

TEST(FrameBudget, MovingFramesTakeTheFinestLevelAFakeCostModelFitsInTheBudget) {
  FrameBudget budget(640, 480, 40.0, false);
  budget.measured(budget.pick(false), fake_cost(budget.levels()[0]));  // a still frame first
  std::vector<int> picks;
  for (int frame = 0; frame < 30; ++frame) {
    const int level = budget.pick(true);
    picks.push_back(level);
    budget.measured(level, fake_cost(budget.levels()[size_t(level)]));
  }
  // 1/2 with preview settings: 34 ms; full-size preview 124 ms; 1/4 12 ms.
  for (size_t i = 10; i < picks.size(); ++i) ASSERT_EQ(picks[i], 2) << "frame " << i;
  EXPECT_EQ(budget.pick(false), 0) << "a still frame is full";
  budget.pin(3);
  EXPECT_EQ(budget.pick(false), 3) << "the panel's pin holds moving or not";
  budget.pin(std::nullopt);
  FrameBudget off(640, 480, 0.0);
  EXPECT_EQ(off.pick(true), 0) << "no budget: every frame full";
}

// Sharp previews: camera rays at every pixel (a fixed 20 ms here), light by the lattice's share of it.
double sharp_cost(const PreviewLevel& level) {
  const double d = double(level.divisor) * level.light;
  return 0.004 + 0.02 / double(level.divisor * level.divisor) + 0.2 * (level.cheap ? 0.6 : 1.0) / (d * d);
}

TEST(FrameBudget, AHeavySceneGoesStraightToFewerPixelsWhenSharpPreviewsCostFarMore) {
  FrameBudget budget(640, 480, 40.0);
  const int first = budget.pick(true);
  ASSERT_EQ(budget.levels()[size_t(first)], (PreviewLevel{1, true, 8})) << "the cheapest sharp preview first";
  budget.measured(first, 0.45);  // camera rays at every pixel: Sponza's 450 ms
  const PreviewLevel next = budget.levels()[size_t(budget.pick(true))];
  EXPECT_EQ(next.divisor, 4) << "the first level whose pixels, a sixteenth, would fit: not one level a frame";
}

TEST(FrameBudget, AfterTheStopEachFrameIsFinerThanTheOneBeforeUpToTheFullFrame) {
  FrameBudget budget(640, 480, 40.0);
  budget.measured(budget.pick(false), sharp_cost(budget.levels()[0]));
  int moving = 0;
  for (int frame = 0; frame < 30; ++frame) {
    moving = budget.pick(true);
    budget.measured(moving, sharp_cost(budget.levels()[size_t(moving)]));
  }
  // From the cheapest sharp preview (light 1/8) finer while a frame takes at most 0.7 of the budget:
  // light 1/4 takes 4 + 20 + 7.5 = 31.5 ms (light 1/6: 27 ms; 1/3 would take 37).
  EXPECT_EQ(budget.levels()[size_t(moving)], (PreviewLevel{1, true, 4})) << "a level within the budget";
  std::vector<int> after;
  for (int frame = 0; frame < 10 && (after.empty() || after.back() != 0); ++frame) {
    after.push_back(budget.pick(false));
    budget.measured(after.back(), sharp_cost(budget.levels()[size_t(after.back())]));
  }
  ASSERT_EQ(after.back(), 0) << "the refinement ends at the full frame";
  int before = moving;
  for (int level : after) {
    EXPECT_LT(level, before) << "each frame after the stop is finer than the one before";
    EXPECT_EQ(budget.levels()[size_t(level)].divisor, 1) << "at full resolution";
    before = level;
  }
  EXPECT_LE(after.size(), 4u) << "a few steps, not every level";
  EXPECT_EQ(budget.pick(false), 0) << "then full frames";
  FrameBudget coarse(640, 480, 40.0, false);
  coarse.pick(true);
  EXPECT_EQ(coarse.pick(false), 0) << "coarse previews: the full frame at once";
}

TEST(FrameBudget, APreviewWeighsItsShareOfAFullFramesSamples) {
  RenderSettings settings;
  settings.aa_samples = 4;
  EXPECT_DOUBLE_EQ(level_weight(settings, {1, false}), 1.0);
  EXPECT_DOUBLE_EQ(level_weight(settings, {2, true}), 1.0 / 16.0);
  EXPECT_DOUBLE_EQ(level_weight(settings, {1, true, 3}), 1.0 / 36.0) << "light on one pixel in 9, one sub-sample in 4";
  settings.method = MethodKind::PathTracer;
  EXPECT_DOUBLE_EQ(level_weight(settings, {2, true}), 0.25);
  EXPECT_EQ(preview_settings(RenderSettings{}, {2, true}).aa_samples, 1);
  EXPECT_EQ(preview_settings(RenderSettings{}, {2, true}).compensation_samples, 0);
  RenderSettings caustics;
  caustics.caustics = true;
  EXPECT_FALSE(preview_settings(caustics, {2, true}).caustics) << "a preview shoots no photons";
  EXPECT_TRUE(preview_settings(caustics, {1, false}).caustics);
  EXPECT_EQ(preview_settings(RenderSettings{}, {2, true}).paths_per_set, RenderSettings{}.paths_per_set / 4)
      << "a preview pixel has the light paths of one of a full pixel's 4 sub-samples";
}

class MotionPlannerTest : public ::testing::Test {
 protected:
  MotionPlannerTest() : scene(make_builtin_scene("cornell")) {
    options.render.width = 640;
    options.render.height = 480;
    options.sharp_previews = false;  // previews over fewer pixels, which the frame's width tells
  }
  MovingView view(uint64_t camera_generation, uint64_t settings_generation = 0) const {
    MovingView v;
    v.camera = scene_camera(scene, 0.0);
    v.camera.position.x += 0.01f * float(camera_generation);
    v.camera_generation = camera_generation;
    v.settings_generation = settings_generation;
    return v;
  }
  Scene scene;
  MasterOptions options;
};

TEST_F(MotionPlannerTest, PassesCountOnThroughMovesAndStartOverWithNewSettings) {
  MotionPlanner planner(options, scene, 40.0);
  RenderSettings s;
  const auto t0 = MotionPlanner::Clock::now();
  const FrameSetup a = planner.next(view(0), s, t0);
  const FrameSetup b = planner.next(view(1), s, t0 + std::chrono::milliseconds(10));  // moved: a preview, the next pass
  const FrameSetup b2 = planner.next(view(1), s, t0 + std::chrono::milliseconds(60));  // between two drag events
  const FrameSetup c = planner.next(view(1), s, t0 + std::chrono::milliseconds(400));  // still again: full
  EXPECT_EQ(a.width, 640);
  EXPECT_LT(b.width, 640) << "a moving frame is a preview";
  EXPECT_LT(b2.width, 640) << "a frame between two of a drag's events is still part of the move";
  EXPECT_EQ(s.aa_samples, RenderSettings{}.aa_samples) << "a still frame has the full settings";
  EXPECT_EQ(c.width, 640);
  EXPECT_EQ(b.seed, a.seed + 1);
  EXPECT_EQ(c.seed, a.seed + 3) << "fresh VPL sets every frame, moving or not";
  EXPECT_EQ(c.sample_begin, 1u) << "the clamp relaxes with the passes since the camera stopped";
  EXPECT_TRUE(c.want_surfaces);
  const FrameSetup d = planner.next(view(1, 1), s, t0 + std::chrono::milliseconds(500));
  EXPECT_EQ(d.seed, a.seed) << "new settings: passes start over";
}

// The window's history keeps one full-size frame's surfaces while the camera
// stands still (view_history.h): a still view asks for them until such a
// frame has come, a preview's do not count, and a move or new settings ask again.
TEST_F(MotionPlannerTest, AStillViewAsksForSurfacesUntilAFullFrameBringsThem) {
  MotionPlanner planner(options, scene, 40.0);
  RenderSettings s;
  const auto t0 = MotionPlanner::Clock::now();
  const FrameSetup a = planner.next(view(0), s, t0);
  const FrameSetup a2 = planner.next(view(0), s, t0);
  EXPECT_TRUE(a.want_surfaces);
  EXPECT_TRUE(a2.want_surfaces) << "none has come yet";
  planner.completed(a.frame_id, 0.1);
  EXPECT_FALSE(planner.next(view(0), s, t0).want_surfaces) << "a full frame of this view brought them";
  const FrameSetup moved = planner.next(view(1), s, t0 + std::chrono::milliseconds(10));
  ASSERT_LT(moved.width, 640) << "a moving frame is a preview";
  EXPECT_TRUE(moved.want_surfaces);
  planner.completed(moved.frame_id, 0.01);
  const FrameSetup still = planner.next(view(1), s, t0 + std::chrono::milliseconds(400));
  ASSERT_EQ(still.width, 640);
  EXPECT_TRUE(still.want_surfaces) << "a preview's surfaces are coarser than the history keeps";
  planner.completed(still.frame_id, 0.1);
  EXPECT_FALSE(planner.next(view(1), s, t0 + std::chrono::milliseconds(500)).want_surfaces);
  EXPECT_TRUE(planner.next(view(1, 1), s, t0 + std::chrono::milliseconds(600)).want_surfaces)
      << "new settings start the history over";
  options.reproject = false;
  MotionPlanner off(options, scene, 40.0);
  EXPECT_FALSE(off.next(view(0), s, t0).want_surfaces) << "no reprojection, no surfaces";
}

TEST_F(MotionPlannerTest, SharpPreviewsAreFullSizeWithLightOnALatticeAndRefineAfterTheStop) {
  options.sharp_previews = true;
  MotionPlanner planner(options, scene, 40.0);
  RenderSettings s;
  const auto t0 = MotionPlanner::Clock::now();
  planner.completed(planner.next(view(0), s, t0).frame_id, 0.2);  // a full frame: 200 ms
  const FrameSetup moved = planner.next(view(1), s, t0 + std::chrono::milliseconds(10));
  EXPECT_EQ(moved.width, 640) << "camera rays at every pixel";
  EXPECT_GT(s.light_divisor, 1) << "light on a lattice";
  EXPECT_EQ(s.aa_samples, 1);
  const int moving_divisor = s.light_divisor;
  planner.completed(moved.frame_id, 0.03);
  const FrameSetup still = planner.next(view(1), s, t0 + std::chrono::milliseconds(400));
  EXPECT_EQ(still.width, 640);
  EXPECT_LT(s.light_divisor, moving_divisor) << "the first frame after the stop is finer";
}

TEST_F(MotionPlannerTest, AMoveCancelsTheFramesItLeftBehindButTheOldestPreview) {
  MotionPlanner planner(options, scene, 40.0);
  RenderSettings s;
  const uint64_t full = planner.next(view(0), s).frame_id;
  const uint64_t full2 = planner.next(view(0), s).frame_id;
  EXPECT_EQ(planner.stale(view(1), {full, full2}), (std::vector<uint64_t>{full, full2}))
      << "full frames of an old view: both go";
  const uint64_t preview = planner.next(view(1), s).frame_id;
  const uint64_t preview2 = planner.next(view(2), s).frame_id;
  EXPECT_EQ(planner.stale(view(3), {preview, preview2}), (std::vector<uint64_t>{preview2}))
      << "the oldest preview is what the window shows next";
  EXPECT_EQ(planner.stale(view(3, 1), {preview, preview2}), (std::vector<uint64_t>{preview, preview2}))
      << "frames of old settings all go";
  EXPECT_TRUE(planner.stale(view(2), {preview2}).empty()) << "a frame of the current view stays";
}

TEST(FrameRate, AveragesOverTheLastSecond) {
  FrameRate rate;
  const auto t0 = FrameRate::Clock::time_point{} + std::chrono::hours(1);
  for (int i = 0; i <= 30; ++i) rate.shown(t0 + std::chrono::milliseconds(20 * i));  // 50 fps
  rate.shown(t0 + std::chrono::milliseconds(601));  // two frames 1 ms apart: no 1000 fps reading
  EXPECT_NEAR(rate.fps(t0 + std::chrono::milliseconds(601)), 31.0 / 0.601, 1e-6);
  EXPECT_NEAR(rate.waiting(t0 + std::chrono::milliseconds(2601)), 2.0, 1e-9);
  EXPECT_EQ(rate.fps(t0 + std::chrono::milliseconds(2601)), 0.0);
}

}  // namespace
}  // namespace igi
