// The accuracy suite's scenes: each loads by name, validates, has the stated
// triangles and lights, is deterministic, and survives a glTF round trip
// with the same triangles, vertices, materials, lights and camera.
#include <cmath>
#include <filesystem>

#include <gtest/gtest.h>

#include "core/settings.h"
#include "lighting/lights.h"
#include "scene/builtin_scenes.h"
#include "scene/gltf_loader.h"
#include "scene/accel.h"
#include "scene/gltf_writer.h"
#include "scene/load_scene.h"
#include "scene/suite_scenes.h"

namespace igi {
namespace {

namespace fs = std::filesystem;

size_t emissive_triangles(const Scene& s) {
  size_t n = 0;
  for (uint32_t m : s.triangle_material) n += s.materials[m].is_emissive();
  return n;
}

size_t triangles_of(const Scene& s, MaterialType type) {
  size_t n = 0;
  for (uint32_t m : s.triangle_material) n += s.materials[m].type == type;
  return n;
}

void expect_same_scene(const Scene& a, const Scene& b) {
  ASSERT_EQ(a.triangles, b.triangles);
  ASSERT_EQ(a.triangle_material, b.triangle_material);
  ASSERT_EQ(a.positions.size(), b.positions.size());
  for (size_t i = 0; i < a.positions.size(); ++i)
    ASSERT_LT(glm::length(a.positions[i] - b.positions[i]), 1e-6f) << "position " << i;
  ASSERT_EQ(a.materials.size(), b.materials.size());
  for (size_t i = 0; i < a.materials.size(); ++i) {
    EXPECT_EQ(a.materials[i].name, b.materials[i].name);
    EXPECT_EQ(a.materials[i].type, b.materials[i].type);
    EXPECT_LT(glm::length(a.materials[i].base_color - b.materials[i].base_color), 1e-6f);
    EXPECT_LT(glm::length(a.materials[i].emission - b.materials[i].emission), 1e-4f);
    if (a.materials[i].type == MaterialType::Conductor) EXPECT_NEAR(a.materials[i].alpha, b.materials[i].alpha, 1e-6f);
    if (a.materials[i].type == MaterialType::Glass) EXPECT_NEAR(a.materials[i].ior, b.materials[i].ior, 1e-6f);
  }
  ASSERT_EQ(a.normals.size(), b.normals.size());
  for (size_t i = 0; i < a.normals.size(); ++i)
    ASSERT_LT(glm::length(a.normals[i] - b.normals[i]), 1e-5f) << "normal " << i;
  ASSERT_EQ(a.lights.size(), b.lights.size());
  for (size_t i = 0; i < a.lights.size(); ++i) {
    EXPECT_EQ(a.lights[i].type, b.lights[i].type);
    EXPECT_LT(glm::length(a.lights[i].position - b.lights[i].position), 1e-5f);
    EXPECT_LT(glm::length(a.lights[i].direction - b.lights[i].direction), 1e-5f);
    EXPECT_LT(glm::length(a.lights[i].intensity - b.lights[i].intensity), 1e-4f);
    EXPECT_NEAR(a.lights[i].outer_cone, b.lights[i].outer_cone, 1e-6f);
  }
  ASSERT_TRUE(b.camera.has_value());
  EXPECT_LT(glm::length(a.camera->position - b.camera->position), 1e-5f);
  EXPECT_LT(glm::length(a.camera->forward - b.camera->forward), 1e-5f);
  EXPECT_NEAR(a.camera->vfov, b.camera->vfov, 1e-6f);
}

void expect_round_trip(const std::string& name) {
  const Scene scene = load_scene(name);
  const fs::path dir = fs::path(IGI_TEST_OUTPUT_DIR) / "suite_scenes";
  fs::create_directories(dir);
  const std::string path = (dir / (name + ".gltf")).string();
  write_gltf(scene, path);
  const LoadedScene loaded = load_gltf(path);
  EXPECT_TRUE(loaded.warnings.empty()) << loaded.warnings.front();
  expect_same_scene(scene, loaded.scene);
}

TEST(SuiteScenes, NamesAreRegistered) {
  for (const char* name : {"corner", "rooms", "rooms-1", "rooms-7", "rooms-10", "corridor", "glossy", "glossy-medium", "large", "glass"})
    EXPECT_TRUE(is_builtin_scene(name)) << name;
  for (const char* name : {"rooms-0", "rooms-11", "rooms-", "rooms-x", "roomsy"})
    EXPECT_FALSE(is_builtin_scene(name)) << name;
  EXPECT_THROW(make_rooms_scene(11), SceneError);
  EXPECT_EQ(make_cornell_box().triangles.size(), 32u) << "the Cornell box is unchanged";
}

TEST(SuiteScenes, CornerIsAClosedRoomWithOneSpotLight) {
  const Scene s = load_scene("corner");
  EXPECT_NO_THROW(s.validate());
  EXPECT_EQ(s.triangles.size(), 12u);
  ASSERT_EQ(s.lights.size(), 1u);
  EXPECT_EQ(s.lights[0].type, LightType::Spot);
  EXPECT_EQ(emissive_triangles(s), 0u);
  // Aimed into the floor corner (4, 0, 4).
  const glm::vec3 to_corner = glm::normalize(glm::vec3(4, 0, 4) - s.lights[0].position);
  EXPECT_GT(glm::dot(to_corner, s.lights[0].direction), 0.9999f);
  expect_round_trip("corner");
}

TEST(SuiteScenes, RoomsHaveDoorwaysAndOneLightEach) {
  for (int n : {1, 4, 10}) {
    const Scene s = make_rooms_scene(n);
    EXPECT_NO_THROW(s.validate());
    // Outer box 12, inner walls 2 (n - 1) n segments of 3 quads, 2 per light.
    EXPECT_EQ(s.triangles.size(), size_t(12 + 12 * n * (n - 1) + 2 * n * n)) << n;
    EXPECT_EQ(emissive_triangles(s), size_t(2 * n * n)) << n;
    EXPECT_EQ(LightSet(s).lights().size(), size_t(2 * n * n)) << n;
    EXPECT_NEAR(s.bounds().upper.x, 4.0f * n, 1e-5f);
  }
  EXPECT_EQ(load_scene("rooms").triangles.size(), make_rooms_scene(4).triangles.size());
  expect_round_trip("rooms");
  expect_round_trip("rooms-10");
}

TEST(SuiteScenes, CorridorHidesItsLampFromTheCameraRoom) {
  const Scene s = load_scene("corridor");
  EXPECT_NO_THROW(s.validate());
  EXPECT_EQ(emissive_triangles(s), 2u);
  EXPECT_TRUE(s.lights.empty());
  EXPECT_EQ(suite_room("corridor", s.camera->position), 0) << "the camera stands in room 0";
  // From anywhere in the camera's room (x, z in [1, 5]) to anywhere on the lamp: a wall.
  const Accel accel(s);
  int lines = 0;
  for (uint32_t t = 0; t < s.triangles.size(); ++t) {
    if (!s.materials[s.triangle_material[t]].is_emissive()) continue;
    for (int k = 0; k < 3; ++k) {
      const glm::vec3 lamp = 0.98f * s.positions[s.triangles[t][k]] + 0.02f * s.positions[s.triangles[t][(k + 1) % 3]];
      for (float x = 1.05f; x < 5.0f; x += 0.45f)
        for (float z = 1.05f; z < 5.0f; z += 0.45f)
          for (float y : {0.05f, 1.2f, 2.45f}) {
            const glm::vec3 p(x, y, z), d = lamp - p;
            ++lines;
            ASSERT_TRUE(accel.occluded(Ray{p, glm::normalize(d), 0.0f, glm::length(d) * 0.999f})) << x << " " << y << " " << z;
          }
    }
  }
  EXPECT_GT(lines, 1000);
  expect_round_trip("corridor");
}

TEST(SuiteScenes, GlossyIsTheCornellBoxWithAMetalFloor) {
  const Scene s = load_scene("glossy");
  EXPECT_NO_THROW(s.validate());
  EXPECT_EQ(s.triangles.size(), make_cornell_box().triangles.size());
  EXPECT_EQ(triangles_of(s, MaterialType::Conductor), 2u);
  for (size_t t = 0; t < s.triangles.size(); ++t)
    if (s.materials[s.triangle_material[t]].type == MaterialType::Conductor)
      for (int k = 0; k < 3; ++k) EXPECT_NEAR(s.positions[s.triangles[t][k]].y, 0.0f, 1e-6f) << "on the floor";
  EXPECT_EQ(emissive_triangles(s), 2u);
  expect_round_trip("glossy");
}

TEST(SuiteScenes, GlossyMediumIsTheTiltedLightRoomWithAMediumRoughMetalFloor) {
  const Scene s = load_scene("glossy-medium");
  EXPECT_NO_THROW(s.validate());
  EXPECT_EQ(s.triangles.size(), load_scene("tilted-light").triangles.size());
  EXPECT_EQ(triangles_of(s, MaterialType::Conductor), 2u);
  for (size_t t = 0; t < s.triangles.size(); ++t) {
    const Material& m = s.materials[s.triangle_material[t]];
    if (m.type != MaterialType::Conductor) continue;
    EXPECT_GT(m.alpha, RenderSettings{}.glossy_threshold) << "VPLs shade it";
    EXPECT_LT(m.alpha, 0.3f) << "medium rough";
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(s.positions[s.triangles[t][k]].y, 0.0f, 1e-6f) << "on the floor";
  }
  EXPECT_EQ(emissive_triangles(s), 2u);
  expect_round_trip("glossy-medium");
}

TEST(SuiteScenes, GlassHasAMirrorBlockAndASmoothGlassSphereClearOfTheFloor) {
  const Scene s = load_scene("glass");
  EXPECT_NO_THROW(s.validate());
  EXPECT_EQ(triangles_of(s, MaterialType::Mirror), 10u) << "the tall block's five faces";
  EXPECT_EQ(triangles_of(s, MaterialType::Diffuse) + triangles_of(s, MaterialType::Mirror), 22u) << "no short block";
  EXPECT_GT(triangles_of(s, MaterialType::Glass), 3000u);
  EXPECT_EQ(emissive_triangles(s), 2u);
  ASSERT_EQ(s.normals.size(), s.positions.size());
  for (size_t t = 0; t < s.triangles.size(); ++t) {
    const Material& m = s.materials[s.triangle_material[t]];
    if (m.type != MaterialType::Glass) continue;
    EXPECT_EQ(m.ior, 1.5f);
    for (int k = 0; k < 3; ++k) {
      const glm::vec3 p = s.positions[s.triangles[t][k]];
      EXPECT_NEAR(glm::length(p - glm::vec3(0.185f, 0.135f, 0.17f)), 0.09f, 1e-5f) << "on the sphere";
      EXPECT_GT(p.y, 0.04f) << "hung above the floor";
      // Smooth shading: the vertex normal is the sphere's, not the facet's.
      EXPECT_GT(glm::dot(s.normals[s.triangles[t][k]], glm::normalize(p - glm::vec3(0.185f, 0.135f, 0.17f))), 0.99999f);
    }
  }
  expect_round_trip("glass");
}

TEST(SuiteScenes, LargeHasAMillionTriangles) {
  const Scene s = load_scene("large");
  EXPECT_NO_THROW(s.validate());
  EXPECT_GE(s.triangles.size(), 1'000'000u);
  EXPECT_EQ(emissive_triangles(s), 2u);
  const Scene again = make_large_scene();
  EXPECT_EQ(s.triangles, again.triangles) << "deterministic";
  EXPECT_EQ(s.positions, again.positions);
  expect_round_trip("large");
}

TEST(SuiteScenes, GroupByMaterialKeepsEveryTriangleCorner) {
  Scene s = make_cornell_box();
  s.triangle_material[0] = s.triangle_material[1] = 2;  // green floor, out of order
  Scene grouped = s;
  group_by_material(grouped);
  ASSERT_EQ(grouped.triangles.size(), s.triangles.size());
  EXPECT_TRUE(std::is_sorted(grouped.triangle_material.begin(), grouped.triangle_material.end()));
  EXPECT_EQ(grouped.positions.size(), s.positions.size());
}

}  // namespace
}  // namespace igi
