// write_gltf then load_gltf gives back the scene: the same vertices and
// triangles in the same order (triangles grouped by material), materials,
// lights and camera to float precision, textures to 8-bit sRGB precision.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "scene/gltf_loader.h"
#include "scene/gltf_writer.h"
#include "support/image_compare.h"

namespace igi {
namespace {

namespace fs = std::filesystem;

fs::path test_dir() { return test::fresh_test_dir("gltf_writer"); }

// A quad per material at depth z, triangles grouped by material as the
// writer emits them.
void add_quad(Scene& scene, uint32_t material, float z, bool with_attributes) {
  const uint32_t base = uint32_t(scene.positions.size());
  const glm::vec2 corners[4] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  for (glm::vec2 c : corners) {
    scene.positions.push_back(glm::vec3(c * (1.0f + z), z));
    if (with_attributes) {
      scene.normals.push_back(glm::normalize(glm::vec3(c.x - 0.5f, c.y - 0.5f, 2.0f)));
      scene.uvs.push_back(c * 0.5f + glm::vec2(z));
    }
  }
  scene.triangles.push_back(glm::uvec3(base, base + 1, base + 2));
  scene.triangles.push_back(glm::uvec3(base, base + 2, base + 3));
  scene.triangle_material.insert(scene.triangle_material.end(), {material, material});
}

Material make_material(const char* name, MaterialType type, glm::vec3 color) {
  Material m;
  m.name = name;
  m.type = type;
  m.base_color = color;
  return m;
}

Scene rich_scene(bool with_attributes) {
  Scene scene;
  scene.name = "rich";
  scene.materials.push_back(make_material("lamp", MaterialType::Diffuse, {0.5f, 0.6f, 0.7f}));
  scene.materials.back().emission = {5.0f, 2.5f, 1.0f};
  scene.materials.push_back(make_material("copper", MaterialType::Conductor, {0.9f, 0.6f, 0.3f}));
  scene.materials.back().alpha = 0.36f;
  scene.materials.back().double_sided = false;
  scene.materials.push_back(make_material("mirror", MaterialType::Mirror, {1.0f, 1.0f, 1.0f}));
  scene.materials.push_back(make_material("glass", MaterialType::Glass, {1.0f, 0.9f, 1.0f}));
  scene.materials.back().ior = 1.45f;
  scene.materials.push_back(make_material("leaf", MaterialType::Diffuse, {0.2f, 0.7f, 0.1f}));
  scene.materials.back().alpha_mask = true;
  scene.materials.back().alpha_cutoff = 0.3f;
  scene.materials.back().base_alpha = 0.8f;
  for (uint32_t m = 0; m < scene.materials.size(); ++m) add_quad(scene, m, 0.25f * float(m), with_attributes);
  return scene;
}

void add_lights_and_camera(Scene& scene) {
  PunctualLight point;
  point.position = {1, 2, 3};
  point.intensity = {4, 2, 1};
  PunctualLight spot;
  spot.type = LightType::Spot;
  spot.position = {0, 5, 0};
  spot.direction = glm::normalize(glm::vec3(0, -1, 0.2f));
  spot.intensity = glm::vec3(3);
  spot.inner_cone = 0.2f, spot.outer_cone = 0.6f;
  PunctualLight sun;
  sun.type = LightType::Directional;
  sun.direction = glm::normalize(glm::vec3(1, -1, -1));
  sun.intensity = {0.5f, 0.5f, 0.4f};
  scene.lights = {point, spot, sun};
  Camera camera;
  camera.position = {0, 1, 6};
  camera.forward = glm::normalize(glm::vec3(0.3f, -0.2f, -1));
  const glm::vec3 y(0, 1, 0);
  camera.up = glm::normalize(y - glm::dot(y, camera.forward) * camera.forward);
  camera.vfov = 0.7f;
  scene.camera = camera;
}

template <typename V>
void expect_near(V actual, V expected, float tolerance, const std::string& what) {
  for (int k = 0; k < V::length(); ++k)
    EXPECT_NEAR(actual[k], expected[k], tolerance) << what << " component " << k;
}

void expect_same_geometry(const Scene& a, const Scene& b) {
  ASSERT_EQ(a.positions.size(), b.positions.size());
  ASSERT_EQ(a.normals.size(), b.normals.size());
  ASSERT_EQ(a.uvs.size(), b.uvs.size());
  ASSERT_EQ(a.triangles, b.triangles);
  ASSERT_EQ(a.triangle_material, b.triangle_material);
  for (size_t i = 0; i < a.positions.size(); ++i) {
    expect_near(a.positions[i], b.positions[i], 1e-6f, "position " + std::to_string(i));
    if (!a.normals.empty()) expect_near(a.normals[i], b.normals[i], 1e-6f, "normal " + std::to_string(i));
    if (!a.uvs.empty()) expect_near(a.uvs[i], b.uvs[i], 1e-6f, "uv " + std::to_string(i));
  }
}

void expect_same_materials(const Scene& a, const Scene& b) {
  ASSERT_EQ(a.materials.size(), b.materials.size());
  for (size_t i = 0; i < a.materials.size(); ++i) {
    const Material &m = a.materials[i], &n = b.materials[i];
    SCOPED_TRACE(m.name);
    EXPECT_EQ(m.name, n.name);
    EXPECT_EQ(m.type, n.type);
    expect_near(m.base_color, n.base_color, 1e-6f, "base_color");
    expect_near(m.emission, n.emission, 1e-5f, "emission");
    if (m.type == MaterialType::Conductor) {
      EXPECT_NEAR(m.alpha, n.alpha, 1e-6f);
    }
    if (m.type == MaterialType::Glass) {
      EXPECT_FLOAT_EQ(m.ior, n.ior);
    }
    EXPECT_EQ(m.alpha_mask, n.alpha_mask);
    EXPECT_FLOAT_EQ(m.alpha_cutoff, n.alpha_cutoff);
    EXPECT_FLOAT_EQ(m.base_alpha, n.base_alpha);
    EXPECT_EQ(m.double_sided, n.double_sided);
    EXPECT_EQ(m.base_color_texture, n.base_color_texture);
  }
}

void expect_same_lights_and_camera(const Scene& a, const Scene& b) {
  ASSERT_EQ(a.lights.size(), b.lights.size());
  for (size_t i = 0; i < a.lights.size(); ++i) {
    const PunctualLight &l = a.lights[i], &m = b.lights[i];
    EXPECT_EQ(l.type, m.type);
    expect_near(l.position, m.position, 1e-6f, "light position");
    if (l.type != LightType::Point) expect_near(l.direction, m.direction, 1e-6f, "light direction");
    expect_near(l.intensity, m.intensity, 1e-6f, "light intensity");
    if (l.type == LightType::Spot) {
      EXPECT_FLOAT_EQ(l.inner_cone, m.inner_cone);
      EXPECT_FLOAT_EQ(l.outer_cone, m.outer_cone);
    }
  }
  ASSERT_EQ(a.camera.has_value(), b.camera.has_value());
  if (!a.camera) return;
  expect_near(a.camera->position, b.camera->position, 1e-6f, "camera position");
  expect_near(a.camera->forward, b.camera->forward, 1e-6f, "camera forward");
  expect_near(a.camera->up, b.camera->up, 1e-6f, "camera up");
  EXPECT_FLOAT_EQ(a.camera->vfov, b.camera->vfov);
}

LoadedScene round_trip(const Scene& scene, const fs::path& dir, const std::string& stem) {
  const fs::path path = dir / (stem + ".gltf");
  write_gltf(scene, path.string());
  EXPECT_TRUE(fs::exists(dir / (stem + ".bin"))) << "the buffer is a sibling .bin";
  return load_gltf(path.string());
}

TEST(GltfWriter, RoundTripGivesTheSameScene) {
  Scene scene = rich_scene(true);
  add_lights_and_camera(scene);
  const LoadedScene loaded = round_trip(scene, test_dir(), "rich");
  EXPECT_TRUE(loaded.warnings.empty()) << loaded.warnings.front();
  expect_same_geometry(scene, loaded.scene);
  expect_same_materials(scene, loaded.scene);
  expect_same_lights_and_camera(scene, loaded.scene);
}

TEST(GltfWriter, RoundTripWithoutNormalsUvsOrCamera) {
  const Scene scene = rich_scene(false);
  const LoadedScene loaded = round_trip(scene, test_dir(), "bare");
  EXPECT_TRUE(loaded.scene.normals.empty());
  EXPECT_TRUE(loaded.scene.uvs.empty());
  EXPECT_FALSE(loaded.scene.camera.has_value());
  expect_same_geometry(scene, loaded.scene);
}

TEST(GltfWriter, TrianglesOutOfMaterialOrderKeepTheirCorners) {
  Scene scene = rich_scene(true);
  std::swap(scene.triangles[0], scene.triangles[2]);
  std::swap(scene.triangle_material[0], scene.triangle_material[2]);
  const Scene loaded = round_trip(scene, test_dir(), "shuffled").scene;
  ASSERT_EQ(loaded.triangles.size(), scene.triangles.size());
  // Written grouped by material, in scene order within each: material 0
  // now owns scene triangles 1 and 2, which become loaded triangles 0 and 1.
  for (size_t i = 0; i < 2; ++i) {
    const glm::uvec3 t = scene.triangles[i + 1], u = loaded.triangles[i];
    for (int k = 0; k < 3; ++k) EXPECT_EQ(scene.positions[t[k]], loaded.positions[u[k]]) << i;
    EXPECT_EQ(loaded.triangle_material[i], 0u);
  }
}

TEST(GltfWriter, EmissionAboveOneUsesEmissiveStrength) {
  const fs::path path = test_dir() / "lamp.gltf";
  write_gltf(rich_scene(true), path.string());
  std::ifstream in(path);
  const nlohmann::json doc = nlohmann::json::parse(in);
  const nlohmann::json& lamp = doc["materials"][0];
  EXPECT_DOUBLE_EQ(lamp["emissiveFactor"][0].get<double>(), 1.0);
  const nlohmann::json& strength = lamp["extensions"]["KHR_materials_emissive_strength"];
  EXPECT_DOUBLE_EQ(strength["emissiveStrength"].get<double>(), 5.0);
  const nlohmann::json& glass = doc["materials"][3]["extensions"];
  EXPECT_DOUBLE_EQ(glass["KHR_materials_transmission"]["transmissionFactor"].get<double>(), 1.0);
  EXPECT_FLOAT_EQ(glass["KHR_materials_ior"]["ior"].get<float>(), 1.45f);
  const auto used = doc["extensionsUsed"].get<std::vector<std::string>>();
  for (const char* name :
       {"KHR_materials_emissive_strength", "KHR_materials_transmission", "KHR_materials_ior"})
    EXPECT_NE(std::find(used.begin(), used.end(), name), used.end()) << name;
}

// The specification's units, as Blender reads them: candela and lux at 683 lm/W.
TEST(GltfWriter, LampsAreWrittenInCandelaAndLux) {
  Scene scene = rich_scene(true);
  add_lights_and_camera(scene);
  const fs::path path = test_dir() / "lamps.gltf";
  write_gltf(scene, path.string());
  std::ifstream in(path);
  const nlohmann::json lights = nlohmann::json::parse(in)["extensions"]["KHR_lights_punctual"]["lights"];
  ASSERT_EQ(lights.size(), 3u);
  EXPECT_DOUBLE_EQ(lights[0]["intensity"].get<double>(), 4.0 * 683);  // point: 4 W/sr, colour (1, 0.5, 0.25)
  EXPECT_DOUBLE_EQ(lights[1]["intensity"].get<double>(), 3.0 * 683);
  EXPECT_DOUBLE_EQ(lights[2]["intensity"].get<double>(), 0.5 * 683);  // sun: 0.5 W/m^2
  EXPECT_DOUBLE_EQ(lights[0]["color"][1].get<double>(), 0.5);
}

TEST(GltfWriter, TextureRoundTripsThroughPng) {
  Scene scene = rich_scene(true);
  Texture texture;
  texture.width = 2, texture.height = 2;
  texture.texels = {{0.0f, 0.2f, 1.0f, 1.0f}, {0.5f, 0.5f, 0.5f, 0.5f},  //
                    {1.0f, 0.0f, 0.0f, 0.0f}, {0.05f, 0.8f, 0.3f, 1.0f}};
  scene.textures.push_back(texture);
  scene.materials[4].base_color_texture = 0;
  const fs::path dir = test_dir();
  const LoadedScene loaded = round_trip(scene, dir, "textured");
  EXPECT_TRUE(fs::exists(dir / "textured_texture0.png"));
  ASSERT_EQ(loaded.scene.textures.size(), 1u);
  const Texture& back = loaded.scene.textures[0];
  ASSERT_EQ(back.width, 2);
  ASSERT_EQ(back.height, 2);
  for (size_t i = 0; i < 4; ++i)
    expect_near(back.texels[i], texture.texels[i], 0.01f, "texel " + std::to_string(i));
  expect_same_materials(scene, loaded.scene);
}

TEST(GltfWriter, UnwritablePathIsAnError) {
  const fs::path path = test_dir() / "no" / "such" / "folder" / "scene.gltf";
  try {
    write_gltf(rich_scene(true), path.string());
    ADD_FAILURE() << "expected SceneError";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find(path.string()), std::string::npos) << e.what();
  }
}

TEST(GltfWriter, InconsistentSceneIsAnError) {
  Scene scene = rich_scene(true);
  scene.triangles[3].z = 999;
  const fs::path path = test_dir() / "broken.gltf";
  try {
    write_gltf(scene, path.string());
    ADD_FAILURE() << "expected SceneError";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("triangle 3"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(fs::exists(path));
}

}  // namespace
}  // namespace igi
