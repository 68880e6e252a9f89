// Convergence on images, not means: at the defaults, igi's relMSE against
// the path tracer keeps falling from 16 to 256 passes on the scenes where a
// blur or bound that stayed would show (glass and its caustics, a glossy
// floor, rooms through doorways, a corner lit by bounced light). A blur that
// does not vanish with passes (the discontinuity buffer's window, a fixed
// photon radius) sets a floor that relMSE flattens onto: the filter's
// hand-over and the photon radii that shrink (filter/discontinuity_buffer.h,
// photons/caustic_map.h) are what this test would lose.
//
// The reference is two independent pt renders, and relMSE is taken against
// both with their own noise cancelled (image/metrics.h,
// rel_mse_two_references): against one reference its noise alone was more
// than igi's error at 256 passes on the glass scene.
#include <cstdio>
#include <string>

#include <gtest/gtest.h>

#include "image/metrics.h"
#include "photons/caustic_settings.h"
#include "scene/load_scene.h"
#include "support/image_compare.h"
#include "support/render_fixture.h"

namespace igi {
namespace {

struct ConvergenceCase {
  const char* scene;
  double bound;  // relMSE at 256 passes over relMSE at 16 passes, at most
};

class Convergence : public ::testing::TestWithParam<ConvergenceCase> {};

TEST_P(Convergence, RelMseKeepsFallingFrom16To256Passes) {
  constexpr int kWidth = 40, kHeight = 40, kReferenceSpp = 1024;
  const test::Prepared p(load_scene(GetParam().scene));
  // The defaults, as igi-render picks them for this scene (caustics where it has mirrors or glass).
  RenderSettings s;
  s.caustics = photons::has_specular_surfaces(p.scene, s.glossy_threshold);
  RenderSettings pt;
  pt.method = MethodKind::PathTracer;
  const Image a = p.render(pt, kWidth, kHeight, kReferenceSpp, 1001);
  const Image b = p.render(pt, kWidth, kHeight, kReferenceSpp, 2002);
  const Image sixteen = p.render(s, kWidth, kHeight, 16, 1);
  const Image late = p.render(s, kWidth, kHeight, 256, 1);
  const double e16 = rel_mse_two_references(sixteen, a, b), e256 = rel_mse_two_references(late, a, b);
  std::printf("[converge] %s %dx%d: relMSE (two references) %.6f at 16 passes, %.6f at 256: %.3f (bound %.2f); "
              "against one reference %.6f, %.6f\n",
              GetParam().scene, kWidth, kHeight, e16, e256, e256 / e16, GetParam().bound, rel_mse(sixteen, a),
              rel_mse(late, a));
  ASSERT_GT(e16, 0.0);
  if (e256 > GetParam().bound * e16) {
    test::write_failure_images(std::string("converge-") + GetParam().scene + "-256", late, a);
    ADD_FAILURE() << "relMSE at 256 passes is " << e256 / e16 << "x its value at 16 passes, above "
                  << GetParam().bound << ": a blur or bound that passes do not remove";
  }
}

// Bounds about 1.5x what was measured here (2026-12-07): glass 0.133, glossy
// 0.169, rooms 0.222, corner 0.267. With the window filtering every pass in
// full and a fixed photon radius they were 0.862, 0.870, 0.447 and 0.813.
INSTANTIATE_TEST_SUITE_P(Scenes, Convergence,
                         ::testing::Values(ConvergenceCase{"glass", 0.25}, ConvergenceCase{"glossy", 0.25},
                                           ConvergenceCase{"rooms", 0.33}, ConvergenceCase{"corner", 0.4}),
                         [](const auto& info) { return std::string(info.param.scene); });

}  // namespace
}  // namespace igi
