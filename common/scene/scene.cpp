#include "scene/scene.h"

#include <array>
#include <cmath>
#include <string>

#include "image/image.h"

namespace igi {

const char* material_type_name(MaterialType type) {
  switch (type) {
    case MaterialType::Diffuse: return "diffuse";
    case MaterialType::Conductor: return "conductor";
    case MaterialType::Mirror: return "mirror";
    case MaterialType::Glass: return "glass";
    case MaterialType::MetallicRoughness: return "metallic-roughness";
  }
  return "unknown";
}

namespace {

// Byte to linear value, as decoding a whole image to floats gives it
// (scene/texture_decode.cpp once did): the same float expression, so either store samples alike.
struct ByteDecoding {
  std::array<float, 256> linear, srgb;
  ByteDecoding() {
    for (int i = 0; i < 256; ++i) {
      linear[size_t(i)] = float(i) * (1.0f / 255.0f);
      srgb[size_t(i)] = srgb_to_linear(linear[size_t(i)]);
    }
  }
};
const ByteDecoding kBytes;

}  // namespace

glm::vec4 Texture::texel(int x, int y) const {
  const size_t at = size_t(y) * size_t(width) + size_t(x);
  if (bytes.empty()) return texels[at];
  const uint8_t* b = bytes.data() + 4 * at;
  const std::array<float, 256>& colour = srgb ? kBytes.srgb : kBytes.linear;
  return {colour[b[0]], colour[b[1]], colour[b[2]], kBytes.linear[b[3]]};
}

glm::vec4 Texture::sample(glm::vec2 uv) const {
  if (width <= 0 || height <= 0) return glm::vec4(1.0f);
  float fx = (uv.x - std::floor(uv.x)) * width - 0.5f;
  float fy = (uv.y - std::floor(uv.y)) * height - 0.5f;
  int x0 = static_cast<int>(std::floor(fx)), y0 = static_cast<int>(std::floor(fy));
  float tx = fx - x0, ty = fy - y0;
  auto at = [&](int x, int y) {
    x = ((x % width) + width) % width;
    y = ((y % height) + height) % height;
    return texel(x, y);
  };
  return glm::mix(glm::mix(at(x0, y0), at(x0 + 1, y0), tx),
                  glm::mix(at(x0, y0 + 1), at(x0 + 1, y0 + 1), tx), ty);
}

glm::vec4 Texture::mean() const {
  glm::dvec4 sum(0.0);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) sum += glm::dvec4(texel(x, y));
  return width > 0 && height > 0 ? glm::vec4(sum / (double(width) * double(height))) : glm::vec4(1.0f);
}

Bounds Scene::bounds() const {
  Bounds b;
  for (const glm::uvec3& t : triangles)
    for (int k = 0; k < 3; ++k) b.extend(positions[t[k]]);
  return b;
}

bool Scene::has_light() const {
  if (!lights.empty() || has_environment()) return true;
  for (uint32_t m : triangle_material)
    if (materials[m].is_emissive()) return true;
  return false;
}

// From above, on the diagonal the lights face most: the view Blender opens
// with (its default camera at x, -y, +z, Z up) in the quadrant the scene is
// lit from, so a file without a camera shows its lit side.
Camera Scene::auto_camera() const {
  Bounds b = bounds();
  Camera cam;
  if (b.empty()) return cam;
  const glm::vec3 c = b.center();
  glm::vec3 toward_lights(0.0f);  // unit vectors from the centre towards each light
  for (const PunctualLight& light : lights) {
    const glm::vec3 v = light.type == LightType::Directional ? -light.direction : light.position - c;
    if (glm::length(v) > 0.0f) toward_lights += glm::normalize(v);
  }
  glm::vec3 best(0.0f);
  float best_dot = -INFINITY;
  for (const glm::vec2 side : {glm::vec2(1, 1), glm::vec2(-1, 1), glm::vec2(-1, -1), glm::vec2(1, -1)}) {
    const glm::vec3 d = glm::normalize(glm::vec3(side.x, 0.7f, side.y));
    if (const float dot = glm::dot(d, toward_lights); dot > best_dot + 1e-4f) best = d, best_dot = dot;
  }
  const float radius = 0.5f * glm::length(b.upper - b.lower);
  cam.position = c + best * (radius / std::sin(0.5f * cam.vfov));
  cam.forward = -best;
  return cam;
}

static bool finite(glm::vec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

void Scene::validate() const {
  const std::string where = "scene '" + name + "': ";
  if (triangles.empty()) throw SceneError(where + "no geometry (no triangles)");
  if (triangles.size() > kMaxTriangles || positions.size() > kMaxVertices)
    throw SceneError(where + std::to_string(triangles.size()) + " triangles and " + std::to_string(positions.size()) +
                     " vertices, over the limit of " + std::to_string(kMaxTriangles) + " and " +
                     std::to_string(kMaxVertices));
  if (triangle_material.size() != triangles.size())
    throw SceneError(where + "triangle_material has " + std::to_string(triangle_material.size()) +
                     " entries, expected one per triangle (" + std::to_string(triangles.size()) + ")");
  if (!normals.empty() && normals.size() != positions.size())
    throw SceneError(where + "normals must be empty or one per position");
  if (!uvs.empty() && uvs.size() != positions.size())
    throw SceneError(where + "uvs must be empty or one per position");
  for (size_t i = 0; i < positions.size(); ++i)
    if (!finite(positions[i]))
      throw SceneError(where + "position " + std::to_string(i) + " is not finite");
  for (size_t i = 0; i < triangles.size(); ++i) {
    for (int k = 0; k < 3; ++k)
      if (triangles[i][k] >= positions.size())
        throw SceneError(where + "triangle " + std::to_string(i) + " indexes vertex " +
                         std::to_string(triangles[i][k]) + " of " + std::to_string(positions.size()));
    if (triangle_material[i] >= materials.size())
      throw SceneError(where + "triangle " + std::to_string(i) + " uses material " +
                       std::to_string(triangle_material[i]) + " of " + std::to_string(materials.size()));
  }
  for (const Material& m : materials)
    for (const TextureRef* t : {&m.base_color_texture, &m.metallic_roughness_texture, &m.metallic_texture,
                                &m.roughness_texture, &m.normal_texture})
      if (t->index >= int(textures.size()))
        throw SceneError(where + "material '" + m.name + "' names texture " + std::to_string(t->index) + " of " +
                         std::to_string(textures.size()));
  if (!finite(environment) || environment.x < 0.0f || environment.y < 0.0f || environment.z < 0.0f)
    throw SceneError(where + "the environment's radiance must be finite and >= 0");
  if (!has_light())
    throw SceneError(where + "no light (no emissive material, no punctual light, no environment): "
                             "light it with a sky, --environment 1,1,1");
}

}  // namespace igi
