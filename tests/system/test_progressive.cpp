// Progressive frames (issue 12, fault 9): the master's passes are igi-render's
// passes, pt continues its sample sequence, and --first-frame rebuilds the sum.
#include <filesystem>

#include <gtest/gtest.h>

#include "view/frame_plan.h"
#include "sampling/sobol.h"
#include "scene/builtin_scenes.h"
#include "scene/load_scene.h"
#include "support/image_compare.h"
#include "support/process.h"
#include "support/render_fixture.h"

namespace igi {
namespace {

RenderOptions render(MethodKind method) {
  RenderOptions r;
  r.settings.method = method;
  r.samples = 2;
  r.seed = 7;
  return r;
}

TEST(Progressive, EveryVplPassIsJitteredFromOneSampleSetPassZeroIncluded) {
  const Scene scene = make_cornell_box();
  for (int i = 0; i < 4; ++i) {
    const FrameSetup f = plan_frame(render(MethodKind::Igi), CameraPath{}, scene, i, true);
    const glm::vec2 j = sample_2d(uint32_t(i), 0, 7);
    EXPECT_EQ(f.jitter_x, j.x) << "pass " << i;
    EXPECT_EQ(f.jitter_y, j.y) << "pass " << i;
    EXPECT_EQ(f.seed, 7u + uint32_t(i)) << "fresh VPLs each pass";
  }
  const FrameSetup still = plan_frame(render(MethodKind::Igi), CameraPath{}, scene, 3, false);
  EXPECT_EQ(still.jitter_x, 0.5f) << "without --progressive: the pixel centre, one seed";
  EXPECT_EQ(still.seed, 7u);
}

TEST(Progressive, PathTracingContinuesItsSampleSequenceUnderOneScrambling) {
  const Scene scene = make_cornell_box();
  for (int i = 0; i < 4; ++i) {
    const FrameSetup f = plan_frame(render(MethodKind::PathTracer), CameraPath{}, scene, i, true);
    EXPECT_EQ(f.seed, 7u) << "the same scrambling, pass " << i;
    EXPECT_EQ(f.sample_begin, uint32_t(2 * i)) << "samples [2i, 2i + 2)";
    EXPECT_EQ(f.sample_count, 2u);
  }
}

// igi-render's first `passes` passes of the same view.
Image offline_passes(int passes) {
  test::Prepared p(load_scene("cornell"));
  RenderSettings s;
  s.paths_per_set = 8;
  return p.render(s, 96, 72, passes, 5, 2, 16);
}

std::string master(const std::string& extra) {
  return std::string(IGI_MASTER_BINARY) + " --workers 2 --worker-threads 1 --scene cornell --method igi --vpl-paths 8 "
         "--size 96x72 --tile 16 --seed 5 --progressive --quiet " + extra;
}

// The master's accumulated frame 3 is igi-render's 4 passes, bit for bit; and
// a run resumed with --first-frame 2 writes the very same frame 3.
TEST(Progressive, FramesAreTheOfflinePassesAndFirstFrameRebuildsTheSum) {
  auto whole = test::run(master("--frames 4 -o " + test::output_path("prog.exr")), 120);
  ASSERT_EQ(whole.exit_code, 0) << whole.output;
  EXPECT_TRUE(test::images_identical("prog-offline", read_image(test::output_path("prog-0003.exr")), offline_passes(4)));
  auto resumed = test::run(master("--frames 2 --first-frame 2 -o " + test::output_path("prog-resumed.exr")), 120);
  ASSERT_EQ(resumed.exit_code, 0) << resumed.output;
  EXPECT_NE(resumed.output.find("rendering frames 0-1 again (not written)"), std::string::npos) << resumed.output;
  EXPECT_FALSE(std::filesystem::exists(test::output_path("prog-resumed-0001.exr")));
  EXPECT_TRUE(test::images_identical("prog-resumed", read_image(test::output_path("prog-resumed-0003.exr")),
                                     read_image(test::output_path("prog-0003.exr"))));
}

// Past pass 16 the filter hands over (filter/discontinuity_buffer.h) and the
// clamp has relaxed 4x: the master and two workers still give igi-render's
// passes, bit for bit, at frame 19.
TEST(Progressive, LateFramesHandedOverByTheFilterAreTheOfflinePasses) {
  auto r = test::run(master("--frames 20 -o " + test::output_path("prog-late.exr")), 120);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_TRUE(test::images_identical("prog-late", read_image(test::output_path("prog-late-0019.exr")), offline_passes(20)));
}

}  // namespace
}  // namespace igi
