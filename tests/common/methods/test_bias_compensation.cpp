// Bias compensation for clamped VPLs (methods/bias_compensation.h): the
// energy the clamp cuts comes back where it was cut, and nowhere else.
//
//   a. corner     the corner scene's corner region against pt, with and without
//   b. furnace    closed sphere, exact answer Le / (1 - a), and the analytic
//                 value of one compensation level where the clamp cuts everywhere
//   c. tiles      bit-identical whatever the tiling (global-pixel random numbers)
//   d. cluster    igi-master with two workers equals the in-process render
//
// Images are tiny (48 x 36) and seeds fixed: VPL figures are deterministic
// for a given build; the bounds carry margin for the seed-to-seed spread.
#include <cmath>
#include <cstdio>
#include <map>

#include <gtest/gtest.h>

#include "core/gbuffer.h"
#include "core/method.h"
#include "scene/builtin_scenes.h"
#include "support/image_compare.h"
#include "support/process.h"
#include "support/render_fixture.h"

namespace igi {
namespace {

using test::luminance;
using test::render_tiled;
using test::vpl_settings;

constexpr int kWidth = 48, kHeight = 36;

// A region of a scene's image against pt: sum(image) / sum(pt) - 1 over the
// pixels whose visible point `in_region` accepts.
class RegionBias {
 public:
  template <class InRegion>
  RegionBias(const test::Prepared& p, int pt_spp, InRegion in_region) {
    RenderSettings pt;
    pt.method = MethodKind::PathTracer;
    reference_ = p.render(pt, kWidth, kHeight, pt_spp, 7);
    const std::vector<GSample> g = p.visible_points(kWidth, kHeight);
    for (size_t i = 0; i < g.size(); ++i)
      if (g[i].valid() && in_region(g[i])) pixels_.push_back(i);
  }
  double operator()(const Image& image) const {
    double a = 0, b = 0;
    for (size_t i : pixels_) {
      a += luminance(image.pixels[i]);
      b += luminance(reference_.pixels[i]);
    }
    return a / b - 1.0;
  }

 private:
  Image reference_;
  std::vector<size_t> pixels_;
};

// a. The spot lights one corner; the clamp cuts the VPLs crowded there.
// Region: visible points within 0.5 m of the corner, as in test_stability.cpp.
TEST(BiasCompensation, CornerRegainsTheClampedEnergy) {
  const test::Prepared p(make_builtin_scene("corner"));
  const glm::vec3 corner(4.0f, 0.0f, 4.0f);
  const RegionBias bias(p, 512, [&](const GSample& g) { return glm::distance(g.surface.position, corner) < 0.5f; });
  // 8 frames of one clamp each (no relaxation across them).
  auto render = [&](float clamp, int samples) {
    return p.render_frames(vpl_settings(MethodKind::InstantRadiosity, 8, clamp, true, samples), kWidth, kHeight, 8);
  };
  std::printf("[corner] ir M=8 x 8 frames, unclamped: corner against pt %+.1f %% (the estimate's own spread)\n",
              100 * bias(render(0.0f, 0)));
  // test_stability measures a 12 % corner loss against the unclamped render at 0.62 m.
  for (float distance : {0.62f, 1.24f}) {
    const float clamp = p.clamp_at(distance);
    const double without = bias(render(clamp, 0)), with = bias(render(clamp, 4));
    std::printf("[corner] clamp at %.2f m: corner against pt %+.1f %% without, %+.1f %% with 4 compensation samples\n",
                distance, 100 * without, 100 * with);
    // 10 %: the unclamped ir's spread against pt in this region (test_stability).
    EXPECT_LT(std::abs(with), 0.10) << "bound: compensated corner within 10 % of pt, clamp " << clamp;
    EXPECT_LT(without, -0.10) << "the clamp alone darkens the corner by more than 10 %";
    // One level leaves out the second-order term: at least half the loss comes back.
    EXPECT_GT(with - without, -0.5 * without) << "clamp " << clamp;
  }
}

// a'. A GGX floor rough enough for VPLs (alpha 0.25) is clamped on f G, its
// lobe times G (core/clamp.h), so the clamp cuts the lobe's peak at any
// distance, not only close VPLs; compensation draws from the lobe and brings
// it back. Region: the floor's pixels.
TEST(BiasCompensation, AGlossyFloorRegainsWhatTheClampCutFromItsLobe) {
  const test::Prepared p(make_builtin_scene("glossy-medium"));
  const RegionBias bias(p, 1024, [](const GSample& g) { return g.surface.material->type == MaterialType::Conductor; });
  auto render = [&](float clamp, int samples) {
    return p.render_frames(vpl_settings(MethodKind::Igi, 16, clamp, true, samples), kWidth, kHeight, 8);
  };
  const double unclamped = bias(render(0.0f, 0)), without = bias(render(0.3f, 0)), with = bias(render(0.3f, 4));
  std::printf("[glossy floor] igi M=16 x 8 frames against pt: unclamped %+.1f %%, clamp 0.3 without compensation "
              "%+.1f %%, with 4 samples %+.1f %%\n", 100 * unclamped, 100 * without, 100 * with);
  EXPECT_LT(without, unclamped - 0.05) << "the clamp cuts the lobe";
  EXPECT_GT(with - without, -0.5 * (without - unclamped)) << "at least half of it comes back";
  EXPECT_LT(std::abs(with - unclamped), 0.05);
}

// b. Inside the furnace sphere, G = cos_x cos_y / r^2 = 1 / (4 R^2) for any
// two points: a clamp below that scales every VPL by c = b / G, and each
// level of compensation adds a (1 - c) times the level below it, per unit of
// reflected radiance R = Le a / (1 - a):
//   one level  X1 = Le + c R + a (1 - c) (Le + c R)
//   two levels X2 = Le + c R + a (1 - c) X1              (exact: Le + R)
// the rest is the third-order term two levels leave out.
TEST(BiasCompensation, FurnaceHoldsAndTwoLevelsAreExactlyTwoLevels) {
  const float albedo = 0.5f, le = 1.0f;
  const test::Prepared p(make_furnace(albedo, le));
  const double exact = le / (1.0 - albedo), reflected = exact - le;
  auto mean = [&](float clamp, int samples) {
    const Image image = p.render_frames(vpl_settings(MethodKind::InstantRadiosity, 8, clamp, true, samples), 32, 24, 4);
    return luminance(image.mean());
  };
  // 0.35 m: b = 8.3 > G = 0.25, nothing is cut, nothing added.
  const double mild = mean(p.clamp_at(0.35f), 2);
  // The whole diagonal, 2 sqrt(3): b = 1/12, c = 1/3.
  const double diagonal = p.scene.bounds().diagonal(), b = 1.0 / (diagonal * diagonal), c = b / 0.25;
  const float far = p.clamp_at(float(diagonal));
  const double clamped = mean(far, 0), compensated = mean(far, 4);
  const double one_level = le + c * reflected + albedo * (1 - c) * (le + c * reflected);
  const double two_levels = le + c * reflected + albedo * (1 - c) * one_level;
  std::printf("[furnace] exact %.3f; clamp at 0.35 m + compensation %.4f; at the diagonal: %.4f (analytic %.4f), "
              "compensated %.4f (two levels, analytic %.4f; one level %.4f)\n",
              exact, mild, clamped, le + c * reflected, compensated, two_levels, one_level);
  EXPECT_NEAR(mild, exact, 0.02 * exact) << "bound: 2 %, the VPL estimate's spread at this size";
  EXPECT_NEAR(clamped, le + c * reflected, 0.03 * exact) << "bound: 3 %, the tessellated sphere's G is not constant";
  EXPECT_NEAR(compensated, two_levels, 0.03 * exact) << "bound: 3 %, as above";
  EXPECT_GT(compensated, one_level + 0.5 * (two_levels - one_level)) << "the second level is there";
}

// c. Per-pixel random numbers hash the GLOBAL pixel and frame seed only.
TEST(BiasCompensation, TilesOfAnySizeAndOffsetMatchTheWholeFrameBitForBit) {
  const test::Prepared p(make_cornell_box());
  for (MethodKind kind : {MethodKind::InstantRadiosity, MethodKind::Igi}) {
    const RenderSettings settings = vpl_settings(kind, 4, 0.05f, true, 2);
    auto method = make_method(p.context(), settings);
    const FrameSetup frame = p.frame(61, 45, 3);
    method->begin_frame(frame);
    const int border = tile_border(settings);
    const Image whole = render_tiled(*method, frame, border, frame.width, frame.height, 0, 0);
    const std::string name = std::string("bc-tiles-") + method_name(kind);
    EXPECT_TRUE(test::images_identical(name + "-8x8", render_tiled(*method, frame, border, 8, 8, 0, 0), whole));
    EXPECT_TRUE(test::images_identical(name + "-37x23", render_tiled(*method, frame, border, 37, 23, 5, 11), whole));
    EXPECT_TRUE(test::images_identical(name + "-threads", p.render(settings, 61, 45, 1, 3, 2, 16), whole));
    // And the compensation does something here (the box has creases).
    const Image plain = p.render(vpl_settings(kind, 4, 0.05f, true, 0), 61, 45, 1, 3);
    EXPECT_GT(whole.mean().x, plain.mean().x) << "compensation adds light";
  }
}

// d. The same settings through igi-master, two workers, the Welcome message.
TEST(BiasCompensation, DistributedEqualsSingleProcessBitForBit) {
  const int w = 96, h = 72;
  const std::string out = test::output_path("bc-dist.exr");
  const std::string command = std::string(IGI_MASTER_BINARY) + " --scene cornell --method igi --vpl-paths 8 --size " +
                              std::to_string(w) + "x" + std::to_string(h) +
                              " --tile 16 --worker-threads 1 --compensate 2 --clamp 0.1 --workers 2 --frames 1 -o " + out;
  auto r = test::run(command);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const test::Prepared p(make_cornell_box());
  RenderSettings s = vpl_settings(MethodKind::Igi, 8, 0.1f, true, 2, 4);  // the master's default --aa 4
  s.interleave = RenderSettings{}.interleave;                             // and --vpl-sets
  s.importance_paths = RenderSettings{}.importance_paths;                 // and --importance
  EXPECT_TRUE(test::images_identical("bc-dist", read_image(out), p.render(s, w, h, 1, 1)));
}

}  // namespace
}  // namespace igi
