// glTF materials as files have them: metallic-roughness and normal textures,
// KHR_texture_transform, AMD_split_roughnessMetallic's BC4 DDS maps, emissive
// textures, required extensions (--ignore-extension) and what a master packs
// for its workers. Each is read back where shading reads it: surface_at.
#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <OpenImageIO/imageio.h>

#include "io/file_bytes.h"
#include "scene/gltf_loader.h"
#include "scene/gltf_pack.h"
#include "scene/gltf_writer.h"
#include "scene/surface.h"
#include "scene/texture_decode.h"
#include "support/gltf_builder.h"
#include "support/image_compare.h"

namespace igi {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;
using GltfBuilder = test::GltfFile;

fs::path test_dir() { return test::fresh_test_dir("gltf_materials"); }

// An RGBA PNG of w x h texels, the bytes stored as given.
std::string write_png(const fs::path& path, int w, int h, const std::vector<unsigned char>& rgba) {
  auto out = OIIO::ImageOutput::create(path.string());
  OIIO::ImageSpec spec(w, h, 4, OIIO::TypeDesc::UINT8);
  spec.attribute("oiio:UnassociatedAlpha", 1);
  EXPECT_TRUE(out && out->open(path.string(), spec));
  EXPECT_TRUE(out->write_image(OIIO::TypeDesc::UINT8, rgba.data()));
  out->close();
  return path.filename().string();
}

// A DDS file of one 4 x 4 BC4 block (DX10 header, DXGI_FORMAT_BC4_UNORM).
std::vector<unsigned char> bc4_dds(const std::vector<unsigned char>& block) {
  std::vector<unsigned char> dds(148, 0);
  auto u32 = [&dds](size_t at, uint32_t v) { for (int i = 0; i < 4; ++i) dds[at + size_t(i)] = (v >> (8 * i)) & 0xff; };
  dds[0] = 'D', dds[1] = 'D', dds[2] = 'S', dds[3] = ' ';
  u32(4, 124), u32(12, 4), u32(16, 4), u32(28, 1), u32(76, 32), u32(80, 4);
  dds[84] = 'D', dds[85] = 'X', dds[86] = '1', dds[87] = '0';
  u32(128, 80), u32(132, 3), u32(140, 1);
  dds.insert(dds.end(), block.begin(), block.end());
  return dds;
}

// The quad's material (triangle 0: uv = (b1 + b2, b2)) under a white sky.
GltfBuilder quad_with(const json& material) {
  GltfBuilder b;
  b.add_root({{"mesh", b.add_quad_mesh(b.add("materials", material))}});
  return b;
}

LoadedScene load(const fs::path& path, std::vector<std::string> ignored = {}) {
  GltfOptions options;
  options.environment = glm::vec3(1.0f);
  options.camera_given = true;
  options.ignored_extensions = std::move(ignored);
  return load_gltf(path.string(), options);
}

// What shading sees at uv on triangle 0, looking straight down onto it.
SurfacePoint surface(const Scene& scene, glm::vec2 uv) {
  Hit hit{1.0f, 0, {uv.x - uv.y, uv.y}};
  return surface_at(scene, hit, glm::vec3(0.0f, 0.0f, -1.0f));
}

size_t lines_with(const std::vector<std::string>& lines, const std::string& text) {
  size_t n = 0;
  for (const std::string& line : lines) n += line.find(text) != std::string::npos;
  return n;
}

// Blue metallic, green roughness, linear, times the factors; the transform's offset moves the lookup.
TEST(GltfMaterials, MetallicRoughnessTextureWithItsTransform) {
  const fs::path dir = test_dir();
  const std::string png = write_png(dir / "mr.png", 2, 1, {0, 128, 255, 255, 0, 255, 0, 255});
  const json pbr = {{"metallicFactor", 0.8}, {"roughnessFactor", 0.5}, {"metallicRoughnessTexture", {{"index", 0}}}};
  GltfBuilder b = quad_with({{"pbrMetallicRoughness", pbr}});
  b.add("images", {{"uri", png}});
  b.add("textures", {{"source", 0}});
  const LoadedScene plain = load(b.write_gltf(dir, "plain"));
  const SurfacePoint left = surface(plain.scene, {0.25f, 0.1f}), right = surface(plain.scene, {0.75f, 0.1f});
  EXPECT_EQ(left.material->type, MaterialType::MetallicRoughness);
  EXPECT_NEAR(left.metallic, 0.8f, 1e-5f);
  EXPECT_NEAR(left.alpha, std::pow(0.5f * 128.0f / 255.0f, 2.0f), 1e-5f) << "green read linearly, alpha = roughness^2";
  EXPECT_NEAR(right.metallic, 0.0f, 1e-6f);
  EXPECT_NEAR(right.alpha, 0.25f, 1e-5f);
  b.doc["materials"][0]["pbrMetallicRoughness"]["metallicRoughnessTexture"]["extensions"] = {
      {"KHR_texture_transform", {{"offset", {0.5, 0.0}}}}};
  b.doc["extensionsUsed"] = {"KHR_texture_transform"};
  const LoadedScene moved = load(b.write_gltf(dir, "moved"));
  EXPECT_TRUE(moved.warnings.empty()) << moved.warnings.front();
  EXPECT_NEAR(surface(moved.scene, {0.25f, 0.1f}).metallic, 0.0f, 1e-6f) << "offset 0.5: the right texel";
  EXPECT_NEAR(surface(moved.scene, {0.75f, 0.1f}).metallic, 0.8f, 1e-5f);
}

// x along increasing u, y along decreasing v (glTF's v runs down the image), scaled by `scale`.
TEST(GltfMaterials, NormalMapBendsTheShadingNormal) {
  const fs::path dir = test_dir();
  const std::string png = write_png(dir / "n.png", 2, 1, {218, 128, 218, 255, 128, 218, 218, 255});
  GltfBuilder b = quad_with({{"pbrMetallicRoughness", {{"metallicFactor", 0.0}}},
                             {"normalTexture", {{"index", 0}, {"scale", 1.0}}}});
  b.add("images", {{"uri", png}});
  b.add("textures", {{"source", 0}});
  const LoadedScene loaded = load(b.write_gltf(dir, "bent"));
  const float c = 2.0f * 218.0f / 255.0f - 1.0f;  // 45 degrees
  const glm::vec3 along_u = surface(loaded.scene, {0.25f, 0.1f}).shading_normal;
  EXPECT_NEAR(along_u.x, c / std::sqrt(2.0f * c * c), 0.01f);  // the quad's u runs along +x
  EXPECT_NEAR(along_u.z, c / std::sqrt(2.0f * c * c), 0.01f);
  const glm::vec3 along_v = surface(loaded.scene, {0.75f, 0.1f}).shading_normal;
  EXPECT_NEAR(along_v.y, -0.707f, 0.01f) << "its v runs along +y: the map's y leans to -y";
  b.doc["materials"][0]["normalTexture"]["scale"] = 0.5;
  const LoadedScene half = load(b.write_gltf(dir, "half"));
  EXPECT_NEAR(surface(half.scene, {0.25f, 0.1f}).shading_normal.x, 0.5f * c / std::sqrt(0.25f * c * c + c * c), 0.01f);
  EXPECT_EQ(surface(half.scene, {0.25f, 0.1f}).geometric_normal, glm::vec3(0, 0, 1));
}

TEST(GltfMaterials, Bc4BlocksDecodeAsTheirPalette) {
  // r0 > r1: eight values; texel i takes index i for i < 8 (3 bits each, little-endian).
  uint64_t bits = 0;
  for (uint64_t i = 0; i < 8; ++i) bits |= i << (3 * i);
  std::vector<unsigned char> block = {200, 100};
  for (int i = 0; i < 6; ++i) block.push_back((bits >> (8 * i)) & 0xff);
  const std::vector<unsigned char> dds = bc4_dds(block);
  const Texture t = decode_dds_bc4(dds.data(), dds.size(), "t.dds", GltfDiagnostics{});
  ASSERT_EQ(t.width, 4);
  const int expected[8] = {200, 100, 186, 171, 157, 143, 129, 114};
  for (int i = 0; i < 8; ++i) EXPECT_NEAR(t.texel(i % 4, i / 4).y * 255.0f, expected[i], 1e-3f) << "index " << i;
  std::vector<unsigned char> cut = dds;
  cut.resize(150);
  EXPECT_THROW(decode_dds_bc4(cut.data(), cut.size(), "t.dds", GltfDiagnostics{}), SceneError);
}

// Sponza's: a roughness map that only a BC4 DDS holds (MSFT_texture_dds), beside the core material.
TEST(GltfMaterials, AmdSplitRoughnessMetallicReadsItsDdsMap) {
  const fs::path dir = test_dir();
  test::write_bytes(dir / "rough.dds", bc4_dds({128, 0, 0, 0, 0, 0, 0, 0}));
  const json split = {{"roughnessTexture", {{"index", 0}}}};
  GltfBuilder b = quad_with({{"pbrMetallicRoughness", {{"metallicFactor", 0.0}}},
                             {"extensions", {{"AMD_split_roughnessMetallic", split}}}});
  b.add("images", {{"uri", "rough.dds"}});
  b.add("textures", {{"extensions", {{"MSFT_texture_dds", {{"source", 0}}}}}});
  b.doc["extensionsUsed"] = {"AMD_split_roughnessMetallic", "MSFT_texture_dds"};
  b.doc["extensionsRequired"] = {"AMD_split_roughnessMetallic"};
  const fs::path path = b.write_gltf(dir, "split");
  const LoadedScene loaded = load(path);
  EXPECT_NEAR(surface(loaded.scene, {0.5f, 0.5f}).alpha, std::pow(128.0f / 255.0f, 2.0f), 1e-5f);
  const LoadedScene without = load(path, {"AMD_split_roughnessMetallic"});
  EXPECT_NEAR(surface(without.scene, {0.5f, 0.5f}).alpha, 1.0f, 1e-6f) << "the core material: roughness 1";
  EXPECT_EQ(lines_with(without.warnings, "AMD_split_roughnessMetallic left out (--ignore-extension)"), 1u);
}

// A required extension igi does not read: an error that names the option, which loads it.
TEST(GltfMaterials, AnUnreadRequiredExtensionNamesTheOptionThatLoadsTheFile) {
  const fs::path dir = test_dir();
  GltfBuilder b = quad_with({{"extensions", {{"KHR_materials_sheen", {{"x", 1}}}}}});
  b.doc["extensionsUsed"] = {"KHR_materials_sheen"};
  b.doc["extensionsRequired"] = {"KHR_materials_sheen"};
  const fs::path path = b.write_gltf(dir, "required");
  try {
    load(path);
    ADD_FAILURE() << "a required extension that is not read loaded";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("--ignore-extension KHR_materials_sheen loads it anyway (materials are read"),
              std::string::npos)
        << e.what();
  }
  const LoadedScene loaded = load(path, {"KHR_materials_sheen"});
  EXPECT_EQ(lines_with(loaded.warnings, "KHR_materials_sheen left out (--ignore-extension): materials are read"), 1u);
}

// MSFT_texture_dds required, every texture with a PNG beside its (absent) DDS:
// nothing is lost, so the file loads with notices; a master packs the PNG and
// not the DDS, which is not there.
TEST(GltfMaterials, DdsAlternatesWithCoreSourcesLoadAndPackWithoutTheirDds) {
  const fs::path dir = test_dir();
  const std::string png = write_png(dir / "base.png", 1, 1, {255, 128, 0, 255});
  GltfBuilder b = quad_with({{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}});
  b.add("images", {{"uri", png}});
  b.add("images", {{"uri", "base.dds"}});
  b.add("textures", {{"source", 0}, {"extensions", {{"MSFT_texture_dds", {{"source", 1}}}}}});
  b.doc["extensionsUsed"] = {"MSFT_texture_dds"};
  b.doc["extensionsRequired"] = {"MSFT_texture_dds"};
  const fs::path path = b.write_gltf(dir, "dds");
  const LoadedScene loaded = load(path);
  EXPECT_TRUE(loaded.warnings.empty()) << loaded.warnings.front();
  EXPECT_EQ(lines_with(loaded.notices, "MSFT_texture_dds: textures read their core PNG or JPEG images"), 1u);
  EXPECT_EQ(lines_with(loaded.notices, "1 of the file's 2 images are not there; no material reads them"), 1u);
  const SceneFile file = scene_file_for_workers(path.string());
  EXPECT_TRUE(file.packed);
  fs::create_directories(dir / "worker");
  test::write_bytes(dir / "worker" / file.name, file.bytes);
  const LoadedScene packed = load(dir / "worker" / file.name);
  EXPECT_EQ(packed.scene.textures[0].bytes, loaded.scene.textures[0].bytes);
  EXPECT_EQ(lines_with(packed.notices, "images are not there"), 0u) << "the DDS went as a placeholder";
}

// What the master sends leaves an ignored extension out, so workers read the file as it does.
TEST(GltfMaterials, AnIgnoredExtensionIsLeftOutOfWhatWorkersGet) {
  const fs::path dir = test_dir();
  test::write_bytes(dir / "rough.dds", bc4_dds({128, 0, 0, 0, 0, 0, 0, 0}));
  GltfBuilder b = quad_with({{"pbrMetallicRoughness", {{"metallicFactor", 0.0}}},
                             {"extensions", {{"AMD_split_roughnessMetallic", {{"roughnessTexture", {{"index", 0}}}}}}}});
  b.add("images", {{"uri", "rough.dds"}});
  b.add("textures", {{"extensions", {{"MSFT_texture_dds", {{"source", 0}}}}}});
  b.doc["extensionsUsed"] = {"AMD_split_roughnessMetallic", "MSFT_texture_dds"};
  const std::vector<std::string> ignored = {"AMD_split_roughnessMetallic"};
  for (const fs::path& path : {b.write_gltf(dir, "split"), b.write_glb(dir, "split")}) {
    const SceneFile file = scene_file_for_workers(path.string(), ignored);
    EXPECT_EQ(std::string(file.bytes.begin(), file.bytes.end()).find("AMD_split"), std::string::npos) << path;
    fs::create_directories(dir / "worker");
    test::write_bytes(dir / "worker" / file.name, file.bytes);
    EXPECT_EQ(surface(load(dir / "worker" / file.name).scene, {0.5f, 0.5f}).alpha,
              surface(load(path, ignored).scene, {0.5f, 0.5f}).alpha)
        << path;
  }
}

TEST(GltfMaterials, EmissiveTextureGlowsWithItsMean) {
  const fs::path dir = test_dir();
  const std::string png = write_png(dir / "e.png", 2, 1, {255, 0, 0, 255, 0, 0, 255, 255});
  GltfBuilder b = quad_with({{"emissiveFactor", {1.0, 1.0, 0.5}}, {"emissiveTexture", {{"index", 0}}}});
  b.add("images", {{"uri", png}});
  b.add("textures", {{"source", 0}});
  const LoadedScene loaded = load(b.write_gltf(dir, "glow"));
  const glm::vec3 e = loaded.scene.materials[0].emission;
  EXPECT_NEAR(e.x, 0.5f, 1e-5f);
  EXPECT_NEAR(e.y, 0.0f, 1e-6f);
  EXPECT_NEAR(e.z, 0.25f, 1e-5f);
  EXPECT_EQ(lines_with(loaded.warnings, "emissiveTexture read as its mean colour"), 1u);
}

// --export-gltf writes the model's parameters, textures and transforms back: the same surface.
TEST(GltfMaterials, ExportedMetallicRoughnessReadsBackTheSame) {
  const fs::path dir = test_dir();
  const std::string png = write_png(dir / "mr.png", 2, 1, {0, 128, 255, 255, 0, 255, 0, 255});
  const json info = {{"index", 0}, {"extensions", {{"KHR_texture_transform", {{"offset", {0.25, 0.0}}, {"rotation", 0.3}, {"scale", {2.0, 1.5}}}}}}};
  const json specular = {{"specularFactor", 0.7}, {"specularColorFactor", {1.0, 0.8, 0.6}}};
  GltfBuilder b = quad_with({{"pbrMetallicRoughness", {{"metallicFactor", 0.6}, {"roughnessFactor", 0.7}, {"metallicRoughnessTexture", info}}},
                             {"normalTexture", {{"index", 0}, {"scale", 0.5}}},
                             {"extensions", {{"KHR_materials_specular", specular}, {"KHR_materials_ior", {{"ior", 1.7}}}}}});
  b.add("images", {{"uri", png}});
  b.add("textures", {{"source", 0}});
  b.doc["extensionsUsed"] = {"KHR_texture_transform", "KHR_materials_specular", "KHR_materials_ior"};
  const Scene original = load(b.write_gltf(dir, "original")).scene;
  write_gltf(original, (dir / "exported.gltf").string());
  const Scene exported = load(dir / "exported.gltf").scene;
  for (glm::vec2 uv : {glm::vec2(0.2f, 0.1f), glm::vec2(0.7f, 0.4f)}) {
    const SurfacePoint a = surface(original, uv), e = surface(exported, uv);
    EXPECT_NEAR(a.metallic, e.metallic, 1e-5f);
    EXPECT_NEAR(a.alpha, e.alpha, 1e-5f);
    EXPECT_NEAR(glm::dot(a.shading_normal, e.shading_normal), 1.0f, 1e-5f);
  }
  const Material &m = original.materials[0], &n = exported.materials[0];
  EXPECT_NEAR(m.specular_weight, n.specular_weight, 1e-6f);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(m.specular_f0[c], n.specular_f0[c], 1e-6f);
  EXPECT_FLOAT_EQ(m.ior, n.ior);
}

}  // namespace
}  // namespace igi
