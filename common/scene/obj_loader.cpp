#include "scene/obj_loader.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <tuple>

#define TINYOBJLOADER_IMPLEMENTATION
#include <tiny_obj_loader.h>

#include "io/file_bytes.h"
#include "scene/gltf_diagnostics.h"
#include "scene/gltf_materials.h"
#include "scene/texture_decode.h"
#include "scene/gltf_writer.h"
#include "scene/scene.h"

namespace igi {
namespace {

namespace fs = std::filesystem;

constexpr float kMirrorAlpha = 1e-3f;  // a GGX alpha under this is a mirror
constexpr float kDefaultAlbedo = 0.8f;

float luminance(glm::vec3 c) { return 0.2126f * c.x + 0.7152f * c.y + 0.0722f * c.z; }
glm::vec3 rgb(const tinyobj::real_t c[3]) { return {float(c[0]), float(c[1]), float(c[2])}; }

std::string trimmed(std::string text) {
  while (!text.empty() && (text.back() == '\n' || text.back() == ' ')) text.pop_back();
  return text;
}

// tinyobjloader's MTL reading, confined to the OBJ's folder (as glTF's buffers
// and images are): an `mtllib` that leads elsewhere is an error.
class FolderMaterialReader : public tinyobj::MaterialReader {
 public:
  FolderMaterialReader(std::string folder, std::string root, const GltfDiagnostics& diag)
      : folder_(std::move(folder)), root_(std::move(root)), diag_(diag) {}

  bool operator()(const std::string& name, std::vector<tinyobj::material_t>* materials,
                  std::map<std::string, int>* names, std::string* warn, std::string* err) override {
    const std::string path = (fs::path(folder_) / name).string();
    if (!inside_folder(root_, path)) diag_.fail("mtllib " + name, "outside the scene's folder");
    std::ifstream in(path);
    if (!in) diag_.fail("mtllib " + name, "cannot be read (no such file beside the OBJ)");
    tinyobj::LoadMtl(names, materials, &in, warn, err);
    return true;
  }

 private:
  std::string folder_, root_;
  const GltfDiagnostics& diag_;
};

class ObjConverter {
 public:
  ObjConverter(const std::string& path, GltfDiagnostics& diag)
      : path_(path), folder_(fs::path(path).parent_path().string()), diag_(diag) {
    if (folder_.empty()) folder_ = ".";
    std::error_code error;
    root_ = fs::weakly_canonical(folder_, error).string();
  }

  Scene convert();

 private:
  void read();
  Material to_material(const tinyobj::material_t& m);
  int texture(const std::string& name, const std::string& material);
  void report_unmapped(const tinyobj::material_t& m);
  void add_triangles();
  uint32_t vertex(const tinyobj::index_t& index, glm::vec3 face_normal);

  std::string path_, folder_, root_;
  GltfDiagnostics& diag_;
  tinyobj::attrib_t attrib_;
  std::vector<tinyobj::shape_t> shapes_;
  std::vector<tinyobj::material_t> materials_;
  Scene scene_;
  bool normals_ = false, uvs_ = false;
  std::map<std::tuple<int, int, int>, uint32_t> vertex_of_;  // (v, vn or -1 - face, vt) -> Scene vertex
  std::map<std::string, int> texture_of_;                     // file -> Scene texture
  int face_ = 0;
};

void ObjConverter::read() {
  std::ifstream in(path_);
  if (!in) throw SceneError(path_ + ": no such file, or it cannot be read");
  FolderMaterialReader materials(folder_, root_, diag_);
  std::string warn, err;
  if (!tinyobj::LoadObj(&attrib_, &shapes_, &materials_, &warn, &err, &in, &materials, true, false))
    throw SceneError(path_ + ": not a readable OBJ file" + (err.empty() ? std::string() : ": " + trimmed(err)));
  std::istringstream lines(warn + err);  // tinyobjloader's notes: unknown lines, a missing material
  for (std::string line; std::getline(lines, line);)
    if (!line.empty()) diag_.warn_once("tinyobj " + line, trimmed(line));
}

int ObjConverter::texture(const std::string& name, const std::string& material) {
  const std::string path = (fs::path(folder_) / name).string();
  const std::string shown = "material '" + material + "': map_Kd " + name;
  if (auto it = texture_of_.find(path); it != texture_of_.end()) return it->second;
  if (!inside_folder(root_, path)) diag_.fail(shown, "outside the scene's folder");
  const std::optional<std::vector<uint8_t>> bytes = read_file_bytes(path);
  if (!bytes || bytes->empty()) diag_.fail(shown, "the image file is missing or empty");
  scene_.textures.push_back(decode_texture(bytes->data(), bytes->size(), shown, diag_));
  return texture_of_[path] = int(scene_.textures.size() - 1);
}

// What the mapping leaves out, once a feature for the whole file.
void ObjConverter::report_unmapped(const tinyobj::material_t& m) {
  const std::pair<const char*, const std::string*> maps[] = {
      {"map_Ka", &m.ambient_texname},     {"map_Ks", &m.specular_texname},
      {"map_Ns", &m.specular_highlight_texname}, {"bump map", &m.bump_texname},
      {"disp", &m.displacement_texname},  {"map_d", &m.alpha_texname},
      {"refl", &m.reflection_texname},    {"map_Ke", &m.emissive_texname},
      {"map_Pr", &m.roughness_texname},   {"map_Pm", &m.metallic_texname},
      {"norm", &m.normal_texname}};
  for (const auto& [key, name] : maps)
    if (!name->empty()) diag_.warn_once(key, std::string(key) + " ignored: materials take Kd, Ks, Ns, Ke, d, Ni and map_Kd");
  const std::pair<const char*, tinyobj::real_t> pbr[] = {{"Pr", m.roughness},   {"Pm", m.metallic},
                                                        {"Ps", m.sheen},       {"Pc", m.clearcoat_thickness},
                                                        {"Pcr", m.clearcoat_roughness}, {"aniso", m.anisotropy}};
  for (const auto& [key, value] : pbr)
    if (value != 0) diag_.warn_once(key, std::string(key) + " (the PBR extension) ignored: materials take Kd, Ks, Ns, Ke, d, Ni and map_Kd");
  if (luminance(rgb(m.ambient)) > 0.0f)
    diag_.warn_once("Ka", "Ka (ambient colour) ignored: light comes from the scene's emitters");
  for (const auto& [key, value] : m.unknown_parameter) diag_.warn_once(key, key + " ignored (" + m.name + ")");
}

Material ObjConverter::to_material(const tinyobj::material_t& m) {
  Material out;
  out.name = m.name;
  out.emission = glm::max(rgb(m.emission), glm::vec3(0.0f));
  const glm::vec3 kd = glm::clamp(rgb(m.diffuse), 0.0f, 1.0f), ks = glm::clamp(rgb(m.specular), 0.0f, 1.0f);
  const bool glass = m.dissolve < 1.0f || m.illum == 4 || m.illum == 6 || m.illum == 7 || m.illum == 9;
  if (glass) {
    out.type = MaterialType::Glass;
    out.ior = m.ior > 1.0f ? float(m.ior) : 1.5f;
    const glm::vec3 tint = glm::clamp(rgb(m.transmittance), 0.0f, 1.0f);
    out.base_color = luminance(tint) > 0.0f ? tint : glm::vec3(1.0f);
    if (m.dissolve > 0.0f && m.dissolve < 1.0f)
      diag_.warn_once("d", "d (dissolve) between 0 and 1 read as clear glass: no partial coverage");
  } else if (luminance(ks) > luminance(kd)) {
    const float alpha = std::sqrt(2.0f / (std::max(float(m.shininess), 0.0f) + 2.0f));
    out.type = alpha < kMirrorAlpha ? MaterialType::Mirror : MaterialType::Conductor;
    out.base_color = ks;
    out.alpha = std::max(alpha, kMirrorAlpha);
    if (luminance(kd) > 0.0f) diag_.warn_once("Kd beside Ks", "Kd beside a brighter Ks dropped: no layered material");
  } else {
    out.base_color = kd;
    if (!m.diffuse_texname.empty()) out.base_color_texture.index = texture(m.diffuse_texname, m.name);
    if (luminance(ks) > 0.0f) diag_.warn_once("Ks beside Kd", "Ks beside a brighter Kd dropped: no layered material");
  }
  report_unmapped(m);
  return out;
}

uint32_t ObjConverter::vertex(const tinyobj::index_t& index, glm::vec3 face_normal) {
  const size_t normals = attrib_.normals.size() / 3, uvs = attrib_.texcoords.size() / 2;
  const std::string face = "face " + std::to_string(face_);  // its vertex index is checked by add_triangles
  if (index.normal_index >= 0 && size_t(index.normal_index) >= normals)
    diag_.fail(face, "normal " + std::to_string(index.normal_index + 1) + " of " + std::to_string(normals));
  if (index.texcoord_index >= 0 && size_t(index.texcoord_index) >= uvs)
    diag_.fail(face, "texture coordinate " + std::to_string(index.texcoord_index + 1) + " of " + std::to_string(uvs));
  const int normal_key = index.normal_index >= 0 ? index.normal_index : -1 - face_;
  const auto key = std::make_tuple(index.vertex_index, normal_key, index.texcoord_index);
  if (auto it = vertex_of_.find(key); it != vertex_of_.end()) return it->second;
  const float* p = &attrib_.vertices[3 * size_t(index.vertex_index)];
  scene_.positions.emplace_back(p[0], p[1], p[2]);
  if (normals_) {
    glm::vec3 n = face_normal;
    if (index.normal_index >= 0) {
      const float* v = &attrib_.normals[3 * size_t(index.normal_index)];
      n = glm::vec3(v[0], v[1], v[2]);
    }
    scene_.normals.push_back(glm::length(n) > 0.0f ? glm::normalize(n) : face_normal);
  }
  if (uvs_) {
    glm::vec2 uv(0.0f);
    if (index.texcoord_index >= 0) {
      const float* t = &attrib_.texcoords[2 * size_t(index.texcoord_index)];
      uv = glm::vec2(t[0], 1.0f - t[1]);  // OBJ's v grows up, glTF's down
    }
    scene_.uvs.push_back(uv);
  }
  return vertex_of_[key] = uint32_t(scene_.positions.size() - 1);
}

void ObjConverter::add_triangles() {
  const uint32_t fallback = uint32_t(scene_.materials.size());  // for faces without a material
  bool used_fallback = false;
  for (const tinyobj::shape_t& shape : shapes_) {
    const tinyobj::mesh_t& mesh = shape.mesh;
    for (size_t f = 0, at = 0; f < mesh.num_face_vertices.size(); at += mesh.num_face_vertices[f], ++f, ++face_) {
      if (mesh.num_face_vertices[f] != 3) diag_.fail("face " + std::to_string(face_), "not a triangle after triangulation");
      glm::vec3 corner[3];
      for (int k = 0; k < 3; ++k) {
        const int v = mesh.indices[at + size_t(k)].vertex_index;
        if (v < 0 || size_t(v) >= attrib_.vertices.size() / 3)
          diag_.fail("face " + std::to_string(face_), "vertex " + std::to_string(v + 1) + " of " +
                                                         std::to_string(attrib_.vertices.size() / 3));
        corner[k] = glm::vec3(attrib_.vertices[3 * size_t(v)], attrib_.vertices[3 * size_t(v) + 1],
                              attrib_.vertices[3 * size_t(v) + 2]);
      }
      const glm::vec3 cross = glm::cross(corner[1] - corner[0], corner[2] - corner[0]);
      const glm::vec3 face_normal = glm::length(cross) > 0.0f ? glm::normalize(cross) : glm::vec3(0, 0, 1);
      glm::uvec3 triangle;
      for (int k = 0; k < 3; ++k) triangle[k] = vertex(mesh.indices[at + size_t(k)], face_normal);
      const int material = f < mesh.material_ids.size() ? mesh.material_ids[f] : -1;
      used_fallback |= material < 0 || size_t(material) >= materials_.size();
      scene_.triangles.push_back(triangle);
      scene_.triangle_material.push_back(material >= 0 && size_t(material) < materials_.size() ? uint32_t(material)
                                                                                                : fallback);
    }
  }
  if (used_fallback) {
    Material white;
    white.name = "default";
    white.base_color = glm::vec3(kDefaultAlbedo);
    scene_.materials.push_back(white);
  }
}

Scene ObjConverter::convert() {
  read();
  scene_.name = fs::path(path_).stem().string();
  for (const tinyobj::material_t& m : materials_) scene_.materials.push_back(to_material(m));
  for (const tinyobj::shape_t& shape : shapes_)
    for (const tinyobj::index_t& index : shape.mesh.indices) {
      normals_ |= index.normal_index >= 0;
      uvs_ |= index.texcoord_index >= 0;
    }
  add_triangles();
  return std::move(scene_);
}

}  // namespace

bool is_obj_file(const std::string& path) {
  std::string extension = fs::path(path).extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(), [](unsigned char c) { return std::tolower(c); });
  return extension == ".obj";
}

std::vector<uint8_t> obj_as_glb(const std::string& path, std::vector<std::string>* warnings) {
  GltfDiagnostics diag;
  diag.file = path;
  const Scene scene = ObjConverter(path, diag).convert();
  if (warnings) *warnings = std::move(diag.warnings);
  return write_glb_bytes(scene, fs::path(path).stem().string() + ".glb");
}

}  // namespace igi
