#include "fuzz/seeds.h"

#include <filesystem>

#include <nlohmann/json.hpp>

#include "image/image.h"
#include "protocol/codec.h"
#include "scene/builtin_scenes.h"
#include "scene/gltf_writer.h"
#include "scene/scene_file.h"
#include "support/animated_gltf.h"
#include "viewer/display_messages.h"

namespace igi::fuzz {
namespace {

namespace fs = std::filesystem;
using namespace protocol;

RenderSettings settings() {
  RenderSettings s;
  s.clamp = 0.05f;
  s.compensation_samples = 4;
  s.lightcuts_error = 0.05f;
  s.lightcuts_spacing = 8;
  s.glass_branches = 2;
  s.caustics = true;
  s.caustic_photons = 5000;
  s.caustic_radius = 0.02f;
  s.importance_paths = 256;
  s.bidir_vpls = 32;
  return s;
}

TileResult tile_result() {
  TileResult m;
  m.frame_id = 3;
  m.job_id = 17;
  m.tile = {32, 64, 2, 2, 1};
  m.render_seconds = 0.25f;
  m.frame_state_hash = 0x1234abcd5678ef00;
  m.rays = {4, 40, 12};
  m.nonfinite_pixels = 1;
  m.pixels = {{0.1f, 0.2f, 0.3f}, {1.0f, 0.5f, 0.0f}, {0.0f, 0.0f, 0.0f}, {7.5f, 2.0f, 1.0f}};
  return m;
}

// Display frames: the same tile as half floats (values a half holds exactly).
TileResult half_tile_result() {
  TileResult m = tile_result();
  m.pixel_format = PixelFormat::Float16;
  m.pixels = {{0.125f, 0.25f, 0.375f}, {1.0f, 0.5f, 0.0f}, {0.0f, -0.0f, 65504.0f}, {7.5f, 2.0f, 1.0f}};
  return m;
}

// The window's frames: pixels and the surfaces they show (a wall, a glossy pixel, the sky).
TileResult surface_tile_result() {
  TileResult m = half_tile_result();
  m.surfaces = {{2.5f, {0, 0, 127}, 0}, {2.6f, {12, -5, 126}, 0}, {1.0f, {0, 127, 0}, PixelSurface::kViewDependent},
                {0.0f, {0, 0, 0}, 0}};
  return m;
}

// --pixel-codec zstd: the half tile's pixel block as one zstd frame.
TileResult zstd_tile_result() {
  TileResult m = half_tile_result();
  m.pixel_codec = PixelCodec::Zstd;
  return m;
}

// --pixels rgb9e5: one shared-exponent word a pixel, zstd-packed as on a slow link.
TileResult rgb9e5_tile_result() {
  TileResult m = zstd_tile_result();
  m.pixel_format = PixelFormat::Rgb9e5;
  return m;
}

// --pixel-codec lz4: the float tile's pixel block as one lz4 block.
TileResult lz4_tile_result() {
  TileResult m = tile_result();
  m.pixel_codec = PixelCodec::Lz4;
  return m;
}

// The window's frames over a slow link: pixels and surfaces, each block packed.
TileResult packed_surface_tile_result() {
  TileResult m = surface_tile_result();
  m.pixel_format = PixelFormat::Rgb9e5;
  m.pixel_codec = PixelCodec::Zstd;
  return m;
}

FrameSetupMsg frame_setup() {
  FrameSetupMsg m;
  m.frame.frame_id = 3;
  m.frame.camera.position = {0.0f, 1.0f, 3.0f};
  m.frame.width = 640;
  m.frame.height = 480;
  m.frame.seed = 99;
  m.frame.sample_begin = 8;
  m.frame.sample_count = 4;
  m.frame.jitter_x = 0.25f;
  m.frame.pose.time = 1.25;
  m.frame.pose.light_offset = {0.1f, 0.0f, -0.2f};
  m.frame.want_surfaces = true;
  return m;
}


std::vector<uint8_t> read_all(const fs::path& path) {
  std::optional<std::vector<uint8_t>> bytes = read_file_bytes(path.string());
  if (!bytes) throw SceneError(path.string() + ": cannot read a seed written a moment ago");
  return *bytes;
}

// The writer's .gltf refers to name.bin and name_textureN.png: inline them.
std::vector<uint8_t> embedded_gltf(const fs::path& path) {
  nlohmann::json doc = nlohmann::json::parse(read_all(path));
  for (const char* array : {"buffers", "images"}) {
    if (!doc.contains(array)) continue;
    for (nlohmann::json& item : doc[array]) {
      const std::string mime = array == std::string("images") ? "image/png" : "application/octet-stream";
      const fs::path file = path.parent_path() / item["uri"].get<std::string>();
      item["uri"] = "data:" + mime + ";base64," + test::base64(read_all(file));
    }
  }
  const std::string text = doc.dump();
  return {text.begin(), text.end()};
}

Scene textured_quad() {
  Scene s;
  s.name = "textured-quad";
  Texture texture;
  texture.width = texture.height = 2;
  texture.texels = {{1, 0, 0, 1}, {0, 1, 0, 1}, {0, 0, 1, 1}, {1, 1, 1, 0.5f}};
  s.textures.push_back(texture);
  Material m;
  m.name = "checker";
  m.base_color_texture.index = 0;
  m.alpha_mask = true;
  s.materials.push_back(m);
  s.positions = {{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}};
  s.normals = std::vector<glm::vec3>(4, {0, 0, 1});
  s.uvs = {{0, 1}, {1, 1}, {1, 0}, {0, 0}};
  s.triangles = {{0, 1, 2}, {0, 2, 3}};
  s.triangle_material = {0, 0};
  PunctualLight light;
  light.position = {0, 0, 2};
  s.lights.push_back(light);
  return s;
}

Scene spot_and_camera() {
  Scene s;
  s.name = "spot-camera";
  Material floor;
  floor.type = MaterialType::Conductor;
  floor.alpha = 0.2f;
  add_quad(s, {-2, 0, 2}, {2, 0, 2}, {2, 0, -2}, {-2, 0, -2}, add_material(s, floor));
  Material glass;
  glass.type = MaterialType::Glass;
  glass.ior = 1.33f;
  add_quad(s, {-0.5f, 0, 0}, {0.5f, 0, 0}, {0.5f, 1, 0}, {-0.5f, 1, 0}, add_material(s, glass));
  PunctualLight spot;
  spot.type = LightType::Spot;
  spot.position = {0, 3, 0};
  spot.direction = {0, -1, 0};
  spot.intensity = glm::vec3(20.0f);
  spot.inner_cone = 0.2f;
  spot.outer_cone = 0.6f;
  s.lights.push_back(spot);
  s.camera = Camera{{0.0f, 1.5f, 4.0f}, glm::normalize(glm::vec3(0.0f, -0.3f, -1.0f)), {0, 1, 0}, 0.8f};
  return s;
}

Scene directional_with_emitter() {
  Scene s;
  s.name = "sun-and-lamp";
  Material mirror;
  mirror.type = MaterialType::Mirror;
  add_quad(s, {-1, 0, 1}, {1, 0, 1}, {1, 0, -1}, {-1, 0, -1}, add_material(s, mirror));
  Material lamp;
  lamp.emission = glm::vec3(5.0f, 4.0f, 3.0f);
  lamp.double_sided = false;
  add_quad(s, {-0.2f, 1, -0.2f}, {-0.2f, 1, 0.2f}, {0.2f, 1, 0.2f}, {0.2f, 1, -0.2f}, add_material(s, lamp));
  PunctualLight sun;
  sun.type = LightType::Directional;
  sun.direction = glm::normalize(glm::vec3(1, -2, 0.5f));
  sun.intensity = glm::vec3(3.0f);
  s.lights.push_back(sun);
  return s;
}

}  // namespace

std::vector<Seed> decode_seeds() {
  Welcome welcome;
  welcome.session = 42;
  welcome.scene_name = "cornell.glb";
  welcome.scene_hash = 0xfeedface;
  welcome.scene_size = 4096;
  welcome.settings = settings();
  welcome.timeout_ms = 1500;
  welcome.pixel_format = PixelFormat::Float16;
  SceneData data;
  data.scene_hash = 0xfeedface;
  data.file_name = "cornell.glb";
  data.bytes = {'g', 'l', 'T', 'F', 2, 0, 0, 0};
  TileJobMsg job;
  job.frame_id = 3;
  job.job_id = 17;
  job.tile = {32, 64, 40, 40, 1};
  const std::vector<std::pair<std::string, Message>> messages = {
      {"Hello", Hello{"0123456789ab clang-14", "avx512", 16}},
      {"Welcome", welcome},
      {"Refuse", Refuse{"build id differs"}},
      {"SceneRequest", SceneRequest{0xfeedface}},
      {"SceneData", data},
      {"FrameSetup", frame_setup()},
      {"TileJob", job},
      {"TileResult", tile_result()},
      {"TileResult-half", half_tile_result()},
      {"TileResult-surfaces", surface_tile_result()},
      {"TileResult-zstd", zstd_tile_result()},
      {"TileResult-rgb9e5", rgb9e5_tile_result()},
      {"TileResult-surfaces-zstd", packed_surface_tile_result()},
      {"TileResult-lz4", lz4_tile_result()},
      {"CancelFrame", CancelFrame{3}},
      {"Heartbeat", Heartbeat{}},
      {"Bye", Bye{"shutting down"}},
      {"Bye-quarantined", Bye{"VPL sets differ", ByeKind::Quarantined}},
  };
  std::vector<Seed> seeds;
  for (const auto& [name, message] : messages) seeds.push_back({name + ".bin", encode(message)});
  return seeds;
}

std::vector<Seed> display_seeds() {
  display::Welcome welcome;
  welcome.scene = "cornell";
  welcome.width = 64;
  welcome.height = 48;
  welcome.preview_levels = {"full", "preview 1/2"};
  display::View view;
  view.camera_generation = 3;
  view.stamp_us = 123456789;
  display::Frame frame;
  frame.sequence = 7;
  frame.width = 4;
  frame.height = 2;
  frame.full = true;
  frame.status = "12.0 fps  full";
  frame.level = "full";
  frame.seconds = 0.04f;
  const std::vector<uint8_t> rgb(4 * 2 * 3, 128);
  frame.pixels = display::pack_pixels(rgb);
  const std::vector<std::pair<std::string, display::Message>> messages = {
      {"display-Hello", display::Hello{"igi-view 1"}},
      {"display-Welcome", welcome},
      {"display-Refuse", display::Refuse{"another viewer is connected"}},
      {"display-View", view},
      {"display-Ack", display::Ack{7}},
      {"display-Request", display::Request{display::RequestKind::SaveImage}},
      {"display-Reply", display::Reply{"metered", 2.0f, {}}},
      {"display-Reply-image", display::Reply{"saved igi-shot-0000.exr", 0.0f, {'v', '/', '1', 1, 2, 0, 0, 0}}},
      {"display-Frame", frame},
      {"display-Ping", display::Ping{}},
      {"display-Bye", display::Bye{"the window closed"}},
  };
  std::vector<Seed> seeds;
  for (const auto& [name, message] : messages) seeds.push_back({name + ".bin", display::encode(message)});
  return seeds;
}

std::vector<Seed> scene_seeds(const std::string& scratch_dir) {
  const fs::path dir(scratch_dir);
  fs::create_directories(dir);
  std::vector<Seed> seeds;
  const Scene scenes[] = {make_cornell_box(), textured_quad(), spot_and_camera(), directional_with_emitter()};
  for (const Scene& scene : scenes) {
    const fs::path glb = dir / (scene.name + ".glb"), gltf = dir / (scene.name + ".gltf");
    write_gltf(scene, glb.string());
    write_gltf(scene, gltf.string());
    seeds.push_back({glb.filename().string(), read_all(glb)});
    seeds.push_back({gltf.filename().string(), embedded_gltf(gltf)});
  }
  // The textured quad again with a JPEG, so that the fuzzer starts from both
  // of glTF's image formats (stb's JPEG decoder once took a 600-byte file
  // that claimed 8000 x 8000 pixels for 12 s and 1.4 GB).
  Image image(8, 8);
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 8; ++x) image.at(x, y) = glm::vec3(float(x) / 8.0f, float(y) / 8.0f, 0.5f);
  const fs::path jpeg = dir / "texture.jpg";
  write_image(image, jpeg.string());
  nlohmann::json doc = nlohmann::json::parse(embedded_gltf(dir / "textured-quad.gltf"));
  doc["images"][0]["uri"] = "data:image/jpeg;base64," + test::base64(read_all(jpeg));
  const std::string jpeg_quad = doc.dump();
  seeds.push_back({"textured-quad-jpeg.gltf", std::vector<uint8_t>(jpeg_quad.begin(), jpeg_quad.end())});
  const std::string animated = test::animated_document(true).dump();  // the camera flies too
  seeds.push_back({"animated.gltf", std::vector<uint8_t>(animated.begin(), animated.end())});
  return seeds;
}

}  // namespace igi::fuzz
