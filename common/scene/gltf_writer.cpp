#include "scene/gltf_writer.h"
#include "scene/light_units.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <set>
#include <sstream>

#include <glm/gtc/quaternion.hpp>
#include <tiny_gltf.h>

namespace igi {
namespace {

namespace fs = std::filesystem;
using Object = tinygltf::Value::Object;

// Triangles of one material with their own vertices, in first-use order.
struct Submesh {
  std::vector<glm::vec3> positions, normals;
  std::vector<glm::vec2> uvs;
  std::vector<uint32_t> indices;
};

// Everything the writer checks before it reads: the indices it follows.
void check_writable(const Scene& scene, const std::string& path) {
  const std::string where = path + ": scene '" + scene.name + "': ";
  if (scene.triangle_material.size() != scene.triangles.size())
    throw SceneError(where + "triangle_material has " + std::to_string(scene.triangle_material.size()) +
                     " entries, expected one per triangle (" + std::to_string(scene.triangles.size()) + ")");
  if ((!scene.normals.empty() && scene.normals.size() != scene.positions.size()) ||
      (!scene.uvs.empty() && scene.uvs.size() != scene.positions.size()))
    throw SceneError(where + "normals and uvs must be empty or one per position");
  for (size_t t = 0; t < scene.triangles.size(); ++t)
    if (glm::any(glm::greaterThanEqual(scene.triangles[t], glm::uvec3(uint32_t(scene.positions.size())))) ||
        scene.triangle_material[t] >= scene.materials.size())
      throw SceneError(where + "triangle " + std::to_string(t) +
                       " indexes a vertex or material that does not exist");
  for (const Material& m : scene.materials)
    for (const TextureRef* t : {&m.base_color_texture, &m.metallic_roughness_texture, &m.metallic_texture,
                                &m.roughness_texture, &m.normal_texture})
      if (t->index >= int(scene.textures.size()))
        throw SceneError(where + "material '" + m.name + "' names texture " + std::to_string(t->index) + " of " +
                         std::to_string(scene.textures.size()));
}

// Appends a 4-byte aligned bufferView over `bytes` to buffer 0.
int add_buffer_view(tinygltf::Model& model, const void* data, size_t bytes, int target) {
  std::vector<unsigned char>& buffer = model.buffers[0].data;
  buffer.resize((buffer.size() + 3) / 4 * 4, 0);
  tinygltf::BufferView view;
  view.buffer = 0;
  view.byteOffset = buffer.size();
  view.byteLength = bytes;
  view.target = target;
  buffer.resize(buffer.size() + bytes);
  std::memcpy(buffer.data() + view.byteOffset, data, bytes);
  model.bufferViews.push_back(view);
  return int(model.bufferViews.size() - 1);
}

template <typename T>
int add_accessor(tinygltf::Model& model, const std::vector<T>& values, int type, int component, int target) {
  tinygltf::Accessor accessor;
  accessor.bufferView = add_buffer_view(model, values.data(), values.size() * sizeof(T), target);
  accessor.count = values.size();
  accessor.type = type;
  accessor.componentType = component;
  model.accessors.push_back(accessor);
  return int(model.accessors.size() - 1);
}

// glTF requires min and max on POSITION accessors.
void set_bounds(tinygltf::Accessor& accessor, const std::vector<glm::vec3>& positions) {
  glm::vec3 lower(positions[0]), upper(positions[0]);
  for (glm::vec3 p : positions) lower = glm::min(lower, p), upper = glm::max(upper, p);
  accessor.minValues = {lower.x, lower.y, lower.z};
  accessor.maxValues = {upper.x, upper.y, upper.z};
}

std::vector<std::vector<uint32_t>> triangles_by_material(const Scene& scene) {
  std::vector<std::vector<uint32_t>> groups(scene.materials.size());
  for (size_t t = 0; t < scene.triangles.size(); ++t)
    groups[scene.triangle_material[t]].push_back(uint32_t(t));
  return groups;
}

// `remap` is all ~0u on entry and on exit, so one vector serves every material.
Submesh compact(const Scene& scene, const std::vector<uint32_t>& triangles, std::vector<uint32_t>& remap) {
  Submesh sub;
  for (uint32_t t : triangles)
    for (int k = 0; k < 3; ++k) {
      const uint32_t v = scene.triangles[t][k];
      if (remap[v] == ~0u) {
        remap[v] = uint32_t(sub.positions.size());
        sub.positions.push_back(scene.positions[v]);
        if (!scene.normals.empty()) sub.normals.push_back(scene.normals[v]);
        if (!scene.uvs.empty()) sub.uvs.push_back(scene.uvs[v]);
      }
      sub.indices.push_back(remap[v]);
    }
  for (uint32_t t : triangles)
    for (int k = 0; k < 3; ++k) remap[scene.triangles[t][k]] = ~0u;
  return sub;
}

tinygltf::Primitive write_primitive(tinygltf::Model& model, const Submesh& sub, int material) {
  tinygltf::Primitive primitive;
  primitive.mode = TINYGLTF_MODE_TRIANGLES;
  primitive.material = material;
  constexpr int kFloat = TINYGLTF_COMPONENT_TYPE_FLOAT, kVertices = TINYGLTF_TARGET_ARRAY_BUFFER;
  const int position = add_accessor(model, sub.positions, TINYGLTF_TYPE_VEC3, kFloat, kVertices);
  set_bounds(model.accessors[size_t(position)], sub.positions);
  primitive.attributes["POSITION"] = position;
  if (!sub.normals.empty())
    primitive.attributes["NORMAL"] = add_accessor(model, sub.normals, TINYGLTF_TYPE_VEC3, kFloat, kVertices);
  if (!sub.uvs.empty())
    primitive.attributes["TEXCOORD_0"] = add_accessor(model, sub.uvs, TINYGLTF_TYPE_VEC2, kFloat, kVertices);
  primitive.indices = add_accessor(model, sub.indices, TINYGLTF_TYPE_SCALAR,
                                   TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT, TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
  return primitive;
}

void write_geometry(const Scene& scene, tinygltf::Model& model) {
  tinygltf::Mesh mesh;
  std::vector<uint32_t> remap(scene.positions.size(), ~0u);
  const std::vector<std::vector<uint32_t>> groups = triangles_by_material(scene);
  for (size_t m = 0; m < groups.size(); ++m)
    if (!groups[m].empty())
      mesh.primitives.push_back(write_primitive(model, compact(scene, groups[m], remap), int(m)));
  if (mesh.primitives.empty()) return;
  model.meshes.push_back(mesh);
  tinygltf::Node node;
  node.mesh = 0;
  model.nodes.push_back(node);
}

void set_extension(tinygltf::Material& material, const char* name, const char* key, double value,
                   std::set<std::string>& used) {
  material.extensions[name] = tinygltf::Value(Object{{key, tinygltf::Value(value)}});
  used.insert(name);
}

// KHR_texture_transform of a reference: offset, rotation and scale from its
// matrix (rotation x scale, as the loader builds it).
tinygltf::ExtensionMap texture_transform(const TextureRef& ref, std::set<std::string>& used) {
  if (!ref.transformed) return {};
  used.insert("KHR_texture_transform");
  const glm::vec2 x = ref.linear[0], y = ref.linear[1];  // (c sx, -s sx), (s sy, c sy)
  const double sx = glm::length(x), sy = glm::length(y), rotation = std::atan2(-double(x.y), double(x.x));
  auto pair = [](double a, double b) { return tinygltf::Value(tinygltf::Value::Array{tinygltf::Value(a), tinygltf::Value(b)}); };
  Object transform{{"offset", pair(ref.offset.x, ref.offset.y)}, {"rotation", tinygltf::Value(rotation)},
                   {"scale", pair(sx, sy)}};
  return {{"KHR_texture_transform", tinygltf::Value(std::move(transform))}};
}

template <typename Info>
void set_texture(Info& info, const TextureRef& ref, std::set<std::string>& used) {
  info.index = ref.index;
  info.extensions = texture_transform(ref, used);
}

// The glTF BRDF's own parameters (gltf_materials.h reads them back).
void write_metallic_roughness(const Material& m, tinygltf::Material& out, std::set<std::string>& used) {
  tinygltf::PbrMetallicRoughness& pbr = out.pbrMetallicRoughness;
  pbr.metallicFactor = m.metallic;
  pbr.roughnessFactor = m.roughness;
  set_texture(pbr.metallicRoughnessTexture, m.metallic_roughness_texture, used);
  if (m.metallic_texture.used() || m.roughness_texture.used())
    throw SceneError("material '" + m.name + "': AMD_split_roughnessMetallic's maps cannot be written");
  set_texture(out.normalTexture, m.normal_texture, used);
  out.normalTexture.scale = m.normal_scale;
  if (m.ior != 1.5f) set_extension(out, "KHR_materials_ior", "ior", m.ior, used);
  const float f0 = (m.ior - 1.0f) / (m.ior + 1.0f);
  const glm::vec3 colour = f0 > 0.0f ? m.specular_f0 / (f0 * f0) : glm::vec3(1.0f);
  if (m.specular_weight != 1.0f || colour != glm::vec3(1.0f)) {
    Object specular{{"specularFactor", tinygltf::Value(double(m.specular_weight))}};
    specular["specularColorFactor"] = tinygltf::Value(
        tinygltf::Value::Array{tinygltf::Value(double(colour.r)), tinygltf::Value(double(colour.g)), tinygltf::Value(double(colour.b))});
    out.extensions["KHR_materials_specular"] = tinygltf::Value(std::move(specular));
    used.insert("KHR_materials_specular");
  }
}

// Built-in models as glTF: Lambert exactly (metallic 0 with no specular
// reflection, KHR_materials_specular's specularFactor 0); the conductor and
// the tinted mirror as metallic 1, which glTF draws with Schlick's Fresnel
// from F0 = base colour, marked {"igi_fresnel": "constant"} so that igi (and
// scripts/mitsuba/) read them back with their constant Fresnel.
tinygltf::Material to_gltf(const Material& m, std::set<std::string>& used) {
  tinygltf::Material out;
  out.name = m.name;
  tinygltf::PbrMetallicRoughness& pbr = out.pbrMetallicRoughness;
  pbr.baseColorFactor = {m.base_color.r, m.base_color.g, m.base_color.b, m.base_alpha};
  set_texture(pbr.baseColorTexture, m.base_color_texture, used);
  const tinygltf::Value constant_fresnel(Object{{"igi_fresnel", tinygltf::Value(std::string("constant"))}});
  switch (m.type) {
    case MaterialType::Diffuse:
      pbr.metallicFactor = 0.0, pbr.roughnessFactor = 1.0;
      set_extension(out, "KHR_materials_specular", "specularFactor", 0.0, used);
      break;
    case MaterialType::Conductor:
      pbr.metallicFactor = 1.0, pbr.roughnessFactor = std::sqrt(double(m.alpha));
      out.extras = constant_fresnel;
      break;
    case MaterialType::Mirror:
      pbr.metallicFactor = 1.0, pbr.roughnessFactor = 0.0;
      if (!m.schlick_fresnel) out.extras = constant_fresnel;
      break;
    case MaterialType::Glass:
      pbr.metallicFactor = 0.0, pbr.roughnessFactor = 0.0;
      set_extension(out, "KHR_materials_transmission", "transmissionFactor", 1.0, used);
      set_extension(out, "KHR_materials_ior", "ior", m.ior, used);
      break;
    case MaterialType::MetallicRoughness: write_metallic_roughness(m, out, used); break;
  }
  // emissiveFactor is clamped to [0, 1]; the strength extension carries the rest.
  const float peak = std::max({m.emission.r, m.emission.g, m.emission.b});
  const glm::vec3 factor = peak > 1.0f ? m.emission / peak : m.emission;
  out.emissiveFactor = {factor.r, factor.g, factor.b};
  if (peak > 1.0f) set_extension(out, "KHR_materials_emissive_strength", "emissiveStrength", peak, used);
  if (m.alpha_mask) out.alphaMode = "MASK", out.alphaCutoff = m.alpha_cutoff;
  out.doubleSided = m.double_sided;
  return out;
}

unsigned char linear_to_srgb8(float c) {
  c = std::clamp(c, 0.0f, 1.0f);
  const float encoded = c <= 0.0031308f ? 12.92f * c : 1.055f * std::pow(c, 1.0f / 2.4f) - 0.055f;
  return static_cast<unsigned char>(std::lround(encoded * 255.0f));
}

// 8-bit RGBA that tinygltf hands to stb_image_write as a PNG: the bytes a
// texture was decoded from as they were, floats encoded as the texture
// reads them (sRGB colour, linear data and alpha).
tinygltf::Image to_png_image(const Texture& texture, const std::string& uri) {
  tinygltf::Image image;
  image.uri = uri;
  image.mimeType = "image/png";
  image.width = texture.width, image.height = texture.height;
  image.component = 4, image.bits = 8, image.pixel_type = TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE;
  if (!texture.bytes.empty()) {
    image.image = texture.bytes;
    return image;
  }
  image.image.resize(texture.texels.size() * 4);
  auto linear8 = [](float c) { return static_cast<unsigned char>(std::lround(std::clamp(c, 0.0f, 1.0f) * 255.0f)); };
  for (size_t i = 0; i < texture.texels.size(); ++i) {
    const glm::vec4 t = texture.texels[i];
    for (int c = 0; c < 3; ++c) image.image[4 * i + size_t(c)] = texture.srgb ? linear_to_srgb8(t[c]) : linear8(t[c]);
    image.image[4 * i + 3] = linear8(t.a);
  }
  return image;
}

// glTF texture i is Scene texture i, so materials keep their indices.
void write_textures(const Scene& scene, const std::string& stem, tinygltf::Model& model) {
  for (size_t i = 0; i < scene.textures.size(); ++i) {
    model.images.push_back(to_png_image(scene.textures[i], stem + "_texture" + std::to_string(i) + ".png"));
    tinygltf::Texture texture;
    texture.source = int(i);
    model.textures.push_back(texture);
  }
}

// Rotation turning local -Z onto `forward` and local +Y towards `up`.
std::vector<double> look_rotation(glm::vec3 forward, glm::vec3 up) {
  const glm::dvec3 z = -glm::normalize(glm::dvec3(forward));
  glm::dvec3 x = glm::cross(glm::dvec3(up), z);
  if (glm::length(x) < 1e-9)  // up parallel to forward: any perpendicular will do
    x = glm::cross(std::abs(z.y) < 0.9 ? glm::dvec3(0, 1, 0) : glm::dvec3(1, 0, 0), z);
  x = glm::normalize(x);
  const glm::dquat q = glm::quat_cast(glm::dmat3(x, glm::cross(z, x), z));
  return {q.x, q.y, q.z, q.w};
}

tinygltf::Light to_gltf(const PunctualLight& light) {
  tinygltf::Light out;
  out.type = light.type == LightType::Point  ? "point"
             : light.type == LightType::Spot ? "spot"
                                             : "directional";
  // color in [0, 1], intensity carrying the magnitude, as glTF authors write
  // it, in the specification's candela and lux (scene/light_units.h)
  const float peak = std::max({light.intensity.r, light.intensity.g, light.intensity.b});
  const glm::vec3 color = peak > 0.0f ? light.intensity / peak : glm::vec3(1.0f);
  out.color = {color.r, color.g, color.b};
  out.intensity = std::max(double(peak), 0.0) * kLumensPerWatt;
  out.spot.innerConeAngle = light.inner_cone;
  out.spot.outerConeAngle = light.outer_cone;
  return out;
}

void write_lights(const Scene& scene, tinygltf::Model& model) {
  for (size_t i = 0; i < scene.lights.size(); ++i) {
    const PunctualLight& light = scene.lights[i];
    model.lights.push_back(to_gltf(light));
    tinygltf::Node node;
    node.name = "light " + std::to_string(i);
    node.translation = {light.position.x, light.position.y, light.position.z};
    if (light.type != LightType::Point) node.rotation = look_rotation(light.direction, glm::vec3(0, 1, 0));
    node.extensions["KHR_lights_punctual"] = tinygltf::Value(Object{{"light", tinygltf::Value(int(i))}});
    model.nodes.push_back(node);
  }
}

void write_camera(const Camera& camera, tinygltf::Model& model) {
  tinygltf::Camera out;
  out.type = "perspective";
  out.perspective.yfov = camera.vfov;
  out.perspective.znear = 1e-3;  // required by glTF, unused by a ray tracer
  out.perspective.zfar = 1e9;
  model.cameras.push_back(out);
  tinygltf::Node node;
  node.name = "camera";
  node.camera = int(model.cameras.size() - 1);
  node.translation = {camera.position.x, camera.position.y, camera.position.z};
  node.rotation = look_rotation(camera.forward, camera.up);
  model.nodes.push_back(node);
}

tinygltf::Model to_model(const Scene& scene, const std::string& stem) {
  tinygltf::Model model;
  model.asset.version = "2.0";
  model.asset.generator = "igi-cluster gltf_writer";
  model.buffers.emplace_back();
  model.buffers[0].uri = stem + ".bin";
  write_geometry(scene, model);
  std::set<std::string> used;
  for (const Material& m : scene.materials) model.materials.push_back(to_gltf(m, used));
  write_textures(scene, stem, model);
  write_lights(scene, model);
  if (scene.camera) write_camera(*scene.camera, model);
  if (!scene.lights.empty()) used.insert("KHR_lights_punctual");
  model.extensionsUsed.assign(used.begin(), used.end());
  if (model.buffers[0].data.empty()) model.buffers.clear();
  tinygltf::Scene root;
  root.name = scene.name;
  for (size_t i = 0; i < model.nodes.size(); ++i) root.nodes.push_back(int(i));
  if (scene.has_environment()) {  // gltf_loader.cpp reads it back
    tinygltf::Value::Array sky;
    for (int c = 0; c < 3; ++c) sky.emplace_back(double(scene.environment[c]));
    tinygltf::Value::Object extras;
    extras["environment"] = tinygltf::Value(std::move(sky));
    root.extras = tinygltf::Value(std::move(extras));
  }
  model.scenes.push_back(root);
  model.defaultScene = 0;
  return model;
}

}  // namespace

std::vector<uint8_t> write_glb_bytes(const Scene& scene, const std::string& name) {
  check_writable(scene, name);
  tinygltf::Model model = to_model(scene, fs::path(name).stem().string());
  for (tinygltf::Buffer& buffer : model.buffers) buffer.uri.clear();
  tinygltf::TinyGLTF writer;
  writer.SetImageWriter(&tinygltf::WriteImageData, nullptr);  // images embedded: no files
  std::ostringstream out;
  if (!writer.WriteGltfSceneToStream(&model, out, false, true)) throw SceneError(name + ": cannot encode the scene as .glb");
  const std::string bytes = std::move(out).str();
  return {bytes.begin(), bytes.end()};
}

void write_gltf(const Scene& scene, const std::string& path) {
  check_writable(scene, path);
  const std::string stem = fs::path(path).stem().string();
  // A .glb carries its buffer and images inside: one self-contained file,
  // which is what a master sends to workers without the scene.
  const bool binary = fs::path(path).extension() == ".glb";
  tinygltf::Model model = to_model(scene, stem);
  if (binary)
    for (tinygltf::Buffer& buffer : model.buffers) buffer.uri.clear();
  tinygltf::TinyGLTF writer;
  tinygltf::FsCallbacks files{&tinygltf::FileExists, &tinygltf::ExpandFilePath, &tinygltf::ReadWholeFile,
                              &tinygltf::WriteWholeFile, nullptr};
  writer.SetImageWriter(&tinygltf::WriteImageData, &files);
  if (!writer.WriteGltfSceneToFile(&model, path, binary, binary, !binary, binary))
    throw SceneError(path + ": cannot write the glTF file or its buffer " + stem + ".bin");
  // tinygltf reports a failed image write only by leaving the file out.
  const fs::path folder = fs::path(path).parent_path();
  for (const tinygltf::Image& image : model.images)
    if (!binary && !fs::exists(folder / image.uri))
      throw SceneError(path + ": cannot write texture " + (folder / image.uri).string());
}

}  // namespace igi
