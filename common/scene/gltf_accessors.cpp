#include "scene/gltf_accessors.h"

#include <cmath>
#include <cstring>
#include <initializer_list>

#include <tiny_gltf.h>

namespace igi {
namespace {

// A checked window onto an accessor's elements.
struct AccessorView {
  const unsigned char* first = nullptr;
  size_t count = 0;
  size_t stride = 0;
  int component_type = 0;
};

std::string type_name(int type) {
  switch (type) {
    case TINYGLTF_TYPE_SCALAR: return "SCALAR";
    case TINYGLTF_TYPE_VEC2: return "VEC2";
    case TINYGLTF_TYPE_VEC3: return "VEC3";
    case TINYGLTF_TYPE_VEC4: return "VEC4";
    case TINYGLTF_TYPE_MAT2: return "MAT2";
    case TINYGLTF_TYPE_MAT3: return "MAT3";
    case TINYGLTF_TYPE_MAT4: return "MAT4";
  }
  return "type " + std::to_string(type);
}

std::string component_name(int component) {
  switch (component) {
    case TINYGLTF_COMPONENT_TYPE_BYTE: return "BYTE";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return "UNSIGNED_BYTE";
    case TINYGLTF_COMPONENT_TYPE_SHORT: return "SHORT";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return "UNSIGNED_SHORT";
    case TINYGLTF_COMPONENT_TYPE_INT: return "INT";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: return "UNSIGNED_INT";
    case TINYGLTF_COMPONENT_TYPE_FLOAT: return "FLOAT";
    case TINYGLTF_COMPONENT_TYPE_DOUBLE: return "DOUBLE";
  }
  return "componentType " + std::to_string(component);
}

std::string accessor_name(int index, const std::string& role) {
  return gltf_element("accessors", size_t(index)) + " (" + role + ")";
}

// True when `count` elements of `element` bytes, `stride` apart, starting
// `offset` bytes in, end inside `length` bytes. Written to never overflow.
bool fits(size_t count, size_t stride, size_t element, size_t offset, size_t length) {
  if (offset > length) return false;
  if (count == 0) return true;
  if (element > length - offset) return false;
  return count - 1 <= (length - offset - element) / stride;
}

void check_component(const tinygltf::Accessor& accessor, const std::string& name,
                     std::initializer_list<int> allowed, const GltfDiagnostics& diag) {
  std::string expected;
  for (int component : allowed) {
    if (accessor.componentType == component) return;
    expected += (expected.empty() ? "" : " or ") + component_name(component);
  }
  diag.fail(name, "componentType " + component_name(accessor.componentType) + ", expected " + expected);
}

AccessorView checked_view(const tinygltf::Model& model, int index, const std::string& role,
                          int type, std::initializer_list<int> components,
                          const GltfDiagnostics& diag) {
  if (index < 0 || size_t(index) >= model.accessors.size())
    diag.fail(role, "accessor " + std::to_string(index) + " does not exist (the file has " +
                        std::to_string(model.accessors.size()) + ")");
  const tinygltf::Accessor& accessor = model.accessors[size_t(index)];
  const std::string name = accessor_name(index, role);
  if (accessor.sparse.isSparse) diag.fail(name, "sparse accessors are not supported");
  if (accessor.type != type)
    diag.fail(name, "type " + type_name(accessor.type) + ", expected " + type_name(type));
  check_component(accessor, name, components, diag);
  if (accessor.bufferView < 0 || size_t(accessor.bufferView) >= model.bufferViews.size())
    diag.fail(name, "bufferView " + std::to_string(accessor.bufferView) +
                        " does not exist (accessors without data are not supported)");

  const tinygltf::BufferView& view = model.bufferViews[size_t(accessor.bufferView)];
  const size_t element = size_t(tinygltf::GetComponentSizeInBytes(uint32_t(accessor.componentType))) *
                         size_t(tinygltf::GetNumComponentsInType(uint32_t(accessor.type)));
  const size_t stride = view.byteStride ? view.byteStride : element;
  if (stride < element)
    diag.fail(name, "byteStride " + std::to_string(stride) + " of bufferView " +
                        std::to_string(accessor.bufferView) + " is less than one element (" +
                        std::to_string(element) + " bytes)");
  if (!fits(accessor.count, stride, element, accessor.byteOffset, view.byteLength))
    diag.fail(name, "count " + std::to_string(accessor.count) + " (stride " + std::to_string(stride) +
                        ", byteOffset " + std::to_string(accessor.byteOffset) + ") exceeds bufferView " +
                        std::to_string(accessor.bufferView) + " (" + std::to_string(view.byteLength) +
                        " bytes)");
  const tinygltf::Buffer& buffer = model.buffers[size_t(view.buffer)];
  return {buffer.data.data() + view.byteOffset + accessor.byteOffset, accessor.count, stride,
          accessor.componentType};
}

template <typename T>
T load(const unsigned char* at) {
  T value;
  std::memcpy(&value, at, sizeof(T));
  return value;
}

bool finite(glm::vec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

}  // namespace

void check_buffer_views(const tinygltf::Model& model, const GltfDiagnostics& diag) {
  for (size_t i = 0; i < model.bufferViews.size(); ++i) {
    const tinygltf::BufferView& view = model.bufferViews[i];
    const std::string name = gltf_element("bufferViews", i);
    if (view.buffer < 0 || size_t(view.buffer) >= model.buffers.size())
      diag.fail(name, "buffer " + std::to_string(view.buffer) + " does not exist (the file has " +
                          std::to_string(model.buffers.size()) + ")");
    const size_t size = model.buffers[size_t(view.buffer)].data.size();
    if (!fits(1, 1, view.byteLength, view.byteOffset, size))
      diag.fail(name, "byteOffset " + std::to_string(view.byteOffset) + " + byteLength " +
                          std::to_string(view.byteLength) + " exceeds buffer " +
                          std::to_string(view.buffer) + " (" + std::to_string(size) + " bytes)");
  }
}

std::pair<const unsigned char*, size_t> buffer_view_bytes(const tinygltf::Model& model, int view,
                                                          const std::string& role,
                                                          const GltfDiagnostics& diag) {
  if (view < 0 || size_t(view) >= model.bufferViews.size())
    diag.fail(role, "bufferView " + std::to_string(view) + " does not exist");
  const tinygltf::BufferView& v = model.bufferViews[size_t(view)];
  return {model.buffers[size_t(v.buffer)].data.data() + v.byteOffset, v.byteLength};
}

std::vector<glm::vec3> read_vec3_floats(const tinygltf::Model& model, int accessor,
                                        const std::string& role, bool require_finite,
                                        const GltfDiagnostics& diag) {
  const AccessorView view = checked_view(model, accessor, role, TINYGLTF_TYPE_VEC3,
                                         {TINYGLTF_COMPONENT_TYPE_FLOAT}, diag);
  std::vector<glm::vec3> values(view.count);
  for (size_t i = 0; i < view.count; ++i) {
    values[i] = load<glm::vec3>(view.first + i * view.stride);
    if (require_finite && !finite(values[i]))
      diag.fail(accessor_name(accessor, role), "element " + std::to_string(i) + " is not finite");
  }
  return values;
}

std::vector<float> read_float_elements(const tinygltf::Model& model, int accessor, int components,
                                       const std::string& role, const GltfDiagnostics& diag) {
  const int type = components == 1 ? TINYGLTF_TYPE_SCALAR : components == 3 ? TINYGLTF_TYPE_VEC3 : TINYGLTF_TYPE_VEC4;
  const AccessorView view = checked_view(model, accessor, role, type, {TINYGLTF_COMPONENT_TYPE_FLOAT}, diag);
  std::vector<float> values(view.count * size_t(components));
  for (size_t i = 0; i < view.count; ++i)
    for (int c = 0; c < components; ++c) {
      const float value = load<float>(view.first + i * view.stride + size_t(c) * sizeof(float));
      if (!std::isfinite(value))
        diag.fail(accessor_name(accessor, role), "element " + std::to_string(i) + " is not finite");
      values[i * size_t(components) + size_t(c)] = value;
    }
  return values;
}

std::vector<glm::vec2> read_texcoords(const tinygltf::Model& model, int accessor,
                                      const std::string& role, GltfDiagnostics& diag) {
  const AccessorView view = checked_view(
      model, accessor, role, TINYGLTF_TYPE_VEC2,
      {TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE,
       TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT},
      diag);
  if (view.component_type != TINYGLTF_COMPONENT_TYPE_FLOAT && !model.accessors[size_t(accessor)].normalized)
    diag.fail(accessor_name(accessor, role), "integer texture coordinates must be normalized");
  std::vector<glm::vec2> uvs(view.count);
  for (size_t i = 0; i < view.count; ++i) {
    const unsigned char* at = view.first + i * view.stride;
    switch (view.component_type) {
      case TINYGLTF_COMPONENT_TYPE_FLOAT: uvs[i] = load<glm::vec2>(at); break;
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: uvs[i] = glm::vec2(at[0], at[1]) / 255.0f; break;
      default: uvs[i] = glm::vec2(load<uint16_t>(at), load<uint16_t>(at + 2)) / 65535.0f;
    }
    if (!std::isfinite(uvs[i].x) || !std::isfinite(uvs[i].y)) {
      diag.warn_once("non-finite texcoord", "non-finite texture coordinates (first in " +
                                                 accessor_name(accessor, role) + ") replaced by (0, 0)");
      uvs[i] = glm::vec2(0.0f);
    }
  }
  return uvs;
}

std::vector<uint32_t> read_indices(const tinygltf::Model& model, int accessor,
                                   const std::string& role, size_t vertex_count,
                                   const GltfDiagnostics& diag) {
  const AccessorView view = checked_view(
      model, accessor, role, TINYGLTF_TYPE_SCALAR,
      {TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT,
       TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT},
      diag);
  std::vector<uint32_t> indices(view.count);
  for (size_t i = 0; i < view.count; ++i) {
    const unsigned char* at = view.first + i * view.stride;
    if (view.component_type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE) indices[i] = at[0];
    else if (view.component_type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT) indices[i] = load<uint16_t>(at);
    else indices[i] = load<uint32_t>(at);
    if (indices[i] >= vertex_count)
      diag.fail(accessor_name(accessor, role),
                "index " + std::to_string(indices[i]) + " at element " + std::to_string(i) +
                    " is out of range: the primitive has " + std::to_string(vertex_count) + " vertices");
  }
  return indices;
}

}  // namespace igi
