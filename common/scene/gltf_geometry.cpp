#include "scene/gltf_geometry.h"

#include <cmath>
#include <cstdint>
#include <optional>

#include <tiny_gltf.h>

#include "scene/gltf_accessors.h"
#include "scene/gltf_materials.h"
#include "scene/triangle.h"

namespace igi {
namespace {

// One primitive in object space, checked: indices in range, positions finite.
struct PrimitiveGeometry {
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;  // empty or one per position
  std::vector<glm::vec2> uvs;      // empty or one per position
  std::vector<glm::uvec3> triangles;
  uint32_t material = 0;
};

const char* mode_name(int mode) {
  switch (mode) {
    case TINYGLTF_MODE_POINTS: return "POINTS";
    case TINYGLTF_MODE_LINE: return "LINES";
    case TINYGLTF_MODE_LINE_LOOP: return "LINE_LOOP";
    case TINYGLTF_MODE_LINE_STRIP: return "LINE_STRIP";
    case TINYGLTF_MODE_TRIANGLE_STRIP: return "TRIANGLE_STRIP";
    case TINYGLTF_MODE_TRIANGLE_FAN: return "TRIANGLE_FAN";
  }
  return "unknown";
}

// TEXCOORD_1 -> TEXCOORD_n: one warning per attribute family.
std::string attribute_family(const std::string& name) {
  const size_t underscore = name.rfind('_');
  if (underscore == std::string::npos || underscore + 1 == name.size()) return name;
  for (size_t i = underscore + 1; i < name.size(); ++i)
    if (!std::isdigit(static_cast<unsigned char>(name[i]))) return name;
  return name.substr(0, underscore) + "_n";
}

std::string attribute_consequence(const std::string& family) {
  if (family == "TEXCOORD_n") return "every texture uses TEXCOORD_0";
  if (family == "COLOR_n") return "colour comes from the material alone";
  if (family == "TANGENT") return "normal maps use tangents from the uv layout (scene/surface.cpp)";
  if (family == "JOINTS_n" || family == "WEIGHTS_n") return "meshes are rendered in their bind pose";
  return "the renderer has no use for it";
}

void warn_ignored_attributes(const tinygltf::Primitive& primitive, GltfDiagnostics& diag) {
  for (const auto& [name, accessor] : primitive.attributes) {
    if (name == "POSITION" || name == "NORMAL" || name == "TEXCOORD_0") continue;
    const std::string family = attribute_family(name);
    const std::string shown = family == name ? name : family + " (" + name + ")";
    diag.warn_once("attribute " + family,
                   "vertex attribute " + shown + " ignored: " + attribute_consequence(family));
  }
}

std::optional<int> attribute(const tinygltf::Primitive& primitive, const char* name) {
  auto it = primitive.attributes.find(name);
  return it == primitive.attributes.end() ? std::nullopt : std::optional<int>(it->second);
}

// Sine of the angle at p0 below float precision, or an area that the
// renderer's float arithmetic (LightSet::triangle_area) rounds to zero, as
// for tiny coordinates: no area to hit or to sample.
bool zero_area(glm::vec3 p0, glm::vec3 p1, glm::vec3 p2) {
  if (!(0.5f * glm::length(triangle_cross(p0, p1, p2)) > 0.0f)) return true;
  const glm::dvec3 e1 = glm::dvec3(p1) - glm::dvec3(p0), e2 = glm::dvec3(p2) - glm::dvec3(p0);
  const double twice_area = glm::length(glm::cross(e1, e2));
  return !(twice_area > 1e-7 * glm::length(e1) * glm::length(e2));
}

bool unit_length(glm::vec3 n) {
  const float length2 = glm::dot(n, n);
  return std::isfinite(length2) && length2 > 0.5f;
}

class GeometryBuilder {
 public:
  GeometryBuilder(const tinygltf::Model& model, GltfDiagnostics& diag, Scene& scene)
      : model_(model), diag_(diag), scene_(scene), meshes_(model.meshes.size()) {}

  void add(const std::vector<MeshInstance>& instances);

 private:
  const std::vector<PrimitiveGeometry>& mesh(int index);
  std::optional<PrimitiveGeometry> read_primitive(const tinygltf::Primitive& primitive,
                                                  const std::string& name);
  std::vector<glm::uvec3> read_triangles(const tinygltf::Primitive& primitive, const std::string& name,
                                         size_t vertex_count);
  uint32_t material_index(int material, const std::string& name);
  void reserve(const std::vector<MeshInstance>& instances);
  void append(const PrimitiveGeometry& geometry, const glm::dmat4& world);
  void append_flat(const PrimitiveGeometry& geometry, const glm::dmat4& world, bool flip);
  void repair_normals(size_t first_vertex, size_t first_triangle);
  void add_part(const PrimitiveGeometry& geometry, const MeshInstance& instance, size_t first_vertex,
                size_t first_triangle);

 public:
  std::vector<DynamicPart> parts;

 private:
  const tinygltf::Model& model_;
  GltfDiagnostics& diag_;
  Scene& scene_;
  std::vector<std::optional<std::vector<PrimitiveGeometry>>> meshes_;  // read on first use
  std::optional<uint32_t> default_material_;
  bool any_normals_ = false, any_uvs_ = false;
  size_t zero_area_ = 0, repaired_normals_ = 0;
};

void GeometryBuilder::add(const std::vector<MeshInstance>& instances) {
  // Read everything first: the vertex layout depends on whether any
  // instanced primitive has normals or uvs.
  for (const MeshInstance& instance : instances)
    for (const PrimitiveGeometry& geometry : mesh(instance.mesh)) {
      any_normals_ |= !geometry.normals.empty();
      any_uvs_ |= !geometry.uvs.empty();
    }
  reserve(instances);
  for (const MeshInstance& instance : instances)
    for (const PrimitiveGeometry& geometry : mesh(instance.mesh)) {
      const size_t first_vertex = scene_.positions.size(), first_triangle = scene_.triangles.size();
      append(geometry, instance.world);
      if (instance.pose_node >= 0) add_part(geometry, instance, first_vertex, first_triangle);
    }
  if (zero_area_ > 0)
    diag_.warn_once("zero-area triangles", "dropped " + std::to_string(zero_area_) + " zero-area triangles");
  if (repaired_normals_ > 0)
    diag_.warn_once("non-finite normals", "replaced " + std::to_string(repaired_normals_) +
                                              " non-finite or zero normals by geometric normals");
}

const std::vector<PrimitiveGeometry>& GeometryBuilder::mesh(int index) {
  std::optional<std::vector<PrimitiveGeometry>>& slot = meshes_[size_t(index)];
  if (slot) return *slot;
  slot.emplace();
  const tinygltf::Mesh& source = model_.meshes[size_t(index)];
  for (size_t p = 0; p < source.primitives.size(); ++p) {
    const std::string name = gltf_element("meshes", size_t(index)) + "." + gltf_element("primitives", p);
    std::optional<PrimitiveGeometry> geometry = read_primitive(source.primitives[p], name);
    if (geometry) slot->push_back(std::move(*geometry));
  }
  return *slot;
}

std::optional<PrimitiveGeometry> GeometryBuilder::read_primitive(const tinygltf::Primitive& primitive,
                                                                 const std::string& name) {
  if (primitive.mode != -1 && primitive.mode != TINYGLTF_MODE_TRIANGLES) {
    diag_.warn_once(std::string("mode ") + mode_name(primitive.mode),
                    std::string("primitives with mode ") + mode_name(primitive.mode) +
                        " skipped: only TRIANGLES are rendered (first: " + name + ")");
    return std::nullopt;
  }
  warn_ignored_attributes(primitive, diag_);
  const std::optional<int> position = attribute(primitive, "POSITION");
  if (!position) {
    diag_.warn_once("no POSITION", "primitives without POSITION skipped (first: " + name + ")");
    return std::nullopt;
  }
  PrimitiveGeometry geometry;
  geometry.positions = read_vec3_floats(model_, *position, "POSITION of " + name, true, diag_);
  const size_t count = geometry.positions.size();
  if (const std::optional<int> normal = attribute(primitive, "NORMAL"))
    geometry.normals = read_vec3_floats(model_, *normal, "NORMAL of " + name, false, diag_);
  if (const std::optional<int> uv = attribute(primitive, "TEXCOORD_0"))
    geometry.uvs = read_texcoords(model_, *uv, "TEXCOORD_0 of " + name, diag_);
  const std::string expected = " elements, POSITION has " + std::to_string(count);
  if (!geometry.normals.empty() && geometry.normals.size() != count)
    diag_.fail(name, "NORMAL has " + std::to_string(geometry.normals.size()) + expected);
  if (!geometry.uvs.empty() && geometry.uvs.size() != count)
    diag_.fail(name, "TEXCOORD_0 has " + std::to_string(geometry.uvs.size()) + expected);
  geometry.triangles = read_triangles(primitive, name, count);
  geometry.material = material_index(primitive.material, name);
  if (geometry.uvs.empty() && scene_.materials[geometry.material].base_color_texture.used())
    diag_.warn_once("texture without uvs", "primitives with a baseColorTexture but no TEXCOORD_0 (first: " +
                                               name + ") sample the texture at (0, 0)");
  return geometry;
}

std::vector<glm::uvec3> GeometryBuilder::read_triangles(const tinygltf::Primitive& primitive,
                                                        const std::string& name, size_t vertex_count) {
  std::vector<uint32_t> indices;
  if (primitive.indices >= 0) {
    indices = read_indices(model_, primitive.indices, "indices of " + name, vertex_count, diag_);
  } else {
    if (vertex_count > UINT32_MAX) diag_.fail(name, "more than 2^32 vertices");
    indices.resize(vertex_count);
    for (size_t i = 0; i < vertex_count; ++i) indices[i] = uint32_t(i);
  }
  if (indices.size() % 3 != 0)
    diag_.fail(name, std::to_string(indices.size()) + (primitive.indices >= 0 ? " indices" : " vertices") +
                         ", expected a multiple of 3 for TRIANGLES");
  std::vector<glm::uvec3> triangles(indices.size() / 3);
  for (size_t t = 0; t < triangles.size(); ++t)
    triangles[t] = glm::uvec3(indices[3 * t], indices[3 * t + 1], indices[3 * t + 2]);
  return triangles;
}

uint32_t GeometryBuilder::material_index(int material, const std::string& name) {
  if (material >= 0) {
    if (size_t(material) >= model_.materials.size())
      diag_.fail(name, "material " + std::to_string(material) + " does not exist (the file has " +
                           std::to_string(model_.materials.size()) + ")");
    return uint32_t(material);
  }
  if (!default_material_) {
    default_material_ = uint32_t(scene_.materials.size());
    scene_.materials.push_back(default_gltf_material());
  }
  return *default_material_;
}

void GeometryBuilder::reserve(const std::vector<MeshInstance>& instances) {
  size_t vertices = 0, triangles = 0;
  for (const MeshInstance& instance : instances)
    for (const PrimitiveGeometry& geometry : mesh(instance.mesh)) {
      const bool flat = any_normals_ && geometry.normals.empty();
      vertices += flat ? 3 * geometry.triangles.size() : geometry.positions.size();
      triangles += geometry.triangles.size();
    }
  // The budget, before anything is expanded: instancing multiplies a small file.
  if (triangles > kMaxTriangles || vertices > kMaxVertices)
    diag_.fail("meshes", "the instanced meshes hold " + std::to_string(triangles) + " triangles and " +
                             std::to_string(vertices) + " vertices, over the limit of " +
                             std::to_string(kMaxTriangles) + " triangles and " + std::to_string(kMaxVertices) +
                             " vertices");
  scene_.positions.reserve(scene_.positions.size() + vertices);
  if (any_normals_) scene_.normals.reserve(scene_.normals.size() + vertices);
  if (any_uvs_) scene_.uvs.reserve(scene_.uvs.size() + vertices);
  scene_.triangles.reserve(scene_.triangles.size() + triangles);
  scene_.triangle_material.reserve(scene_.triangle_material.size() + triangles);
}

void GeometryBuilder::append(const PrimitiveGeometry& geometry, const glm::dmat4& world) {
  const glm::dmat3 linear(world);
  const bool flip = glm::determinant(linear) < 0.0;
  if (any_normals_ && geometry.normals.empty()) return append_flat(geometry, world, flip);
  const glm::dmat3 normal_matrix = glm::transpose(glm::inverse(linear));
  const size_t first_vertex = scene_.positions.size(), first_triangle = scene_.triangles.size();
  for (size_t v = 0; v < geometry.positions.size(); ++v) {
    scene_.positions.push_back(glm::vec3(world * glm::dvec4(geometry.positions[v], 1.0)));
    if (any_normals_)
      scene_.normals.push_back(glm::vec3(glm::normalize(normal_matrix * glm::dvec3(geometry.normals[v]))));
    if (any_uvs_) scene_.uvs.push_back(geometry.uvs.empty() ? glm::vec2(0.0f) : geometry.uvs[v]);
  }
  for (glm::uvec3 t : geometry.triangles) {
    if (flip) std::swap(t.y, t.z);
    t += glm::uvec3(uint32_t(first_vertex));
    if (zero_area(scene_.positions[t.x], scene_.positions[t.y], scene_.positions[t.z])) {
      ++zero_area_;
      continue;
    }
    scene_.triangles.push_back(t);
    scene_.triangle_material.push_back(geometry.material);
  }
  if (any_normals_) repair_normals(first_vertex, first_triangle);
}

// Three vertices per triangle, each with the triangle's geometric normal.
void GeometryBuilder::append_flat(const PrimitiveGeometry& geometry, const glm::dmat4& world, bool flip) {
  for (glm::uvec3 t : geometry.triangles) {
    if (flip) std::swap(t.y, t.z);
    glm::vec3 p[3];
    for (int k = 0; k < 3; ++k) p[k] = glm::vec3(world * glm::dvec4(geometry.positions[t[k]], 1.0));
    if (zero_area(p[0], p[1], p[2])) {
      ++zero_area_;
      continue;
    }
    const glm::vec3 normal = triangle_normal(p[0], p[1], p[2]);
    const uint32_t first = uint32_t(scene_.positions.size());
    for (int k = 0; k < 3; ++k) {
      scene_.positions.push_back(p[k]);
      scene_.normals.push_back(normal);
      if (any_uvs_) scene_.uvs.push_back(geometry.uvs.empty() ? glm::vec2(0.0f) : geometry.uvs[t[k]]);
    }
    scene_.triangles.push_back(glm::uvec3(first, first + 1, first + 2));
    scene_.triangle_material.push_back(geometry.material);
  }
}

// A vertex normal that is not finite or has no length gets the area-weighted
// mean of its triangles' geometric normals.
void GeometryBuilder::repair_normals(size_t first_vertex, size_t first_triangle) {
  std::vector<glm::vec3>& normals = scene_.normals;
  std::vector<size_t> broken;
  for (size_t v = first_vertex; v < normals.size(); ++v)
    if (!unit_length(normals[v])) broken.push_back(v);
  if (broken.empty()) return;
  std::vector<glm::vec3> sum(normals.size() - first_vertex, glm::vec3(0.0f));
  for (size_t t = first_triangle; t < scene_.triangles.size(); ++t) {
    const glm::uvec3 tri = scene_.triangles[t];
    const glm::vec3 face = triangle_cross(scene_, uint32_t(t));  // area-weighted
    for (int k = 0; k < 3; ++k) sum[tri[k] - first_vertex] += face;
  }
  for (size_t v : broken) {
    const glm::vec3 s = sum[v - first_vertex];
    const float length = glm::length(s);
    // A vertex no kept triangle uses is never shaded; any unit vector will do.
    normals[v] = length > 0.0f && std::isfinite(length) ? s / length : glm::vec3(0.0f, 0.0f, 1.0f);
  }
  repaired_normals_ += broken.size();
}

// What posing a moving instance needs: its triangles and vertices as just
// appended, and the object-space data they came from.
void GeometryBuilder::add_part(const PrimitiveGeometry& geometry, const MeshInstance& instance,
                               size_t first_vertex, size_t first_triangle) {
  DynamicPart part;
  part.node = instance.pose_node;
  part.rest_flip = glm::determinant(glm::dmat3(instance.world)) < 0.0;
  part.flat = any_normals_ && geometry.normals.empty();
  for (size_t t = first_triangle; t < scene_.triangles.size(); ++t) {
    part.triangles.push_back(uint32_t(t));
    part.rest_triangles.push_back(scene_.triangles[t]);
  }
  const size_t vertex_count = scene_.positions.size() - first_vertex;
  for (size_t v = 0; v < vertex_count; ++v) part.vertices.push_back(uint32_t(first_vertex + v));
  if (part.flat) {
    // append_flat's vertices: three per kept triangle, in the (mirrored) winding.
    for (glm::uvec3 t : geometry.triangles) {
      if (part.rest_flip) std::swap(t.y, t.z);
      glm::vec3 p[3];
      for (int k = 0; k < 3; ++k) p[k] = glm::vec3(instance.world * glm::dvec4(geometry.positions[t[k]], 1.0));
      if (zero_area(p[0], p[1], p[2])) continue;
      for (int k = 0; k < 3; ++k) part.object_positions.push_back(geometry.positions[t[k]]);
    }
  } else {
    part.object_positions = geometry.positions;
    if (any_normals_) {
      part.object_normals = geometry.normals;
      // A normal the loader repaired stays as repaired, carried back into object space.
      const glm::dmat3 linear(instance.world);
      const glm::dmat3 normal_matrix = glm::transpose(glm::inverse(linear));
      for (size_t v = 0; v < vertex_count; ++v)
        if (!unit_length(glm::vec3(glm::normalize(normal_matrix * glm::dvec3(part.object_normals[v])))))
          part.object_normals[v] = glm::vec3(glm::transpose(linear) * glm::dvec3(scene_.normals[first_vertex + v]));
    }
  }
  parts.push_back(std::move(part));
}

}  // namespace

std::vector<DynamicPart> add_mesh_instances(const tinygltf::Model& model, const std::vector<MeshInstance>& instances,
                                            GltfDiagnostics& diag, Scene& scene) {
  GeometryBuilder builder(model, diag, scene);
  builder.add(instances);
  return std::move(builder.parts);
}

}  // namespace igi
