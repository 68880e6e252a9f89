#pragma once
// The renderer's whole view of a scene: flattened world-space triangles,
// a handful of material models, lights and an optional camera.
//
// Conventions (also in the README):
//  - Units: metres (glTF). Nothing in the renderer depends on absolute scale;
//    scale-dependent options are given relative to the scene's bounding box.
//  - Radiometry: RGB radiance in W/(m^2 sr); punctual light intensity in W/sr;
//    directional irradiance in W/m^2 (KHR_lights_punctual read radiometrically).
//  - Area lights are emissive triangles that emit from their front face only
//    (counter-clockwise winding, right-hand rule gives the front normal).
//  - Colours are linear RGB; textures decoded from sRGB on load.
#include <cstdint>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "scene/camera.h"
#include "scene/environment_map.h"

namespace igi {

enum class MaterialType : uint8_t {
  Diffuse,    // Lambertian, albedo = base_color
  Conductor,  // GGX microfacet metal, alpha = roughness^2, Fresnel = base_color
  Mirror,     // perfect specular reflection, tinted by base_color (or glTF's Schlick: schlick_fresnel)
  Glass,      // smooth dielectric with index of refraction ior
  // glTF 2.0's metallic-roughness BRDF (its Appendix B; material/metallic_roughness.h):
  // a Lambertian base under a GGX dielectric coat, mixed by `metallic` with a
  // GGX conductor of Fresnel F0 = base colour; alpha = roughness^2.
  MetallicRoughness,
};

const char* material_type_name(MaterialType type);

// A texture as a material uses it: which one, and KHR_texture_transform's
// affine map of the uv (u' = linear u + offset; the identity when the file
// gives none).
struct TextureRef {
  int index = -1;  // into Scene::textures, or -1: none
  glm::mat2 linear{1.0f};
  glm::vec2 offset{0.0f};
  bool transformed = false;

  bool used() const { return index >= 0; }
  glm::vec2 uv(glm::vec2 uv) const { return transformed ? linear * uv + offset : uv; }
};

// The smallest GGX alpha of the metallic-roughness model: roughness 0 (a
// perfectly smooth coat) is read as this, a lobe far sharper than any
// --glossy-threshold, so it is gathered with rays (and focuses light as a
// caustic) while its diffuse base takes VPL light.
inline constexpr float kMinMetallicRoughnessAlpha = 1e-3f;

struct Material {
  std::string name;
  MaterialType type = MaterialType::Diffuse;
  glm::vec3 base_color{0.8f};
  float alpha = 1.0f;              // GGX roughness parameter (Conductor; MetallicRoughness: roughness^2, untextured)
  float ior = 1.5f;                // Glass; MetallicRoughness: what its specular_f0 was made from
  TextureRef base_color_texture;   // linear RGBA, times base_color (and alpha times base_alpha)
  // MetallicRoughness only. Per point: metallic x the texture's blue channel,
  // roughness x its green (linear), alpha = max(roughness^2, kMinMetallicRoughnessAlpha).
  float metallic = 0.0f;
  float roughness = 1.0f;
  TextureRef metallic_roughness_texture;
  // AMD_split_roughnessMetallic's maps, each in place of its channel of the
  // texture above (every channel of these holds the value).
  TextureRef metallic_texture, roughness_texture;
  float min_alpha = 1.0f;          // the least alpha over the texture's texels (for the threshold's choices)
  // The dielectric coat's Fresnel (KHR_materials_specular, KHR_materials_ior):
  // F0 = min(((ior - 1) / (ior + 1))^2 x specularColorFactor, 1), and the
  // coat's weight specularFactor, which scales its reflection and how much
  // of the diffuse base it hides. The core material: F0 0.04, weight 1.
  glm::vec3 specular_f0{0.04f};
  float specular_weight = 1.0f;
  // A tangent-space normal map (glTF normalTexture), its x and y scaled by normal_scale.
  TextureRef normal_texture;
  float normal_scale = 1.0f;
  // Mirror: glTF's metal Fresnel, F0 = base colour rising to 1 at grazing
  // angles (Schlick), instead of the constant base colour.
  bool schlick_fresnel = false;
  bool alpha_mask = false;         // glTF alphaMode MASK
  float alpha_cutoff = 0.5f;
  float base_alpha = 1.0f;         // baseColorFactor.a
  bool double_sided = true;        // false: back faces are not hit
  glm::vec3 emission{0.0f};        // front-face radiance, W/(m^2 sr)

  bool is_specular() const { return type == MaterialType::Mirror || type == MaterialType::Glass; }
  // Whether camera rays skip the back of its faces: single-sided, and not
  // glass, which refracts on the way out as on the way in (a closed
  // refractive surface has two sides whatever an exporter's doubleSided says).
  bool culls_back_faces() const { return !double_sided && type != MaterialType::Glass; }
  bool is_emissive() const { return emission.x > 0 || emission.y > 0 || emission.z > 0; }
};

// Texels are linear RGBA, row 0 at the top (glTF/image convention), held
// either as floats or, as 8-bit images are (a quarter of the memory: Sponza's
// 34 M texels take 138 MB, not 550), as bytes decoded at lookup: colour
// channels through the sRGB curve when `srgb`, alpha and data maps (normals,
// metallic-roughness) linearly. Both give the same values for the same bytes.
struct Texture {
  int width = 0;
  int height = 0;
  std::vector<glm::vec4> texels;
  std::vector<uint8_t> bytes;  // RGBA8, when texels is empty
  bool srgb = true;            // bytes only: RGB encoded in sRGB
  // Bilinear lookup with repeat wrapping; uv as in glTF (v down).
  glm::vec4 sample(glm::vec2 uv) const;
  glm::vec4 texel(int x, int y) const;  // 0 <= x < width, 0 <= y < height
  glm::vec4 mean() const;               // over every texel
};

enum class LightType : uint8_t { Point, Spot, Directional };

struct PunctualLight {
  LightType type = LightType::Point;
  glm::vec3 position{0.0f};
  glm::vec3 direction{0.0f, 0.0f, -1.0f};  // direction the light travels (spot, directional)
  glm::vec3 intensity{1.0f};               // W/sr (point, spot) or W/m^2 (directional)
  float inner_cone = 0.0f;                 // radians, spot only
  float outer_cone = 0.785398f;            // radians, spot only
};

struct Bounds {
  glm::vec3 lower{1e30f};
  glm::vec3 upper{-1e30f};
  void extend(glm::vec3 p) { lower = glm::min(lower, p); upper = glm::max(upper, p); }
  glm::vec3 center() const { return 0.5f * (lower + upper); }
  float diagonal() const { return glm::length(upper - lower); }
  bool empty() const { return lower.x > upper.x; }
};

struct SceneAnimation;  // scene/animation.h

// The most triangles (instances counted) and vertices a scene may hold: about
// 200 bytes a triangle between the scene, Embree's copy and its BVH, so
// 13 GiB at the limit. Loaders refuse more before expanding instances (a 1 kB
// glTF can instance a mesh a million times); Scene::validate checks it again.
inline constexpr size_t kMaxTriangles = size_t(1) << 26;
inline constexpr size_t kMaxVertices = 3 * kMaxTriangles;

struct Scene {
  std::string name;
  // Per-vertex data; normals and uvs are either empty or one per position.
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;
  std::vector<glm::vec2> uvs;
  std::vector<glm::uvec3> triangles;
  std::vector<uint32_t> triangle_material;  // one per triangle

  std::vector<Material> materials;
  std::vector<Texture> textures;
  std::vector<PunctualLight> lights;
  // The sky around the scene: radiance (W/(m^2 sr)) arriving from every
  // direction a ray leaves the scene by, constant or, with a map, the map's
  // radiance times this; zero for none. From the command line (--environment
  // R,G,B or FILE, --environment-scale, --environment-rotation) or the glTF
  // scene's extras.
  glm::vec3 environment{0.0f};
  std::shared_ptr<const EnvironmentMap> environment_map;
  std::optional<Camera> camera;
  // What moves (animated nodes, the area lights) and how; null when nothing
  // can. pose_scene() in scene/animation.h moves it.
  std::shared_ptr<const SceneAnimation> animation;

  Bounds bounds() const;
  bool has_light() const;
  bool has_environment() const {
    return (environment.x > 0.0f || environment.y > 0.0f || environment.z > 0.0f) &&
           (!environment_map || environment_map->luminance_integral() > 0.0f);
  }
  // Radiance arriving from `direction` (towards the sky, any length > 0).
  glm::vec3 sky(glm::vec3 direction) const {
    return environment_map ? environment * environment_map->radiance(direction) : environment;
  }
  // A camera that frames the bounding box from above, on the one of its four
  // diagonals (+-x, +-z) that faces the punctual lights most, +x +z first
  // (Blender's default view), looking at its centre.
  Camera auto_camera() const;
  Camera camera_or_auto() const { return camera ? *camera : auto_camera(); }
  // Cheap structural checks shared by every producer of scenes; throws
  // SceneError naming the first broken element.
  void validate() const;
};

struct SceneError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

}  // namespace igi
