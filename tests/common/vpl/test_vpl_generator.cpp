// VPL sets are a pure function of (scene, settings, seed).
#include <cstring>
#include <thread>

#include <gtest/gtest.h>

#include "scene/builtin_scenes.h"
#include "support/render_fixture.h"
#include "vpl/vpl_generator.h"

namespace igi {
namespace {

RenderSettings igi_settings(int n, int m) {
  RenderSettings s;
  s.method = MethodKind::Igi;
  s.interleave = n;
  s.paths_per_set = m;
  return s;
}

TEST(VplGenerator, SameSeedGivesIdenticalSetsOnAnyThread) {
  test::Prepared p(make_cornell_box());
  const RenderSettings settings = igi_settings(3, 32);
  VplSets a = generate_vpls(p.context(), settings, 5);
  VplSets b;
  std::thread([&] { b = generate_vpls(p.context(), settings, 5); }).join();
  ASSERT_EQ(a.vpls.size(), b.vpls.size());
  for (size_t i = 0; i < a.vpls.size(); ++i) {
    EXPECT_EQ(0, std::memcmp(&a.vpls[i].position, &b.vpls[i].position, sizeof(glm::vec3)));
    EXPECT_EQ(0, std::memcmp(&a.vpls[i].flux, &b.vpls[i].flux, sizeof(glm::vec3)));
  }
  EXPECT_EQ(a.hash, b.hash);
  EXPECT_NE(a.hash, generate_vpls(p.context(), settings, 6).hash);
}

TEST(VplGenerator, SetsPartitionPathsAndStartOnTheLight) {
  test::Prepared p(make_cornell_box());
  VplSets sets = generate_vpls(p.context(), igi_settings(3, 16), 1);
  ASSERT_EQ(sets.set_count(), 9);
  int light_vpls = 0;
  for (const Vpl& v : sets.vpls) light_vpls += v.kind == VplKind::Area;
  EXPECT_EQ(light_vpls, 9 * 16);  // one per path
  for (int k = 0; k < 9; ++k) {
    EXPECT_EQ(sets.vpls[sets.set_begin[k]].kind, VplKind::Area) << "set " << k;
    EXPECT_GT(sets.set_begin[k + 1] - sets.set_begin[k], 16u) << "paths bounce: more VPLs than paths";
  }
  // Set k holds paths [k M, (k+1) M), so the union of the 9 sets is the same
  // point set as one set of 9 M paths: the same VPLs, only the flux
  // normalisation (1/M) differs.
  VplSets one = generate_vpls(p.context(), igi_settings(1, 9 * 16), 1);
  ASSERT_EQ(one.vpls.size(), sets.vpls.size());
  for (size_t i = 0; i < one.vpls.size(); ++i) EXPECT_EQ(one.vpls[i].position, sets.vpls[i].position);
}

TEST(VplGenerator, FluxOfLightVplsSumsToEmittedPower) {
  // Each set alone estimates the light's radiance times area: sum of Area VPL
  // flux in a set equals Le * A for the Cornell light.
  test::Prepared p(make_cornell_box());
  VplSets sets = generate_vpls(p.context(), igi_settings(2, 64), 3);
  const glm::vec3 expected = glm::vec3(17, 12, 4) * (0.130f * 0.105f);
  for (int k = 0; k < 4; ++k) {
    glm::vec3 sum(0.0f);
    for (uint32_t i = sets.set_begin[k]; i < sets.set_begin[k + 1]; ++i)
      if (sets.vpls[i].kind == VplKind::Area) sum += sets.vpls[i].flux;
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(sum[c], expected[c], 1e-3f * expected[c]);
  }
}

}  // namespace
}  // namespace igi
