// Lightcuts' building blocks: the light tree (structure, representatives
// chosen in proportion to weight, determinism) and the error bounds (an
// upper bound on every cluster's exact unoccluded light, for Lambertian and
// GGX receivers and emitters, clamped or not, one gather point or several).
#include <cmath>

#include <gtest/gtest.h>

#include "core/direct_lights.h"
#include "lightcuts/cluster_bound.h"
#include "lightcuts/light_contribution.h"
#include "lightcuts/light_tree.h"
#include "sampling/hash.h"
#include "scene/builtin_scenes.h"
#include "scene/suite_scenes.h"
#include "scene/triangle.h"
#include "support/render_fixture.h"
#include "support/tilted_normals.h"
#include "vpl/vpl_generator.h"

namespace igi::lightcuts {
namespace {

LightTree tree_of(const test::Prepared& p, int paths, uint32_t seed, VplSets* vpls_out = nullptr) {
  RenderSettings s;
  s.paths_per_set = paths;
  VplSets vpls = generate_vpls(p.context(), s, seed);
  LightTree tree = build_light_tree(make_light_leaves(p.scene, vpls), p.scene.bounds().diagonal(), seed);
  if (vpls_out) *vpls_out = std::move(vpls);
  return tree;
}

TEST(LightTree, NodesBoundTheirSubtreesAndRepresentativesComeFromThem) {
  const test::Prepared p(make_corner_scene());  // a spot light too: two roots
  const LightTree tree = tree_of(p, 40, 3);
  ASSERT_EQ(tree.roots.size(), 2u);
  ASSERT_EQ(tree.nodes.size(), 2 * tree.leaves.size() - tree.roots.size());
  std::vector<int> leaf_seen(tree.leaves.size(), 0);
  for (uint32_t n = 0; n < tree.nodes.size(); ++n) {
    const LightNode& node = tree.nodes[n];
    ASSERT_GT(node.end, n);
    if (node.is_leaf()) {
      ++leaf_seen[node.leaf];
      EXPECT_EQ(node.representative, node.leaf);
      EXPECT_EQ(node.end, n + 1);
      continue;
    }
    const LightNode &l = tree.nodes[n + 1], &r = tree.nodes[node.right];
    EXPECT_EQ(l.end, node.right) << "left subtree ends where the right one starts";
    EXPECT_EQ(r.end, node.end);
    EXPECT_FLOAT_EQ(node.weight, l.weight + r.weight);
    EXPECT_TRUE(node.representative == l.representative || node.representative == r.representative)
        << "a node's representative is one child's: the cut reuses its ray";
    for (uint32_t m = n; m < node.end; ++m)
      if (tree.nodes[m].is_leaf()) {
        const LightLeaf& leaf = tree.leaves[tree.nodes[m].leaf];
        EXPECT_TRUE(glm::all(glm::greaterThanEqual(leaf.position, node.box.lo)) &&
                    glm::all(glm::lessThanEqual(leaf.position, node.box.hi)));
        if (leaf.light_class == LightClass::Cosine) {
          EXPECT_GE(glm::dot(leaf.normal, node.cone.axis()), node.cone.cos_theta - 1e-5f) << "node " << n;
        }
      }
  }
  for (int seen : leaf_seen) EXPECT_EQ(seen, 1) << "every leaf once";
}

TEST(LightTree, SameInputSameTreeAndTheSeedOnlyMovesRepresentatives) {
  const test::Prepared p(make_cornell_box());
  VplSets vpls;
  const LightTree a = tree_of(p, 30, 5, &vpls);
  const LightTree b = build_light_tree(make_light_leaves(p.scene, vpls), p.scene.bounds().diagonal(), 5);
  EXPECT_EQ(a.hash, b.hash);
  EXPECT_EQ(a.hash, hash_light_tree(a));
  const LightTree c = build_light_tree(make_light_leaves(p.scene, vpls), p.scene.bounds().diagonal(), 6);
  EXPECT_NE(a.hash, c.hash);
  ASSERT_EQ(a.nodes.size(), c.nodes.size());
  int moved = 0;
  for (size_t n = 0; n < a.nodes.size(); ++n) {
    EXPECT_EQ(a.nodes[n].right, c.nodes[n].right);
    moved += a.nodes[n].representative != c.nodes[n].representative;
  }
  EXPECT_GT(moved, 0);
}

// Over 2^15 leaves the top levels build on threads; the tree must not
// depend on which finishes first.
TEST(LightTree, LargeTreesBuildOnThreadsToTheSameTree) {
  std::vector<LightLeaf> leaves(70000);
  for (uint32_t i = 0; i < leaves.size(); ++i) {
    auto u = [i](uint32_t d) { return float(hash(i, d) >> 8) * 0x1p-24f; };
    LightLeaf& l = leaves[i];
    l.position = {u(0), u(1), u(2)};
    l.normal = glm::normalize(glm::vec3(u(3) - 0.5f, u(4) - 0.5f, 1.0f));
    l.intensity = glm::vec3(0.1f + u(5));
    l.weight = max_component(l.intensity);
  }
  const LightTree a = build_light_tree(leaves, 1.7f, 3), b = build_light_tree(leaves, 1.7f, 3);
  EXPECT_EQ(a.hash, b.hash);
  ASSERT_EQ(a.nodes.size(), 2 * leaves.size() - 1);
  for (uint32_t n = 0; n < a.nodes.size(); ++n)
    if (!a.nodes[n].is_leaf()) {
      ASSERT_EQ(a.nodes[n + 1].end, a.nodes[n].right);
      ASSERT_EQ(a.nodes[a.nodes[n].right].end, a.nodes[n].end);
    }
}

// Two leaves of weights 1 and 3: the heavier is the root's representative
// three times in four, over seeds.
TEST(LightTree, RepresentativesAreChosenInProportionToWeight) {
  std::vector<LightLeaf> leaves(2);
  leaves[0].position = {0, 0, 0};
  leaves[1].position = {1, 0, 0};
  for (LightLeaf& l : leaves) l.normal = {0, 0, 1};
  leaves[0].intensity = glm::vec3(1.0f);
  leaves[0].weight = 1.0f;
  leaves[1].intensity = glm::vec3(3.0f);
  leaves[1].weight = 3.0f;
  int heavy = 0;
  const int seeds = 4000;
  for (int seed = 0; seed < seeds; ++seed) {
    const LightTree tree = build_light_tree(leaves, 2.0f, uint32_t(seed));
    heavy += tree.leaves[tree.nodes[0].representative].weight == 3.0f;
  }
  EXPECT_NEAR(double(heavy) / seeds, 0.75, 0.03);
}

// For every gather node and light node of a few pixels: the exact sum of the
// unoccluded contributions of their pairs never exceeds the pair's bound.
void expect_bounds_hold(const Scene& scene, float clamp, int samples_per_pixel) {
  const test::Prepared p(scene);
  VplSets vpls;
  const LightTree tree = tree_of(p, 12, 9, &vpls);
  float clamp_bound = INFINITY;
  if (clamp > 0.0f) clamp_bound = 1.0f / std::pow(clamp * p.scene.bounds().diagonal(), 2.0f);
  const std::vector<Vpl> lights = exact_lights(p.scene);
  const LightingContext lighting{p.scene, vpls, lights, clamp_bound};
  const FrameSetup frame = p.frame(20, 15);
  const GatherPointTracer tracer(*p.accel, frame, samples_per_pixel, 16);
  RayCounts rays;
  GatherTree gather;
  int checked = 0;
  for (int y = 0; y < frame.height; y += 2)
    for (int x = 0; x < frame.width; x += 2) {
      std::vector<GatherPoint> points;
      for (int k = 0; k < samples_per_pixel; ++k) points.push_back(tracer.trace(x, y, k, rays));
      gather.build(points, samples_per_pixel, uint32_t(x * 131 + y));
      if (gather.empty()) continue;
      // exact[g][n]: sum over the gather node's points and the light node's leaves.
      std::vector<std::vector<glm::dvec3>> exact(gather.nodes.size(), std::vector<glm::dvec3>(tree.nodes.size()));
      for (size_t g = gather.nodes.size(); g-- > 0;) {
        const GatherNode& gn = gather.nodes[g];
        for (size_t n = tree.nodes.size(); n-- > 0;) {
          const LightNode& ln = tree.nodes[n];
          if (!gn.is_leaf()) {
            exact[g][n] = exact[gn.left][n] + exact[gn.right][n];
          } else if (!ln.is_leaf()) {
            exact[g][n] = exact[g][n + 1] + exact[g][ln.right];
          } else {
            const GatherPoint& point = gather.points[gn.representative];
            Ray shadow;
            const glm::vec3 c = light_contribution(lighting, point, tree.leaves[ln.leaf], shadow);
            exact[g][n] = glm::dvec3(c * point.throughput * gather.inv_samples);
          }
        }
      }
      for (uint32_t g = 0; g < gather.nodes.size(); ++g)
        for (uint32_t n = 0; n < tree.nodes.size(); ++n) {
          const glm::vec3 bound = pair_bound(gather, g, tree.nodes[n], clamp_bound);
          for (int c = 0; c < 3; ++c)
            ASSERT_LE(exact[g][n][c], double(bound[c]) * (1.0 + 1e-4) + 1e-30)
                << scene.name << ": pixel " << x << "," << y << " gather node " << g << " light node " << n
                << " channel " << c;
          ++checked;
        }
    }
  EXPECT_GT(checked, 1000);
}

TEST(LightcutsBounds, HoldForLambertianReceiversAndEmitters) { expect_bounds_hold(make_cornell_box(), 0.0f, 1); }
TEST(LightcutsBounds, HoldWithTheClamp) { expect_bounds_hold(make_cornell_box(), 0.05f, 1); }
TEST(LightcutsBounds, HoldForGgxReceiversAndGlossyVpls) { expect_bounds_hold(make_glossy_cornell(0.3f), 0.0f, 1); }
TEST(LightcutsBounds, HoldForSharpGgx) { expect_bounds_hold(make_glossy_cornell(0.04f), 0.0f, 1); }
TEST(LightcutsBounds, HoldForSpotLights) { expect_bounds_hold(make_corner_scene(), 0.0f, 1); }
TEST(LightcutsBounds, HoldForTiltedShadingNormals) { expect_bounds_hold(test::tilted_cornell(), 0.0f, 1); }
TEST(LightcutsBounds, HoldForGatherClusters) { expect_bounds_hold(make_glossy_cornell(0.3f), 0.0f, 4); }

}  // namespace
}  // namespace igi::lightcuts
