// --vpl-draws (methods/vpl_draws.h): VPLs drawn from a light tree over all
// sets estimate what ir sums over the same VPLs, ever closer as K grows; the
// tree joins the frame's state hash; bad K is refused with the option's name.
#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>

#include "core/method.h"
#include "core/settings.h"
#include "scene/builtin_scenes.h"
#include "scene/suite_scenes.h"
#include "support/image_compare.h"
#include "support/process.h"
#include "support/render_fixture.h"

namespace igi {
namespace {

struct Difference {
  double mean_ratio = 0.0;  // image mean / ir's
  double rel_rms = 0.0;     // RMS of the per-pixel difference, relative to ir's mean
};

Difference against(const Image& image, const Image& ir) {
  double sum = 0.0, reference = 0.0, squared = 0.0;
  for (size_t i = 0; i < ir.pixels.size(); ++i) {
    const double a = test::luminance(image.pixels[i]), b = test::luminance(ir.pixels[i]);
    sum += a;
    reference += b;
    squared += (a - b) * (a - b);
  }
  const double n = double(ir.pixels.size());
  return {sum / reference, std::sqrt(squared / n) / (reference / n)};
}

// Unfiltered ir, unclamped, one sub-sample: its pixels are the exact sum over
// every VPL. The same frame (same VPLs) with K draws per point instead.
void expect_draws_converge_to_ir(const Scene& scene, const char* name) {
  const test::Prepared p(scene);
  RenderSettings ir = test::vpl_settings(MethodKind::InstantRadiosity, 24, 0.0f, false);
  const Image exact = p.render(ir, 48, 36, 1, 5);
  Difference at[2];
  const int draws[2] = {4, 64};
  for (int i = 0; i < 2; ++i) {
    RenderSettings s = ir;
    s.vpl_draws = draws[i];
    at[i] = against(p.render(s, 48, 36, 1, 5), exact);
  }
  std::printf("%s: K = 4: mean / ir %.4f, relative RMS %.4f; K = 64: %.4f, %.4f\n", name, at[0].mean_ratio,
              at[0].rel_rms, at[1].mean_ratio, at[1].rel_rms);
  EXPECT_NEAR(at[1].mean_ratio, 1.0, 0.02) << name;
  EXPECT_NEAR(at[0].mean_ratio, 1.0, 0.05) << name;
  // 16x the draws: the noise falls about 4x; at least 2.5x.
  EXPECT_LT(at[1].rel_rms, at[0].rel_rms / 2.5) << name;
}

TEST(VplDraws, ConvergeToIrOverTheSameVplsOnTheCornellBox) { expect_draws_converge_to_ir(make_cornell_box(), "cornell"); }
TEST(VplDraws, ConvergeToIrOverTheSameVplsWithGlossyVpls) {
  expect_draws_converge_to_ir(make_glossy_cornell(0.3f), "glossy-rough");
}
TEST(VplDraws, ConvergeToIrOverTheSameVplsUnderTheSky) { expect_draws_converge_to_ir(make_courtyard_scene(), "courtyard"); }

TEST(VplDraws, TheTreeJoinsTheFrameStateHash) {
  const test::Prepared p(make_cornell_box());
  RenderSettings sets = test::vpl_settings(MethodKind::Igi, 8);
  RenderSettings drawn = sets;
  drawn.vpl_draws = 4;
  auto a = make_method(p.context(), sets), b = make_method(p.context(), drawn), c = make_method(p.context(), drawn);
  const FrameSetup frame = p.frame(8, 8, 1);
  a->begin_frame(frame);
  b->begin_frame(frame);
  c->begin_frame(frame);
  EXPECT_NE(a->frame_state_hash(), b->frame_state_hash());
  EXPECT_EQ(b->frame_state_hash(), c->frame_state_hash());
}

TEST(VplDraws, BadCountsAreRefusedNamingTheOption) {
  const std::string render = std::string(IGI_RENDER_BINARY) + " --size 16x16 -o " + test::output_path("bad.exr");
  for (const char* k : {"-1", "1025"}) {
    const test::RunResult r = test::run(render + " --vpl-draws " + k, 20);
    EXPECT_EQ(r.exit_code, 1) << r.output;
    EXPECT_NE(r.output.find(std::string("--vpl-draws: expected 0..1024 VPLs drawn per shading point (0 = sets), got ") + k),
              std::string::npos)
        << r.output;
  }
}

}  // namespace
}  // namespace igi
