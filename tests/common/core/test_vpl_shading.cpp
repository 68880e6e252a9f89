// The one VPL shading rule (core/vpl_contribution.h, VplShading::contribution)
// and its vectorised form for diffuse lanes (methods/shadow_batch.cpp): the
// fast lanes must give what the scalar rule gives, bit for bit, for every
// lane (its light and its shadow ray), so that which lanes take which path
// never shows in an image.
#include <bit>
#include <cstring>
#include <random>

#include <gtest/gtest.h>

#include "methods/shadow_batch.h"
#include "scene/builtin_scenes.h"

namespace igi {
namespace {

uint32_t bits(float v) { return std::bit_cast<uint32_t>(v); }

glm::vec3 unit(std::mt19937& rng) {
  std::normal_distribution<float> n;
  glm::vec3 v;
  do v = glm::vec3(n(rng), n(rng), n(rng));
  while (glm::dot(v, v) < 1e-6f);
  return glm::normalize(v);
}

TEST(VplShading, FastLanesEqualTheScalarRuleBitForBit) {
  const Scene scene = make_cornell_box();
  uint32_t diffuse = 0;
  while (scene.materials[diffuse].type != MaterialType::Diffuse) ++diffuse;
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f), colour(0.05f, 1.0f);
  for (float bound : {INFINITY, 3.0f, 0.2f}) {
    const VplShading shading{scene, bound, 0.2f};
    // 64 receivers a round: diffuse, all kinds of positions, normals and viewers.
    std::vector<GSample> samples(64);
    PixelBatch batch;
    for (uint32_t i = 0; i < samples.size(); ++i) {
      GSample& g = samples[i];
      g.surface.position = 2.0f * glm::vec3(u(rng), u(rng), u(rng));
      g.surface.geometric_normal = unit(rng);
      // A shading normal that leans off the geometric one, on its side.
      glm::vec3 n = glm::normalize(g.surface.geometric_normal + 0.3f * unit(rng));
      if (glm::dot(n, g.surface.geometric_normal) <= 0.0f) n = g.surface.geometric_normal;
      g.surface.shading_normal = n;
      g.surface.material = &scene.materials[diffuse];
      g.surface.albedo = glm::vec3(colour(rng), colour(rng), colour(rng));
      g.wo = unit(rng);
      g.depth = 1.0f;
      g.has_surface = true;
      batch.add(i, g);
    }
    batch.pad();
    ASSERT_TRUE(batch.chunk_fast.size() == 4);
    for (int round = 0; round < 50; ++round) {
      Vpl v;
      v.kind = round % 2 ? VplKind::Area : VplKind::Surface;
      v.position = 2.0f * glm::vec3(u(rng), u(rng), u(rng));
      v.normal = unit(rng);
      v.flux = glm::vec3(colour(rng), colour(rng), colour(rng)) * 3.0f;
      v.incident = unit(rng);
      v.albedo = glm::vec3(colour(rng), colour(rng), colour(rng));
      v.material = diffuse;
      for (size_t first = 0; first < batch.index.size(); first += 16) {
        ShadowPacket packet{};
        fill_shadow_packet(batch, first, v, shading, packet);
        for (int k = 0; k < 16; ++k) {
          const size_t i = first + size_t(k);
          if (i >= batch.count || !batch.fast[i]) continue;
          ShadowQuery q{};
          const glm::vec3 c = shading.contribution(*batch.sample[i], v, q);
          const bool lit = c.x > 0.0f || c.y > 0.0f || c.z > 0.0f;
          ASSERT_EQ(packet.valid[k] != 0, lit) << "lane " << i << ", VPL " << round;
          if (!lit) continue;
          EXPECT_EQ(bits(packet.r[k]), bits(c.x)) << "lane " << i << ", VPL " << round << ": " << packet.r[k] << " " << c.x;
          EXPECT_EQ(bits(packet.g[k]), bits(c.y)) << "lane " << i;
          EXPECT_EQ(bits(packet.b[k]), bits(c.z)) << "lane " << i;
          EXPECT_EQ(bits(packet.rays.org_x[k]), bits(q.origin.x)) << "lane " << i;
          EXPECT_EQ(bits(packet.rays.org_y[k]), bits(q.origin.y)) << "lane " << i;
          EXPECT_EQ(bits(packet.rays.org_z[k]), bits(q.origin.z)) << "lane " << i;
          EXPECT_EQ(bits(packet.rays.dir_x[k]), bits(q.direction.x)) << "lane " << i;
          EXPECT_EQ(bits(packet.rays.dir_y[k]), bits(q.direction.y)) << "lane " << i;
          EXPECT_EQ(bits(packet.rays.dir_z[k]), bits(q.direction.z)) << "lane " << i;
          EXPECT_EQ(bits(packet.rays.tfar[k]), bits(q.tfar)) << "lane " << i;
        }
      }
    }
  }
}

}  // namespace
}  // namespace igi
