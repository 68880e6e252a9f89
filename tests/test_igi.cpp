// The ir and igi methods: tiles independent of tiling and threads, and
// convergence to the path-traced reference.
#include <gtest/gtest.h>

#include "image/metrics.h"
#include "methods/vpl_method.h"
#include "scene/builtin_scenes.h"
#include "support/image_compare.h"
#include "support/render_fixture.h"

namespace igi {
namespace {

RenderSettings vpl_settings(MethodKind kind, int paths, float clamp = 0.0f) {
  RenderSettings s;
  s.method = kind;
  s.paths_per_set = paths;
  s.clamp = clamp;
  return s;
}

const test::Prepared& cornell() {
  static test::Prepared p(make_cornell_box());
  return p;
}

// Renders the frame tile by tile with the given tile size and origin offset.
Image render_tiled(const Method& method, const FrameSetup& frame, int border, int tw, int th, int ox, int oy) {
  Image image(frame.width, frame.height);
  RayCounts rays;
  auto cover = [&](int x, int y, int w, int h) {
    if (w <= 0 || h <= 0) return;
    TileJob job{x, y, w, h, border};
    std::vector<glm::vec3> pixels(size_t(w) * h);
    method.render_tile(job, pixels, rays);
    for (int j = 0; j < h; ++j)
      for (int i = 0; i < w; ++i) image.at(x + i, y + j) = pixels[size_t(j) * w + i];
  };
  for (int y = -oy; y < frame.height; y += th)
    for (int x = -ox; x < frame.width; x += tw) {
      int x0 = std::max(0, x), y0 = std::max(0, y);
      cover(x0, y0, std::min(frame.width, x + tw) - x0, std::min(frame.height, y + th) - y0);
    }
  return image;
}

class TileInvariance : public ::testing::TestWithParam<MethodKind> {};

TEST_P(TileInvariance, TilesOfAnySizeAndOffsetMatchTheWholeFrameBitForBit) {
  const test::Prepared& p = cornell();
  RenderSettings settings = vpl_settings(GetParam(), 4, 0.05f);
  auto method = make_method(p.context(), settings);
  FrameSetup frame = p.frame(83, 61, 3);
  method->begin_frame(frame);
  const int border = tile_border(settings);
  Image whole = render_tiled(*method, frame, border, frame.width, frame.height, 0, 0);
  const std::string name = std::string("tiles-") + method_name(GetParam());
  EXPECT_TRUE(test::images_identical(name + "-8x8", render_tiled(*method, frame, border, 8, 8, 0, 0), whole));
  EXPECT_TRUE(test::images_identical(name + "-40x40", render_tiled(*method, frame, border, 40, 40, 0, 0), whole));
  EXPECT_TRUE(test::images_identical(name + "-37x23", render_tiled(*method, frame, border, 37, 23, 5, 11), whole));
  // Threads and the frame renderer's own tiling.
  EXPECT_TRUE(test::images_identical(name + "-threads", p.render(settings, 83, 61, 1, 3, 2, 16), whole));
  EXPECT_TRUE(test::images_identical(name + "-1thread", p.render(settings, 83, 61, 1, 3, 1, 13), whole));
}

INSTANTIATE_TEST_SUITE_P(Igi, TileInvariance, ::testing::Values(MethodKind::InstantRadiosity, MethodKind::Igi),
                         [](const auto& info) { return std::string(method_name(info.param)); });

// Path-traced reference of the Cornell box, computed once per test run.
const Image& cornell_reference() {
  static Image reference = [] {
    RenderSettings pt;
    pt.method = MethodKind::PathTracer;
    return cornell().render(pt, 64, 48, 2048, 11);
  }();
  return reference;
}

TEST(IgiAccuracy, InstantRadiosityConvergesToPathTracerWithoutClamping) {
  const Image& ref = cornell_reference();
  double previous = 1e30;
  for (int m : {8, 64, 256}) {
    Image ir = cornell().render(vpl_settings(MethodKind::InstantRadiosity, m), 64, 48, 1);
    double e = rel_mse(ir, ref);
    std::printf("ir  M=%3d (%4d VPL paths): relMSE %.4f\n", m, 9 * m, e);
    EXPECT_LT(e, previous) << "relMSE must fall as M grows";
    previous = e;
  }
  EXPECT_LT(previous, 0.05) << "bound at M=256";
  Image ir = cornell().render(vpl_settings(MethodKind::InstantRadiosity, 256), 64, 48, 1);
  glm::vec3 mi = ir.mean(), mr = ref.mean();
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(mi[c], mr[c], 0.02 * mr[c]) << "mean brightness, channel " << c;
}

TEST(IgiAccuracy, IgiConvergesToPathTracerWithoutClamping) {
  const Image& ref = cornell_reference();
  double previous = 1e30;
  for (int m : {4, 32, 256}) {
    Image igi = cornell().render(vpl_settings(MethodKind::Igi, m), 64, 48, 1);
    double e = rel_mse(igi, ref);
    std::printf("igi M=%3d: relMSE %.4f\n", m, e);
    EXPECT_LT(e, previous) << "relMSE must fall as M grows";
    previous = e;
  }
  EXPECT_LT(previous, 0.05) << "bound at M=256";
}

}  // namespace
}  // namespace igi
