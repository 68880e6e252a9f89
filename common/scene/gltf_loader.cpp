#include "scene/gltf_loader.h"

#include <cctype>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <tiny_gltf.h>

#include "scene/gltf_accessors.h"
#include "scene/gltf_diagnostics.h"
#include "scene/gltf_features.h"
#include "scene/gltf_geometry.h"
#include "scene/gltf_materials.h"
#include "scene/gltf_nodes.h"

namespace igi {
namespace {

namespace fs = std::filesystem;

constexpr uint32_t kGlbMagic = 0x46546C67;      // "glTF"
constexpr uint32_t kChunkJson = 0x4E4F534A;     // "JSON"
constexpr uint32_t kChunkBin = 0x004E4942;      // "BIN\0"
constexpr size_t kGlbHeaderBytes = 12, kChunkHeaderBytes = 8;

std::vector<unsigned char> read_file(const std::string& path) {
  std::error_code error;
  if (!fs::is_regular_file(path, error)) throw SceneError(path + ": no such file (or not a regular file)");
  const uintmax_t size = fs::file_size(path, error);
  // tinygltf takes 32-bit lengths; glTF caps .glb files at 4 GiB as well.
  if (error || size > UINT32_MAX)
    throw SceneError(path + ": cannot read the file's size, or it exceeds 4 GiB");
  std::ifstream in(path, std::ios::binary);
  std::vector<unsigned char> bytes(size);
  if (!in || !in.read(reinterpret_cast<char*>(bytes.data()), std::streamsize(size)))
    throw SceneError(path + ": cannot read the file");
  return bytes;
}

uint32_t read_u32(const std::vector<unsigned char>& bytes, size_t at) {
  uint32_t value;  // GLB is little-endian, as is every machine this runs on
  std::memcpy(&value, bytes.data() + at, 4);
  return value;
}

bool is_glb(const std::string& path, const std::vector<unsigned char>& bytes) {
  if (bytes.size() >= 4 && read_u32(bytes, 0) == kGlbMagic) return true;
  std::string extension = fs::path(path).extension().string();
  for (char& c : extension) c = char(std::tolower(static_cast<unsigned char>(c)));
  return extension == ".glb";
}

// Checks the GLB framing before tinygltf reads it, so that a truncated file
// is reported as such and no chunk is read past the end of the bytes.
void check_glb(const std::vector<unsigned char>& bytes, const GltfDiagnostics& diag) {
  const size_t size = bytes.size();
  if (size < kGlbHeaderBytes + kChunkHeaderBytes)
    diag.fail("GLB header",
              "truncated: " + std::to_string(size) + " bytes, shorter than the headers (20 bytes)");
  if (read_u32(bytes, 0) != kGlbMagic) diag.fail("GLB header", "missing the 'glTF' magic");
  if (read_u32(bytes, 4) != 2)
    diag.fail("GLB header", "version " + std::to_string(read_u32(bytes, 4)) + ", expected 2");
  const size_t length = read_u32(bytes, 8);
  if (length > size)
    diag.fail("GLB header", "truncated: the header declares " + std::to_string(length) +
                                " bytes, the file has " + std::to_string(size));
  size_t at = kGlbHeaderBytes;
  for (int chunk = 0; at < length; ++chunk) {
    const std::string name = "GLB chunk " + std::to_string(chunk);
    if (length - at < kChunkHeaderBytes) diag.fail(name, "truncated chunk header");
    const size_t chunk_length = read_u32(bytes, at), type = read_u32(bytes, at + 4);
    if (chunk_length > length - at - kChunkHeaderBytes)
      diag.fail(name, "truncated: declares " + std::to_string(chunk_length) + " bytes, " +
                          std::to_string(length - at - kChunkHeaderBytes) + " remain");
    if (chunk == 0 && type != kChunkJson) diag.fail(name, "expected the JSON chunk first");
    if (chunk == 1 && type != kChunkBin) diag.fail(name, "expected a BIN chunk");
    at += kChunkHeaderBytes + chunk_length;
  }
}

// tinygltf would decode images while parsing, before anything has checked
// bufferViews against their buffers. Keep the encoded bytes of external and
// data-URI images instead; gltf_materials.cpp decodes the ones in use.
bool keep_encoded_image(tinygltf::Image* image, const int, std::string*, std::string*, int, int,
                        const unsigned char* bytes, int size, void*) {
  if (image->bufferView < 0 && bytes && size > 0) image->image.assign(bytes, bytes + size);
  image->as_is = true;
  return true;
}

void add_parser_warnings(const std::string& text, GltfDiagnostics& diag) {
  std::istringstream lines(text);
  for (std::string line; std::getline(lines, line);)
    if (!line.empty()) diag.warnings.push_back(diag.file + ": " + line);
}

tinygltf::Model parse_model(const std::vector<unsigned char>& bytes, GltfDiagnostics& diag) {
  const bool binary = is_glb(diag.file, bytes);
  if (binary) check_glb(bytes, diag);
  tinygltf::TinyGLTF parser;
  parser.SetImageLoader(&keep_encoded_image, nullptr);
  const std::string base_dir = fs::path(diag.file).parent_path().string();
  tinygltf::Model model;
  std::string error, warning;
  bool ok = false;
  try {
    const unsigned size = unsigned(bytes.size());  // read_file capped it at 4 GiB
    ok = binary ? parser.LoadBinaryFromMemory(&model, &error, &warning, bytes.data(), size, base_dir)
                : parser.LoadASCIIFromString(&model, &error, &warning,
                                             reinterpret_cast<const char*>(bytes.data()), size, base_dir);
  } catch (const std::exception& e) {
    error = e.what();
  }
  while (!error.empty() && (error.back() == '\n' || error.back() == ' ')) error.pop_back();
  if (!ok) throw SceneError(diag.file + ": " + (error.empty() ? "not a valid glTF file" : error));
  add_parser_warnings(warning, diag);
  return model;
}

// Scene::validate names the scene, not the file: prefix the file.
void validate_scene(const Scene& scene, const GltfDiagnostics& diag) {
  try {
    scene.validate();
  } catch (const SceneError& e) {
    throw SceneError(diag.file + ": " + e.what());
  }
}

}  // namespace

LoadedScene load_gltf(const std::string& path) {
  GltfDiagnostics diag;
  diag.file = path;
  const tinygltf::Model model = parse_model(read_file(path), diag);
  check_buffer_views(model, diag);
  warn_unsupported_features(model, diag);

  LoadedScene loaded;
  Scene& scene = loaded.scene;
  convert_materials(model, diag, scene);
  FlattenedNodes nodes = flatten_nodes(model, diag);
  add_mesh_instances(model, nodes.instances, diag, scene);
  scene.lights = std::move(nodes.lights);
  scene.camera = nodes.camera;
  scene.name = nodes.scene_name.empty() ? fs::path(path).stem().string() : nodes.scene_name;
  validate_scene(scene, diag);
  loaded.warnings = std::move(diag.warnings);
  return loaded;
}

}  // namespace igi
