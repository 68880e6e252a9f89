// Clamping the geometry term trades blotches for lost energy; the loss must
// sit in corners and creases, where VPLs come closer than the clamp distance.
#include <cstdio>

#include <gtest/gtest.h>

#include "methods/gbuffer.h"
#include "sampling/warp.h"
#include "scene/builtin_scenes.h"
#include "support/render_fixture.h"

namespace igi {
namespace {

// Pixels whose visible point lies within `distance` of another surface,
// found by short probe rays over the hemisphere.
std::vector<bool> crease_mask(const test::Prepared& p, const FrameSetup& frame, float distance) {
  const std::vector<GSample> gbuffer = p.visible_points(frame.width, frame.height);
  std::vector<bool> mask(gbuffer.size(), false);
  for (size_t i = 0; i < gbuffer.size(); ++i) {
    const GSample& g = gbuffer[i];
    if (!g.valid()) continue;
    const Onb f(g.surface.geometric_normal_facing(g.wo));
    for (int k = 0; k < 64 && !mask[i]; ++k) {
      glm::vec3 d = f.to_world(cosine_hemisphere({(k + 0.5f) / 64.0f, (k * 0.618034f) - std::floor(k * 0.618034f)}));
      mask[i] = p.accel->occluded(Ray{offset_origin(g.surface, d), d, 0.0f, distance});
    }
  }
  return mask;
}

// 1 - mean(image) / mean(reference) over the pixels where mask == want.
double energy_loss(const Image& image, const Image& ref, const std::vector<bool>& mask, bool want) {
  double a = 0, b = 0;
  for (size_t i = 0; i < mask.size(); ++i)
    if (mask[i] == want && ref.pixels[i].x < 5.0f) {  // skip the light itself
      a += image.pixels[i].x + image.pixels[i].y + image.pixels[i].z;
      b += ref.pixels[i].x + ref.pixels[i].y + ref.pixels[i].z;
    }
  return 1.0 - a / b;
}

TEST(Clamping, EnergyLossIsConfinedToCreases) {
  test::Prepared p(make_cornell_box());
  const int w = 64, h = 48;
  RenderSettings ir = test::vpl_settings(MethodKind::InstantRadiosity, 16);
  // 16 frames of one clamp each (no relaxation across them).
  const Image unclamped = p.render_frames(ir, w, h, 16);
  for (float fraction : {0.02f, 0.05f, 0.1f}) {  // of the box's diagonal
    const float distance = fraction * p.scene.bounds().diagonal();
    ir.clamp = p.clamp_at(distance);
    const Image clamped = p.render_frames(ir, w, h, 16);
    const std::vector<bool> crease = crease_mask(p, p.frame(w, h), distance);
    const double share = double(std::count(crease.begin(), crease.end(), true)) / crease.size();
    const double open_loss = energy_loss(clamped, unclamped, crease, false);
    const double crease_loss = energy_loss(clamped, unclamped, crease, true);
    std::printf("clamp %.3f (%.1f mm): creases %.0f %% of pixels lose %.1f %%, open surfaces lose %.2f %%\n",
                ir.clamp, 1e3 * distance, 100 * share, 100 * crease_loss, 100 * open_loss);
    EXPECT_LT(std::abs(open_loss), 0.01) << "open surfaces keep their energy";
    EXPECT_GT(crease_loss, 3.0 * std::max(open_loss, 0.003)) << "the loss sits in the creases";
  }
}

}  // namespace
}  // namespace igi
