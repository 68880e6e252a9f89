// load_gltf on small files built here: JSON written with nlohmann::json,
// binary data packed by hand. Valid files check the mapping (counts, world
// positions, materials, lights, camera); broken files must give a SceneError
// naming the file and the offending element, never a crash.
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <OpenImageIO/imageio.h>

#include "io/file_bytes.h"
#include "scene/gltf_json.h"
#include "scene/gltf_loader.h"
#include "scene/load_scene.h"
#include "scene/gltf_pack.h"
#include "support/image_compare.h"

namespace igi {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

constexpr int kFloat = 5126, kUnsignedInt = 5125;

// A fresh folder per test, under the build tree.
fs::path test_dir() { return test::fresh_test_dir("gltf_loader"); }

void write_bytes(const fs::path& path, const std::vector<unsigned char>& bytes) {
  std::ofstream out(path, std::ios::binary);
  out.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
}

// Builds a glTF document and its single binary buffer.
class GltfBuilder {
 public:
  GltfBuilder() {
    doc["asset"] = {{"version", "2.0"}};
    doc["scenes"] = json::array({{{"nodes", json::array()}}});
    doc["scene"] = 0;
  }

  int add(const char* array, json value) {
    doc[array].push_back(std::move(value));
    return int(doc[array].size()) - 1;
  }

  int add_view(const void* data, size_t bytes) {
    bin.resize((bin.size() + 3) / 4 * 4, 0);
    const size_t offset = bin.size();
    const auto* first = static_cast<const unsigned char*>(data);
    bin.insert(bin.end(), first, first + bytes);
    return add("bufferViews", {{"buffer", 0}, {"byteOffset", offset}, {"byteLength", bytes}});
  }

  int add_floats(const std::vector<float>& values, const std::string& type) {
    const size_t components = type == "VEC3" ? 3 : type == "VEC2" ? 2 : 1;
    const int view = add_view(values.data(), values.size() * sizeof(float));
    return add("accessors", {{"bufferView", view}, {"componentType", kFloat},
                             {"count", values.size() / components}, {"type", type}});
  }

  int add_indices(const std::vector<uint32_t>& indices) {
    const int view = add_view(indices.data(), indices.size() * sizeof(uint32_t));
    return add("accessors", {{"bufferView", view}, {"componentType", kUnsignedInt},
                             {"count", indices.size()}, {"type", "SCALAR"}});
  }

  // Unit quad in the z = 0 plane facing +z; accessors POSITION, NORMAL,
  // TEXCOORD_0, indices are added in that order.
  int add_quad_mesh(int material = -1, std::vector<uint32_t> indices = {0, 1, 2, 0, 2, 3}) {
    json primitive = {{"attributes",
                       {{"POSITION", add_floats({0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0}, "VEC3")},
                        {"NORMAL", add_floats({0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1}, "VEC3")},
                        {"TEXCOORD_0", add_floats({0, 0, 1, 0, 1, 1, 0, 1}, "VEC2")}}},
                      {"indices", add_indices(indices)}};
    if (material >= 0) primitive["material"] = material;
    return add("meshes", {{"primitives", json::array({primitive})}});
  }

  int add_root(json node) {
    const int index = add("nodes", std::move(node));
    doc["scenes"][0]["nodes"].push_back(index);
    return index;
  }

  int add_light(json light) {
    doc["extensionsUsed"].push_back("KHR_lights_punctual");
    json& lights = doc["extensions"]["KHR_lights_punctual"]["lights"];
    lights.push_back(std::move(light));
    return int(lights.size()) - 1;
  }

  fs::path write_gltf(const fs::path& dir, const std::string& stem) {
    if (!bin.empty()) doc["buffers"] = json::array({{{"byteLength", bin.size()}, {"uri", stem + ".bin"}}});
    const fs::path path = dir / (stem + ".gltf");
    std::ofstream(path) << doc.dump(2);
    if (!bin.empty()) write_bytes(dir / (stem + ".bin"), bin);
    return path;
  }

  // `to_text` writes the JSON chunk (tests that need text nlohmann::json cannot make).
  fs::path write_glb(const fs::path& dir, const std::string& stem,
                     const std::function<std::string(const json&)>& to_text = [](const json& d) { return d.dump(); }) {
    doc["buffers"] = json::array({{{"byteLength", bin.size()}}});
    std::string text = to_text(doc);
    text.resize((text.size() + 3) / 4 * 4, ' ');
    std::vector<unsigned char> chunk = bin;
    chunk.resize((chunk.size() + 3) / 4 * 4, 0);
    std::vector<unsigned char> out;
    auto u32 = [&out](uint32_t v) { for (int i = 0; i < 4; ++i) out.push_back((v >> (8 * i)) & 0xff); };
    u32(0x46546C67), u32(2), u32(uint32_t(12 + 8 + text.size() + 8 + chunk.size()));
    u32(uint32_t(text.size())), u32(0x4E4F534A);
    out.insert(out.end(), text.begin(), text.end());
    u32(uint32_t(chunk.size())), u32(0x004E4942);
    out.insert(out.end(), chunk.begin(), chunk.end());
    const fs::path path = dir / (stem + ".glb");
    write_bytes(path, out);
    return path;
  }

  json doc;
  std::vector<unsigned char> bin;
};

json diffuse_material() { return {{"pbrMetallicRoughness", {{"metallicFactor", 0}}}}; }

json emissive_material() {
  return {{"pbrMetallicRoughness", {{"baseColorFactor", {0.5, 0.6, 0.7, 1.0}}, {"metallicFactor", 0.0}}},
          {"emissiveFactor", {1.0, 0.5, 0.25}},
          {"extensions", {{"KHR_materials_emissive_strength", {{"emissiveStrength", 4.0}}}}}};
}

// One emissive quad on one node: the smallest scene that must load.
GltfBuilder lit_quad() {
  GltfBuilder b;
  b.doc["extensionsUsed"] = json::array({"KHR_materials_emissive_strength"});
  b.add_root({{"mesh", b.add_quad_mesh(b.add("materials", emissive_material()))}});
  return b;
}

void expect_near(glm::vec3 actual, glm::vec3 expected, float tolerance = 1e-5f) {
  EXPECT_NEAR(actual.x, expected.x, tolerance);
  EXPECT_NEAR(actual.y, expected.y, tolerance);
  EXPECT_NEAR(actual.z, expected.z, tolerance);
}

size_t warnings_with(const LoadedScene& loaded, const std::string& text) {
  size_t count = 0;
  for (const std::string& w : loaded.warnings) count += w.find(text) != std::string::npos;
  return count;
}

// load_gltf must throw SceneError naming the file and every fragment.
void expect_scene_error(const fs::path& path, const std::vector<std::string>& fragments) {
  try {
    load_gltf(path.string());
    ADD_FAILURE() << "expected SceneError loading " << path;
  } catch (const SceneError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find(path.filename().string()), std::string::npos) << message;
    for (const std::string& fragment : fragments)
      EXPECT_NE(message.find(fragment), std::string::npos) << "'" << fragment << "' missing in: " << message;
  }
}

TEST(GltfLoader, MinimalEmissiveQuad) {
  const LoadedScene loaded = load_gltf(lit_quad().write_gltf(test_dir(), "quad").string());
  const Scene& scene = loaded.scene;
  EXPECT_TRUE(loaded.warnings.empty()) << loaded.warnings.front();
  ASSERT_EQ(scene.positions.size(), 4u);
  ASSERT_EQ(scene.normals.size(), 4u);
  ASSERT_EQ(scene.uvs.size(), 4u);
  ASSERT_EQ(scene.triangles.size(), 2u);
  ASSERT_EQ(scene.materials.size(), 1u);
  EXPECT_EQ(scene.triangles[1], glm::uvec3(0, 2, 3));
  EXPECT_EQ(scene.triangle_material, std::vector<uint32_t>({0, 0}));
  const Material& m = scene.materials[0];
  EXPECT_EQ(m.type, MaterialType::Diffuse);
  expect_near(m.base_color, {0.5f, 0.6f, 0.7f});
  expect_near(m.emission, {4.0f, 2.0f, 1.0f});
  EXPECT_FALSE(m.double_sided);
  expect_near(scene.positions[2], {1, 1, 0});
  expect_near(scene.normals[2], {0, 0, 1});
  EXPECT_EQ(scene.uvs[2], glm::vec2(1, 1));
  EXPECT_TRUE(scene.lights.empty());
  EXPECT_FALSE(scene.camera.has_value());
}

TEST(GltfLoader, GlbLoads) {
  const LoadedScene loaded = load_gltf(lit_quad().write_glb(test_dir(), "quad").string());
  EXPECT_EQ(loaded.scene.positions.size(), 4u);
  EXPECT_EQ(loaded.scene.triangles.size(), 2u);
  expect_near(loaded.scene.materials.at(0).emission, {4.0f, 2.0f, 1.0f});
}

TEST(GltfLoader, NestedAndSharedNodesGiveWorldPositions) {
  GltfBuilder b = lit_quad();  // node 0: the quad at the origin
  const int mesh = 0;
  b.doc["nodes"][0]["translation"] = {10, 0, 0};
  const double s = std::sqrt(0.5);
  const int child = 2;  // added after its parent
  b.add_root({{"translation", {0, 5, 0}}, {"rotation", {0, 0, s, s}}, {"children", json::array({child})}});
  b.add("nodes", {{"mesh", mesh}, {"scale", {2, 2, 2}}});
  b.add_root({{"mesh", mesh}, {"matrix", {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, -7, 1}}});
  const Scene scene = load_gltf(b.write_gltf(test_dir(), "nodes").string()).scene;
  ASSERT_EQ(scene.positions.size(), 12u);
  ASSERT_EQ(scene.triangles.size(), 6u);
  // Depth first in file order: node 0, node 1's child, node 3.
  expect_near(scene.positions[1], {11, 0, 0});
  expect_near(scene.positions[2], {11, 1, 0});
  expect_near(scene.positions[5], {0, 7, 0});   // R_z(90) * 2 * (1,0,0) + (0,5,0)
  expect_near(scene.positions[6], {-2, 7, 0});  // R_z(90) * 2 * (1,1,0) + (0,5,0)
  expect_near(scene.normals[6], {0, 0, 1});
  expect_near(scene.positions[10], {1, 1, -7});
}

TEST(GltfLoader, MirroringNodeFlipsWindingAndKeepsNormals) {
  GltfBuilder b = lit_quad();
  b.doc["nodes"][0]["scale"] = {-1, 1, 1};
  const Scene scene = load_gltf(b.write_gltf(test_dir(), "mirror").string()).scene;
  ASSERT_EQ(scene.triangles.size(), 2u);
  expect_near(scene.positions[1], {-1, 0, 0});
  for (const glm::uvec3& t : scene.triangles) {
    const glm::vec3 geometric = glm::cross(scene.positions[t.y] - scene.positions[t.x],
                                           scene.positions[t.z] - scene.positions[t.x]);
    EXPECT_GT(glm::dot(geometric, scene.normals[t.x]), 0.0f) << "front face must stay on the normal's side";
  }
}

TEST(GltfLoader, NonUniformScaleTransformsNormalsByInverseTranspose) {
  GltfBuilder b = lit_quad();
  const float tilted[3] = {0.0f, std::sqrt(0.5f), std::sqrt(0.5f)};
  for (int v = 0; v < 4; ++v) std::memcpy(b.bin.data() + 48 + 12 * v, tilted, sizeof(tilted));  // NORMAL
  b.doc["nodes"][0]["scale"] = {1, 2, 1};
  const Scene scene = load_gltf(b.write_gltf(test_dir(), "scaled").string()).scene;
  // (M^-1)^T n = (0, 1/2, 1) / sqrt(2), normalised; M n would lean the other way.
  expect_near(scene.normals[0], glm::normalize(glm::vec3(0, 0.5f, 1)));
}

// Intensities in the specification's candela: 683 cd is 1 W/sr.
TEST(GltfLoader, PunctualLightsAndCameraAreRead) {
  GltfBuilder b;
  b.add_root({{"mesh", b.add_quad_mesh(b.add("materials", diffuse_material()))}});
  const double s = std::sqrt(0.5);
  const int point = b.add_light({{"type", "point"}, {"color", {1.0, 0.5, 0.25}}, {"intensity", 8.0 * 683}});
  const int spot = b.add_light({{"type", "spot"}, {"intensity", 2.0 * 683}, {"range", 10.0},
                                {"spot", {{"innerConeAngle", 0.1}, {"outerConeAngle", 0.5}}}});
  b.add_root({{"translation", {1, 2, 3}}, {"extensions", {{"KHR_lights_punctual", {{"light", point}}}}}});
  b.add_root({{"translation", {0, 4, 0}}, {"rotation", {-s, 0, 0, s}},  // -Z onto -Y
              {"extensions", {{"KHR_lights_punctual", {{"light", spot}}}}}});
  b.add("cameras", {{"type", "perspective"},
                    {"perspective", {{"yfov", 0.8}, {"znear", 0.01}, {"aspectRatio", 1.5}}}});
  b.add_root({{"camera", 0}, {"translation", {1, 2, 3}}, {"rotation", {0, s, 0, s}}});  // -Z onto -X
  const LoadedScene loaded = load_gltf(b.write_gltf(test_dir(), "lights").string());
  const Scene& scene = loaded.scene;
  ASSERT_EQ(scene.lights.size(), 2u);
  EXPECT_EQ(scene.lights[0].type, LightType::Point);
  expect_near(scene.lights[0].position, {1, 2, 3});
  expect_near(scene.lights[0].intensity, {8, 4, 2});
  EXPECT_EQ(scene.lights[1].type, LightType::Spot);
  expect_near(scene.lights[1].position, {0, 4, 0});
  expect_near(scene.lights[1].direction, {0, -1, 0});
  expect_near(scene.lights[1].intensity, {2, 2, 2});
  EXPECT_FLOAT_EQ(scene.lights[1].inner_cone, 0.1f);
  EXPECT_FLOAT_EQ(scene.lights[1].outer_cone, 0.5f);
  EXPECT_EQ(warnings_with(loaded, "range"), 1u);
  ASSERT_TRUE(scene.camera.has_value());
  expect_near(scene.camera->position, {1, 2, 3});
  expect_near(scene.camera->forward, {-1, 0, 0});
  expect_near(scene.camera->up, {0, 1, 0});
  EXPECT_FLOAT_EQ(scene.camera->vfov, 0.8f);
  EXPECT_EQ(warnings_with(loaded, "aspectRatio"), 1u);
  // One line says how they were read, naming the brightest as written and as read.
  ASSERT_EQ(loaded.notices.size(), 1u);
  for (const char* said : {"2 lamps", "683 lm/W", "5464 cd = 8 W/sr", "--light-units radiometric"})
    EXPECT_NE(loaded.notices[0].find(said), std::string::npos) << said << " missing in: " << loaded.notices[0];
}

// Blender's exporter: a 100 W point lamp is 5435 cd, a 3 W/m^2 sun 2049 lux.
// --light-units radiometric reads a file's numbers as W/sr and W/m^2.
TEST(GltfLoader, LightUnitsSayHowIntensitiesAreRead) {
  GltfBuilder b = lit_quad();
  const int point = b.add_light({{"type", "point"}, {"intensity", 100.0 / (4 * std::numbers::pi) * 683}});
  const int sun = b.add_light({{"type", "directional"}, {"intensity", 3.0 * 683}});
  b.add_root({{"translation", {0, 0, 2}}, {"extensions", {{"KHR_lights_punctual", {{"light", point}}}}}});
  b.add_root({{"extensions", {{"KHR_lights_punctual", {{"light", sun}}}}}});
  const fs::path path = b.write_gltf(test_dir(), "blender-lamps");
  const Scene photometric = load_gltf(path.string()).scene;
  ASSERT_EQ(photometric.lights.size(), 2u);
  expect_near(photometric.lights[0].intensity, glm::vec3(float(100.0 / (4 * std::numbers::pi))));
  expect_near(photometric.lights[1].intensity, glm::vec3(3.0f));
  const LoadedScene radiometric = load_gltf(path.string(), GltfOptions{std::nullopt, LightUnits::Radiometric, false});
  ASSERT_EQ(radiometric.scene.lights.size(), 2u);
  expect_near(radiometric.scene.lights[1].intensity, glm::vec3(3.0f * 683), 1e-3f);
  ASSERT_EQ(radiometric.notices.size(), 2u) << "the units, and the framing camera";
  EXPECT_NE(radiometric.notices[0].find("read as W/sr and W/m^2"), std::string::npos) << radiometric.notices[0];
}

// Blender exports neither its lamp nor its camera by default: the scene gets
// a sun from over the framing camera's shoulder, and both are named.
TEST(GltfLoader, AFileWithoutLightOrCameraGetsASunAndAFramingCamera) {
  GltfBuilder b;
  b.add_root({{"mesh", b.add_quad_mesh(b.add("materials", diffuse_material()))}});
  const LoadedScene loaded = load_gltf(b.write_gltf(test_dir(), "unlit").string());
  EXPECT_TRUE(loaded.warnings.empty());
  ASSERT_EQ(loaded.scene.lights.size(), 1u);
  const PunctualLight& sun = loaded.scene.lights[0];
  EXPECT_EQ(sun.type, LightType::Directional);
  EXPECT_FALSE(loaded.scene.camera.has_value());
  const Camera camera = loaded.scene.auto_camera();
  EXPECT_GT(glm::dot(sun.direction, camera.forward), 0.8f) << "the sun shines the way the camera looks";
  EXPECT_LT(sun.direction.y, camera.forward.y) << "and from higher up";
  ASSERT_EQ(loaded.notices.size(), 2u);
  EXPECT_NE(loaded.notices[0].find("no light"), std::string::npos) << loaded.notices[0];
  EXPECT_NE(loaded.notices[0].find("--environment"), std::string::npos) << loaded.notices[0];
  EXPECT_NE(loaded.notices[1].find("no camera"), std::string::npos) << loaded.notices[1];
}

// The framing camera stands on the side the lamps light: a lamp at -x, +z
// puts it at -x, +z of the centre, one at +x, -z at +x, -z.
TEST(GltfLoader, TheFramingCameraSeesTheLitSide) {
  for (const glm::vec3 lamp : {glm::vec3(-5, 3, 4), glm::vec3(5, 3, -4), glm::vec3(4, 3, 5)}) {
    GltfBuilder b = lit_quad();
    const int point = b.add_light({{"type", "point"}, {"intensity", 683.0}});
    b.add_root({{"translation", {lamp.x, lamp.y, lamp.z}}, {"extensions", {{"KHR_lights_punctual", {{"light", point}}}}}});
    const Scene scene = load_gltf(b.write_gltf(test_dir(), "lamp").string()).scene;
    const Camera camera = scene.auto_camera();
    const glm::vec3 centre = scene.bounds().center();
    EXPECT_GT((camera.position.x - centre.x) * lamp.x, 0.0f) << "lamp at x " << lamp.x;
    EXPECT_GT((camera.position.z - centre.z) * lamp.z, 0.0f) << "lamp at z " << lamp.z;
    EXPECT_GT(camera.position.y, centre.y);
    expect_near(glm::normalize(centre - camera.position), camera.forward);
  }
}

TEST(GltfLoader, SpotConesOutOfOrderAreAnError) {
  GltfBuilder b = lit_quad();
  const json cones = {{"innerConeAngle", 0.6}, {"outerConeAngle", 0.5}};
  const int spot = b.add_light({{"type", "spot"}, {"spot", cones}});
  b.add_root({{"extensions", {{"KHR_lights_punctual", {{"light", spot}}}}}});
  expect_scene_error(b.write_gltf(test_dir(), "cones"), {"lights[0]", "inner < outer"});
}

TEST(GltfLoader, OrthographicCameraIsIgnoredWithAWarning) {
  GltfBuilder b = lit_quad();
  b.add("cameras", {{"type", "orthographic"},
                    {"orthographic", {{"xmag", 1.0}, {"ymag", 1.0}, {"znear", 0.1}, {"zfar", 10.0}}}});
  b.add_root({{"camera", 0}});
  const LoadedScene loaded = load_gltf(b.write_gltf(test_dir(), "ortho").string());
  EXPECT_FALSE(loaded.scene.camera.has_value());
  EXPECT_EQ(warnings_with(loaded, "orthographic camera"), 1u);
}

TEST(GltfLoader, MaterialsMapOntoTheFourModels) {
  GltfBuilder b = lit_quad();
  auto quad_with = [&b](json material) {
    b.add_root({{"mesh", b.add_quad_mesh(b.add("materials", material))}});
  };
  quad_with({{"pbrMetallicRoughness", {{"baseColorFactor", {0.9, 0.8, 0.7, 1}}, {"roughnessFactor", 0.5}}}});
  quad_with({{"pbrMetallicRoughness", {{"roughnessFactor", 0.0}}}});
  quad_with({{"extensions", {{"KHR_materials_transmission", {{"transmissionFactor", 1.0}}},
                             {"KHR_materials_ior", {{"ior", 1.33}}}}}});
  quad_with(json::object());  // no pbrMetallicRoughness: glTF defaults
  quad_with({{"pbrMetallicRoughness", {{"metallicFactor", 0.7}}}});
  quad_with({{"pbrMetallicRoughness", {{"metallicFactor", 0.3}}}});
  quad_with({{"alphaMode", "BLEND"}});
  quad_with({{"alphaMode", "MASK"}, {"alphaCutoff", 0.3}, {"doubleSided", true}});
  b.add_root({{"mesh", b.add_quad_mesh()}});  // no material
  const LoadedScene loaded = load_gltf(b.write_gltf(test_dir(), "materials").string());
  const std::vector<Material>& m = loaded.scene.materials;
  ASSERT_EQ(m.size(), 10u);  // nine from the file, then the default
  EXPECT_EQ(m[1].type, MaterialType::Conductor);
  EXPECT_FLOAT_EQ(m[1].alpha, 0.25f);
  expect_near(m[1].base_color, {0.9f, 0.8f, 0.7f});
  EXPECT_EQ(m[2].type, MaterialType::Mirror);
  EXPECT_EQ(m[3].type, MaterialType::Glass);
  EXPECT_FLOAT_EQ(m[3].ior, 1.33f);
  EXPECT_EQ(m[4].type, MaterialType::Conductor);
  EXPECT_FLOAT_EQ(m[4].alpha, 1.0f);
  expect_near(m[4].base_color, {1, 1, 1});
  EXPECT_EQ(m[5].type, MaterialType::Conductor);
  EXPECT_EQ(m[6].type, MaterialType::Diffuse);
  EXPECT_EQ(warnings_with(loaded, "metallicFactor between 0 and 1"), 1u);
  EXPECT_TRUE(m[7].alpha_mask);
  EXPECT_FLOAT_EQ(m[7].alpha_cutoff, 0.5f);
  EXPECT_EQ(warnings_with(loaded, "BLEND"), 1u);
  EXPECT_TRUE(m[8].alpha_mask);
  EXPECT_FLOAT_EQ(m[8].alpha_cutoff, 0.3f);
  EXPECT_TRUE(m[8].double_sided);
  EXPECT_EQ(m[9].type, MaterialType::Conductor);
  EXPECT_FALSE(m[9].double_sided);
  EXPECT_EQ(loaded.scene.triangle_material.back(), 9u);
}

// 2x1 RGBA PNG: (128, 0, 255, 255) then (0, 64, 0, 128).
fs::path write_png(const fs::path& path) {
  const unsigned char pixels[8] = {128, 0, 255, 255, 0, 64, 0, 128};
  auto out = OIIO::ImageOutput::create(path.string());
  OIIO::ImageSpec spec(2, 1, 4, OIIO::TypeDesc::UINT8);
  spec.attribute("oiio:UnassociatedAlpha", 1);  // store the bytes as given
  EXPECT_TRUE(out && out->open(path.string(), spec));
  EXPECT_TRUE(out->write_image(OIIO::TypeDesc::UINT8, pixels));
  out->close();
  return path;
}

float srgb(float c) { return std::pow((c + 0.055f) / 1.055f, 2.4f); }

void expect_decoded_png(const LoadedScene& loaded) {
  ASSERT_EQ(loaded.scene.textures.size(), 1u);
  const Texture& t = loaded.scene.textures[0];
  ASSERT_EQ(t.width, 2);
  ASSERT_EQ(t.height, 1);
  EXPECT_NEAR(t.texels[0].r, srgb(128.0f / 255.0f), 1e-4f);  // sRGB decoded
  EXPECT_NEAR(t.texels[0].b, 1.0f, 1e-6f);
  EXPECT_NEAR(t.texels[1].a, 128.0f / 255.0f, 1e-6f);  // alpha stays linear
  EXPECT_EQ(loaded.scene.materials[1].base_color_texture, 0);
}

json textured_material() {
  return {{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}, {"metallicFactor", 0}}},
          {"normalTexture", {{"index", 0}}}};
}

// The lit quad with a textured material whose image is `uri`.
GltfBuilder textured_quad(const std::string& uri) {
  GltfBuilder b = lit_quad();
  b.add_root({{"mesh", b.add_quad_mesh(b.add("materials", textured_material()))}});
  b.add("images", {{"uri", uri}});
  b.add("textures", {{"source", 0}});
  return b;
}

TEST(GltfLoader, BaseColorTextureFromFileIsLinear) {
  const fs::path dir = test_dir();
  GltfBuilder b = lit_quad();
  b.add_root({{"mesh", b.add_quad_mesh(b.add("materials", textured_material()))}});
  b.add("images", {{"uri", write_png(dir / "texture.png").filename().string()}});
  b.add("samplers", {{"magFilter", 9728}});  // NEAREST
  b.add("textures", {{"source", 0}, {"sampler", 0}});
  const LoadedScene loaded = load_gltf(b.write_gltf(dir, "textured").string());
  expect_decoded_png(loaded);
  EXPECT_EQ(warnings_with(loaded, "filter"), 1u);
  EXPECT_EQ(warnings_with(loaded, "normalTexture ignored"), 1u);
}

TEST(GltfLoader, BaseColorTextureInGlbBufferView) {
  const fs::path dir = test_dir();
  const std::vector<unsigned char> png = read_file_bytes(write_png(dir / "texture.png").string()).value();
  GltfBuilder b = lit_quad();
  b.add_root({{"mesh", b.add_quad_mesh(b.add("materials", textured_material()))}});
  b.add("images", {{"bufferView", b.add_view(png.data(), png.size())}, {"mimeType", "image/png"}});
  b.add("textures", {{"source", 0}});
  expect_decoded_png(load_gltf(b.write_glb(dir, "textured").string()));
}

// What workers get of a .gltf with files beside it: one .glb that loads as the same scene from any folder.
TEST(GltfLoader, AGltfWithExternalBufferAndImagePacksIntoOneGlbThatLoadsTheSame) {
  const fs::path dir = test_dir();
  GltfBuilder b = lit_quad();
  b.add_root({{"mesh", b.add_quad_mesh(b.add("materials", textured_material()))}});
  b.add("images", {{"uri", write_png(dir / "texture.png").filename().string()}});
  b.add("textures", {{"source", 0}});
  const fs::path gltf = b.write_gltf(dir, "textured");
  const SceneFile file = scene_file_for_workers(gltf.string());
  EXPECT_TRUE(file.packed);
  EXPECT_EQ(file.name, "textured.glb");
  fs::create_directories(dir / "elsewhere");
  const fs::path glb = dir / "elsewhere" / file.name;
  write_bytes(glb, file.bytes);
  const LoadedScene original = load_gltf(gltf.string()), packed = load_gltf(glb.string());
  expect_decoded_png(packed);
  ASSERT_EQ(packed.scene.triangles.size(), original.scene.triangles.size());
  EXPECT_EQ(std::memcmp(packed.scene.triangles.data(), original.scene.triangles.data(),
                        original.scene.triangles.size() * sizeof(original.scene.triangles[0])), 0);
  EXPECT_EQ(packed.scene.textures[0].texels.size(), original.scene.textures[0].texels.size());
  EXPECT_FALSE(scene_file_for_workers(glb.string()).packed) << "a .glb goes as it is";
  fs::remove(dir / "texture.png");
  try {
    scene_file_for_workers(gltf.string());
    ADD_FAILURE() << "a missing image packed";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("'texture.png'"), std::string::npos) << e.what();
  }
}

TEST(GltfLoader, UnknownExtensionWarnsOnceByName) {
  GltfBuilder b = lit_quad();
  b.doc["extensionsUsed"].push_back("EXT_made_up");
  b.doc["materials"][0]["extensions"]["EXT_made_up"] = json::object();
  b.doc["nodes"][0]["extensions"]["EXT_made_up"] = {{"x", 1}};
  const LoadedScene loaded = load_gltf(b.write_gltf(test_dir(), "extension").string());
  EXPECT_EQ(warnings_with(loaded, "EXT_made_up"), 1u);
  EXPECT_EQ(loaded.warnings.size(), 1u) << "known extensions must not warn";
}

TEST(GltfLoader, IgnoredFeaturesWarnOncePerFeature) {
  GltfBuilder b = lit_quad();
  const int uv1 = b.add_floats({0, 0, 1, 0, 1, 1, 0, 1}, "VEC2");
  b.doc["meshes"][0]["primitives"][0]["attributes"]["TEXCOORD_1"] = uv1;
  b.doc["meshes"][0]["primitives"][0]["attributes"]["TEXCOORD_2"] = uv1;
  json lines = b.doc["meshes"][0]["primitives"][0];
  lines["mode"] = 1;
  b.doc["meshes"][0]["primitives"].push_back(lines);
  b.doc["meshes"][0]["primitives"].push_back(lines);
  const LoadedScene loaded = load_gltf(b.write_gltf(test_dir(), "features").string());
  EXPECT_EQ(loaded.scene.triangles.size(), 2u);
  EXPECT_EQ(warnings_with(loaded, "TEXCOORD_n"), 1u);
  EXPECT_EQ(warnings_with(loaded, "LINES"), 1u);
}

TEST(GltfLoader, ZeroAreaTrianglesAreDroppedWithOneWarning) {
  GltfBuilder b;
  const std::vector<uint32_t> indices = {0, 1, 2, 1, 1, 2, 0, 2, 3, 3, 3, 3};
  b.add_root({{"mesh", b.add_quad_mesh(b.add("materials", emissive_material()), indices)}});
  const LoadedScene loaded = load_gltf(b.write_gltf(test_dir(), "degenerate").string());
  EXPECT_EQ(loaded.scene.triangles.size(), 2u);
  EXPECT_EQ(warnings_with(loaded, "dropped 2 zero-area triangles"), 1u);
}

TEST(GltfLoader, NonFiniteNormalIsReplacedByGeometricNormal) {
  GltfBuilder b = lit_quad();
  const float nan = std::numeric_limits<float>::quiet_NaN();
  std::memcpy(b.bin.data() + 48, &nan, sizeof(float));  // NORMAL[0].x
  const LoadedScene loaded = load_gltf(b.write_gltf(test_dir(), "normals").string());
  expect_near(loaded.scene.normals[0], {0, 0, 1});
  EXPECT_EQ(warnings_with(loaded, "replaced 1 non-finite"), 1u);
}

TEST(GltfLoader, MissingFileIsAnError) {
  expect_scene_error(test_dir() / "absent.gltf", {"no such file"});
}

// A scene in another format, or a mistyped built-in name: the error says
// what is read and what to do, not a JSON parse error or "no such file".
TEST(GltfLoader, OtherFormatsAndMistypedBuiltInsSayWhatToDo) {
  const fs::path ply = test_dir() / "cube.ply";
  std::ofstream(ply) << "ply\nformat ascii 1.0\nelement vertex 0\nend_header\n";
  auto error_of = [](const std::string& name) -> std::string {
    try {
      load_scene(name);
    } catch (const SceneError& e) {
      return e.what();
    }
    return "";
  };
  const std::string on_ply = error_of(ply.string());
  for (const char* fragment : {"cube.ply", "glTF 2.0", "OBJ (.obj)", "not .ply", "Blender", "File > Export"})
    EXPECT_NE(on_ply.find(fragment), std::string::npos) << "'" << fragment << "' missing in: " << on_ply;
  EXPECT_EQ(on_ply.find("parse error"), std::string::npos) << on_ply;
  const fs::path blend = test_dir() / "scene.blend";
  std::ofstream(blend) << "BLENDER";
  const std::string on_blend = error_of(blend.string());
  EXPECT_NE(on_blend.find("blender -b"), std::string::npos) << on_blend;
  EXPECT_NE(on_blend.find("export_scene.gltf"), std::string::npos) << on_blend;
  const std::string on_typo = error_of("cornel");
  for (const char* fragment : {"cornel:", "no built-in scene", "glossy-rough", "Did you mean 'cornell'?"})
    EXPECT_NE(on_typo.find(fragment), std::string::npos) << "'" << fragment << "' missing in: " << on_typo;
  const std::string on_far = error_of("zzzzzzzz");
  EXPECT_NE(on_far.find("Built-in scenes:"), std::string::npos) << on_far;
  EXPECT_EQ(on_far.find("Did you mean"), std::string::npos) << on_far;  // nothing near: no guess
  // A glTF path that is missing still says so.
  EXPECT_NE(error_of((test_dir() / "absent.glb").string()).find("no such file"), std::string::npos);
}

TEST(GltfLoader, JsonSyntaxErrorIsAnError) {
  const fs::path path = test_dir() / "broken.gltf";
  std::ofstream(path) << "{ \"asset\": { \"version\": \"2.0\" }, ";
  expect_scene_error(path, {"parse error"});
}

TEST(GltfLoader, TruncatedGlbIsAnError) {
  const fs::path dir = test_dir();
  const fs::path path = lit_quad().write_glb(dir, "truncated");
  fs::resize_file(path, fs::file_size(path) - 16);
  expect_scene_error(path, {"GLB header", "truncated"});
  fs::resize_file(path, 10);
  expect_scene_error(path, {"GLB header", "truncated"});
}

TEST(GltfLoader, MissingBinIsAnError) {
  const fs::path dir = test_dir();
  const fs::path path = lit_quad().write_gltf(dir, "nobin");
  fs::remove(dir / "nobin.bin");
  expect_scene_error(path, {"nobin.bin"});
}

TEST(GltfLoader, AccessorBeyondItsBufferViewIsAnError) {
  GltfBuilder b = lit_quad();
  b.doc["accessors"][1]["count"] = 1000;
  expect_scene_error(b.write_gltf(test_dir(), "accessor"),
                     {"accessors[1]", "NORMAL", "count 1000", "bufferView 1"});
}

TEST(GltfLoader, HugeAccessorCountIsRejectedBeforeAllocating) {
  const fs::path dir = test_dir();
  for (uint64_t count : {uint64_t(1) << 30, uint64_t(1) << 61}) {
    GltfBuilder b = lit_quad();
    b.doc["accessors"][0]["count"] = count;
    expect_scene_error(b.write_gltf(dir, "huge"),
                       {"accessors[0]", "POSITION", "count " + std::to_string(count)});
  }
}

TEST(GltfLoader, IndexPastVertexCountIsAnError) {
  GltfBuilder b;
  b.add_root({{"mesh", b.add_quad_mesh(b.add("materials", emissive_material()), {0, 1, 2, 0, 2, 7})}});
  expect_scene_error(b.write_gltf(test_dir(), "indices"),
                     {"accessors[3]", "indices", "index 7", "4 vertices"});
}

TEST(GltfLoader, NanPositionIsAnError) {
  GltfBuilder b = lit_quad();
  const float nan = std::numeric_limits<float>::quiet_NaN();
  std::memcpy(b.bin.data() + 12, &nan, sizeof(float));  // POSITION[1].x
  expect_scene_error(b.write_gltf(test_dir(), "nan"),
                     {"accessors[0]", "POSITION", "element 1 is not finite"});
}

TEST(GltfLoader, WrongPositionTypeIsAnError) {
  GltfBuilder b = lit_quad();
  b.doc["accessors"][0]["type"] = "VEC2";
  expect_scene_error(b.write_gltf(test_dir(), "type"), {"accessors[0]", "POSITION", "VEC2", "expected VEC3"});
  b.doc["accessors"][0]["type"] = "VEC3";
  b.doc["accessors"][0]["componentType"] = 5123;  // UNSIGNED_SHORT
  expect_scene_error(b.write_gltf(test_dir(), "type"), {"accessors[0]", "UNSIGNED_SHORT", "expected FLOAT"});
}

TEST(GltfLoader, BufferViewBeyondItsBufferIsAnError) {
  GltfBuilder b = lit_quad();
  b.doc["bufferViews"][2]["byteLength"] = 4096;
  expect_scene_error(b.write_gltf(test_dir(), "view"), {"bufferViews[2]", "exceeds buffer 0"});
}

TEST(GltfLoader, SceneWithoutGeometryIsAnError) {
  GltfBuilder b;
  b.add_root({{"extensions", {{"KHR_lights_punctual", {{"light", b.add_light({{"type", "point"}})}}}}}});
  expect_scene_error(b.write_gltf(test_dir(), "empty"), {"no geometry"});
}

// A texture the file asks for and the loader cannot read is broken input: an
// error, not a silent fallback to baseColorFactor.
TEST(GltfLoader, MissingTextureFileIsAnError) {
  GltfBuilder b = textured_quad("absent.png");
  expect_scene_error(b.write_gltf(test_dir(), "textured"), {"images[0]", "'absent.png'", "missing"});
}

TEST(GltfLoader, UndecodableTextureIsAnError) {
  const fs::path dir = test_dir();
  GltfBuilder b = textured_quad("texture.png");
  write_bytes(dir / "texture.png", {'n', 'o', 't', ' ', 'a', 'n', ' ', 'i', 'm', 'a', 'g', 'e'});
  expect_scene_error(b.write_gltf(dir, "garbage"), {"images[0]", "'texture.png'", "neither a PNG nor a JPEG"});
  // A PNG header over broken data.
  std::vector<unsigned char> png = read_file_bytes(write_png(dir / "texture.png").string()).value();
  png.resize(40);
  write_bytes(dir / "texture.png", png);
  expect_scene_error(b.write_gltf(dir, "cut"), {"images[0]", "'texture.png'", "cannot be decoded"});
}

TEST(GltfLoader, TextureHeaderTooLargeIsRejectedBeforeDecoding) {
  const fs::path dir = test_dir();
  std::vector<unsigned char> png = read_file_bytes(write_png(dir / "texture.png").string()).value();
  for (int at : {16, 20}) png[size_t(at)] = 0x7f;  // IHDR width and height: about 2^31
  write_bytes(dir / "texture.png", png);
  GltfBuilder b = textured_quad("texture.png");
  expect_scene_error(b.write_gltf(dir, "huge"), {"images[0]", "at most 2^26 pixels"});
}

// A flat side x side RGB JPEG, at OIIO's default quality.
std::vector<unsigned char> flat_jpeg(const fs::path& path, int side) {
  const std::vector<unsigned char> pixels(size_t(side) * size_t(side) * 3, 90);
  auto out = OIIO::ImageOutput::create(path.string());
  EXPECT_TRUE(out && out->open(path.string(), OIIO::ImageSpec(side, side, 3, OIIO::TypeDesc::UINT8)));
  EXPECT_TRUE(out->write_image(OIIO::TypeDesc::UINT8, pixels.data()));
  out->close();
  return read_file_bytes(path.string()).value();
}

// stb decodes a JPEG whose scan data is cut short as if it were all there: a
// header that claims 8000 x 8000 over a few hundred bytes would cost seconds
// and 1.4 GB. The loader refuses more pixels than the file can hold, and
// still loads a flat image (the most compressible kind a user brings).
TEST(GltfLoader, TextureClaimingMorePixelsThanItsBytesHoldIsRejectedBeforeDecoding) {
  const fs::path dir = test_dir();
  GltfBuilder b = textured_quad("texture.jpg");
  std::vector<unsigned char> jpeg = flat_jpeg(dir / "texture.jpg", 512);
  const LoadedScene flat = load_gltf(b.write_gltf(dir, "flat"));
  ASSERT_EQ(flat.scene.textures.size(), 1u);
  EXPECT_EQ(flat.scene.textures[0].width, 512);
  EXPECT_GT(512 * 512 / double(jpeg.size()), 20.0) << "the flat JPEG should be a compressible one";

  jpeg = flat_jpeg(dir / "texture.jpg", 16);
  for (size_t at = 2; at + 9 <= jpeg.size(); at += 2 + size_t(jpeg[at + 2] << 8 | jpeg[at + 3])) {
    ASSERT_EQ(jpeg[at], 0xFF);
    if (jpeg[at + 1] != 0xC0) continue;  // baseline start of frame: height, then width
    for (size_t i : {at + 5, at + 7}) { jpeg[i] = 8000 >> 8; jpeg[i + 1] = 8000 & 0xFF; }
    break;
  }
  write_bytes(dir / "texture.jpg", jpeg);
  expect_scene_error(b.write_gltf(dir, "bomb"),
                     {"images[0]", "8000 x 8000 pixels in", "more than a JPEG file of that size can hold"});
}

// A scene may name files beside it, never elsewhere: a scene from a peer
// must not read the machine's other files.
TEST(GltfLoader, ExternalFileOutsideTheSceneFolderIsRefused) {
  const fs::path dir = test_dir();
  fs::create_directories(dir / "scene");
  GltfBuilder b = lit_quad();
  b.write_gltf(dir, "quad");  // quad.bin beside scene/, not in it
  b.doc["buffers"][0]["uri"] = "../quad.bin";
  const fs::path path = dir / "scene" / "up.gltf";
  std::ofstream(path) << b.doc.dump();
  expect_scene_error(path, {"quad.bin", "refused: outside the scene's folder"});
}

TEST(GltfLoader, MemoryLoadResolvesExternalFilesOnlyInItsFolder) {
  const fs::path dir = test_dir();
  const fs::path path = lit_quad().write_gltf(dir, "quad");
  const std::vector<uint8_t> bytes = read_file_bytes(path.string()).value();
  EXPECT_EQ(load_gltf_memory(bytes, "quad.gltf", dir.string()).scene.triangles.size(), 2u);
  try {
    load_gltf_memory(bytes, "quad.gltf");
    ADD_FAILURE() << "an external buffer loaded without a resource folder";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("quad.gltf: "), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("quad.bin"), std::string::npos) << e.what();
  }
}

TEST(GltfLoader, CoordinatesBeyondFloatRangeAreAnError) {
  GltfBuilder b = lit_quad();
  b.doc["nodes"][0]["translation"] = {1e20, 0, 0};
  expect_scene_error(b.write_gltf(test_dir(), "far"), {"world-space vertex 0", "within +-1e15 m"});
  GltfBuilder camera = lit_quad();
  camera.add("cameras", {{"type", "perspective"}, {"perspective", {{"yfov", 0.8}, {"znear", 0.1}}}});
  camera.add_root({{"camera", 0}, {"translation", {0, 0, 1e300}}});
  expect_scene_error(camera.write_gltf(test_dir(), "camera"), {"nodes[1]", "cameras[0]", "within +-1e15 m"});
}

TEST(GltfLoader, InfiniteLightIntensityIsAnError) {
  GltfBuilder b = lit_quad();
  b.add_root({{"extensions", {{"KHR_lights_punctual",
                               {{"light", b.add_light({{"type", "point"}, {"intensity", 1e300}})}}}}}});
  expect_scene_error(b.write_gltf(test_dir(), "bright"), {"lights[0]", "not finite"});
}

// Float underflow: the triangles have area in double, none in the renderer's
// float arithmetic, so the emitter cannot be sampled and the scene has no light.
TEST(GltfLoader, EmitterTooSmallForFloatIsNoLight) {
  GltfBuilder b = lit_quad();
  b.doc["nodes"][0]["scale"] = {1e-30, 1e-30, 1e-30};
  b.add_root({{"mesh", b.add_quad_mesh(b.add("materials", diffuse_material()))}});
  const LoadedScene loaded = load_gltf(b.write_gltf(test_dir(), "tiny").string());
  ASSERT_EQ(loaded.scene.lights.size(), 1u) << "the supplied sun";
  EXPECT_EQ(loaded.scene.lights[0].type, LightType::Directional);
  ASSERT_FALSE(loaded.notices.empty());
  EXPECT_NE(loaded.notices[0].find("no light"), std::string::npos) << loaded.notices[0];
}

// The document's text with `placeholder` (a JSON string) replaced by `text`:
// nesting too deep for nlohmann::json to write.
std::string with_text(const json& doc, const std::string& placeholder, const std::string& text) {
  std::string dumped = doc.dump();
  const std::string quoted = "\"" + placeholder + "\"";
  dumped.replace(dumped.find(quoted), quoted.size(), text);
  return dumped;
}

std::string nested_arrays(int depth) { return std::string(size_t(depth), '[') + std::string(size_t(depth), ']'); }

// tinygltf converts extras and extensions recursively: 20,000 levels overflowed
// the stack (SIGSEGV). They are refused from a scan of the bytes first.
TEST(GltfLoader, JsonNestedTooDeepIsRefusedBeforeParsing) {
  const fs::path dir = test_dir();
  GltfBuilder b = lit_quad();
  b.doc["nodes"][0]["extras"] = "DEEP";
  const fs::path gltf = b.write_gltf(dir, "deep-extras");
  std::ofstream(gltf) << with_text(b.doc, "DEEP", nested_arrays(20000));
  expect_scene_error(gltf, {"JSON", "nested deeper than 64 levels"});

  GltfBuilder glb = lit_quad();
  glb.doc["extensions"]["EXT_deep"] = "DEEP";
  std::string objects;
  for (int i = 0; i < 20000; ++i) objects += "{\"a\":";
  objects += "0" + std::string(20000, '}');
  const fs::path binary =
      glb.write_glb(dir, "deep-extensions", [&objects](const json& d) { return with_text(d, "DEEP", objects); });
  expect_scene_error(binary, {"JSON", "nested deeper than 64 levels"});
}

// The scan counts brackets outside strings only, escaped quotes included.
TEST(GltfLoader, BracketsInsideStringsAndModestNestingLoad) {
  GltfBuilder b = lit_quad();
  b.doc["nodes"][0]["extras"] = {{"note", std::string(200, '[') + "\\\"[[[{{{" + std::string(200, '{')},
                                 {"nested", "NESTED"}};
  const fs::path path = b.write_gltf(test_dir(), "strings");
  std::ofstream(path) << with_text(b.doc, "NESTED", nested_arrays(kMaxJsonDepth - 4));
  EXPECT_EQ(load_gltf(path.string()).scene.triangles.size(), 2u);
}

// tinygltf reads a negative or fractional offset as absent (0): glTF asks for integers >= 0.
TEST(GltfLoader, NegativeOrFractionalOffsetsAndStridesAreAnError) {
  const fs::path dir = test_dir();
  GltfBuilder offset = lit_quad();
  offset.doc["accessors"][0]["byteOffset"] = -12;
  expect_scene_error(offset.write_gltf(dir, "offset"), {"accessors[0]", "byteOffset -12", "expected an integer >= 0"});
  GltfBuilder view = lit_quad();
  view.doc["bufferViews"][1]["byteOffset"] = -48;
  expect_scene_error(view.write_gltf(dir, "view"), {"bufferViews[1]", "byteOffset -48"});
  GltfBuilder stride = lit_quad();
  stride.doc["bufferViews"][0]["byteStride"] = 12.5;
  expect_scene_error(stride.write_glb(dir, "stride"), {"bufferViews[0]", "byteStride 12.5"});
}

// glTF: a loader must refuse a file whose extensionsRequired it does not support.
TEST(GltfLoader, UnsupportedRequiredExtensionIsAnError) {
  GltfBuilder b = lit_quad();
  b.doc["extensionsUsed"].push_back("EXT_made_up");
  b.doc["extensionsRequired"] = json::array({"KHR_materials_emissive_strength", "EXT_made_up"});
  expect_scene_error(b.write_gltf(test_dir(), "required"),
                     {"extensionsRequired[1]", "EXT_made_up is required but not supported"});
  GltfBuilder supported = lit_quad();
  supported.doc["extensionsRequired"] = json::array({"KHR_materials_emissive_strength"});
  EXPECT_TRUE(load_gltf(supported.write_gltf(test_dir(), "supported").string()).warnings.empty());
}

// 4,000 instances of a 50,000-triangle mesh: 200 million triangles from a
// 1 MB file, refused by count before a vertex is expanded (Embree ran out of
// memory on them and the renderer wrote through the null buffer it returned).
TEST(GltfLoader, InstancedTrianglesOverTheBudgetAreRefusedBeforeExpanding) {
  GltfBuilder b;
  std::vector<uint32_t> indices;
  for (int t = 0; t < 50000; ++t) indices.insert(indices.end(), {0, 1, 2});
  const int mesh = b.add_quad_mesh(b.add("materials", emissive_material()), indices);
  for (int i = 0; i < 4000; ++i) b.add_root({{"mesh", mesh}, {"translation", {i, 0, 0}}});
  expect_scene_error(b.write_glb(test_dir(), "instances"),
                     {"200000000 triangles", "over the limit of " + std::to_string(kMaxTriangles) + " triangles"});
}

}  // namespace
}  // namespace igi
