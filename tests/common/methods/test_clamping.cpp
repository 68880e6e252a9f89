// Clamping the geometry term trades blotches for lost energy; the loss must
// sit in corners and creases, where VPLs come closer than the clamp distance.
#include <algorithm>
#include <cstdio>

#include <gtest/gtest.h>

#include "core/gbuffer.h"
#include "core/vpl_contribution.h"
#include "sampling/warp.h"
#include "scene/builtin_scenes.h"
#include "scene/load_scene.h"
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

// A glossy receiver takes from a close VPL at most what a white Lambertian
// receiver takes under the same clamp (core/clamp.h): f_white G <= b / pi.
// On glossy-rough (alpha 0.3) every visible floor point, lit by a diffuse VPL
// a few centimetres away in the floor's mirror direction (where its lobe
// peaks), against a bound b; without the glossy clamp the lobe multiplied
// the clamped light by up to tens (printed), which showed as hot splotches
// along the floor's creases.
TEST(Clamping, AGlossyReceiverTakesNoMoreThanAWhiteLambertianUnderTheClamp) {
  const test::Prepared p(load_scene("glossy-rough"));
  const float bound = 100.0f;
  const VplShading shading{p.scene, bound, 0.2f};
  Vpl v;
  v.kind = VplKind::Area;  // emits flux / pi per unit G in every direction of its front: no BSDF of its own
  v.flux = glm::vec3(1.0f);
  double worst = 0.0;
  int floor_points = 0;
  for (const GSample& g : p.visible_points(64, 48)) {
    if (!g.valid() || g.surface.material->type != MaterialType::Conductor) continue;
    const glm::vec3 n = g.surface.shading_normal_facing(g.wo);
    const glm::vec3 mirror = glm::reflect(-g.wo, n);
    v.position = g.surface.position + 0.03f * mirror;
    v.normal = -mirror;
    ShadowQuery q;
    const glm::vec3 c = shading.contribution(g, v, q);
    // A white Lambertian receiver takes at most (1 / pi) x flux x b.
    worst = std::max(worst, double(max_component(c)) / (kInvPi * bound));
    ++floor_points;
  }
  std::printf("glossy-rough: over %d floor points, a VPL 3 cm away in the mirror direction gives %.3f x what a "
              "white Lambertian takes at most\n", floor_points, worst);
  ASSERT_GT(floor_points, 100);
  EXPECT_LE(worst, 1.0 + 1e-4);
  EXPECT_GT(worst, 0.5) << "the VPL must sit where the bound acts, or this proves nothing";
}

// The same bound at the emitting end: on `glossy` a VPL on the metal floor
// (its lobe widened to the glossy threshold, alpha 0.2, whose peak is up to
// 11.6 times a white Lambertian's 1 / pi) 3 cm in front of every visible
// diffuse point, which lies in the VPL's mirror direction. Before the lobe
// was clamped such VPLs lit the walls' feet as spots (printed: how much
// more the lobe gives unclamped).
TEST(Clamping, AGlossyVplGivesNoMoreThanAWhiteLambertianUnderTheClamp) {
  const test::Prepared p(load_scene("glossy"));
  const float bound = 100.0f;
  const VplShading shading{p.scene, bound, 0.2f};
  uint32_t metal = 0;
  while (metal < p.scene.materials.size() && p.scene.materials[metal].type != MaterialType::Conductor) ++metal;
  ASSERT_LT(metal, p.scene.materials.size());
  Vpl v;
  v.kind = VplKind::Surface;
  v.material = metal;
  v.albedo = p.scene.materials[metal].base_color;
  v.flux = glm::vec3(1.0f);
  double worst = 0.0, worst_lobe = 0.0;
  int points = 0;
  for (const GSample& g : p.visible_points(64, 48)) {
    if (!g.valid() || g.surface.material->type != MaterialType::Diffuse) continue;
    const glm::vec3 n = g.surface.shading_normal_facing(g.wo);
    const glm::vec3 out = -n;  // from the VPL to the point
    v.position = g.surface.position + 0.03f * n;
    const glm::vec3 t = std::abs(n.x) < 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
    v.normal = glm::normalize(out + glm::normalize(glm::cross(n, t)));  // 45 degrees from `out`
    v.incident = glm::reflect(-out, v.normal);  // light from the mirror direction: the lobe's peak
    ShadowQuery q;
    // A white Lambertian VPL gives at most (1 / pi) x flux x b, and the diffuse receiver takes 1 / pi of it.
    const double most = double(kInvPi) * kInvPi * bound;
    worst = std::max(worst, double(max_component(shading.contribution(g, v, q))) / most);
    worst_lobe = std::max(worst_lobe, double(max_component(shading.vpl_bsdf(v, out))) / kInvPi);
    ++points;
  }
  std::printf("glossy: over %d diffuse points, a floor VPL 3 cm away gives %.3f x what a white Lambertian VPL gives "
              "at most (its lobe, unclamped, peaks at %.1f x a Lambertian's)\n", points, worst, worst_lobe);
  ASSERT_GT(points, 100);
  EXPECT_LE(worst, 1.0 + 1e-4);
  EXPECT_GT(worst, 0.5) << "the VPL must sit where the bound acts, or this proves nothing";
  EXPECT_GT(worst_lobe, 2.0) << "the lobe must peak above a Lambertian's, or this proves nothing";
}

}  // namespace
}  // namespace igi
