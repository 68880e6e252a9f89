#include "scene/builtin_scenes.h"

#include <algorithm>
#include <cmath>

#include "scene/animation.h"
#include "scene/suite_scenes.h"

namespace igi {

uint32_t add_material(Scene& scene, Material material) {
  scene.materials.push_back(std::move(material));
  return uint32_t(scene.materials.size() - 1);
}

void add_quad(Scene& scene, glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 d, uint32_t material) {
  uint32_t base = uint32_t(scene.positions.size());
  for (glm::vec3 p : {a, b, c, d}) scene.positions.push_back(p);
  scene.triangles.push_back({base, base + 1, base + 2});
  scene.triangles.push_back({base, base + 2, base + 3});
  scene.triangle_material.insert(scene.triangle_material.end(), 2, material);
}

void add_bumpy_sphere(Scene& s, glm::vec3 center, float radius, int rings,
                      const std::function<float(float, float)>& bump, uint32_t material) {
  const int segments = 2 * rings;
  const uint32_t base = uint32_t(s.positions.size());
  for (int i = 0; i <= rings; ++i)
    for (int j = 0; j < segments; ++j) {
      float theta = float(M_PI) * i / rings, phi = 2.0f * float(M_PI) * j / segments;
      glm::vec3 n(std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi));
      s.positions.push_back(center + radius * bump(theta, phi) * n);
    }
  auto index = [&](int i, int j) { return base + uint32_t(i * segments + (j % segments)); };
  for (int i = 0; i < rings; ++i)
    for (int j = 0; j < segments; ++j) {
      // The pole rows lose their degenerate triangle.
      if (i != rings - 1) s.triangles.push_back({index(i, j), index(i + 1, j + 1), index(i + 1, j)});
      if (i != 0) s.triangles.push_back({index(i, j), index(i, j + 1), index(i + 1, j + 1)});
    }
  s.triangle_material.resize(s.triangles.size(), material);
}

Scene make_cornell_box() {
  Scene s;
  s.name = "cornell";
  auto diffuse = [&](const char* name, glm::vec3 albedo) {
    Material m;
    m.name = name;
    m.base_color = albedo;
    return add_material(s, m);
  };
  const uint32_t white = diffuse("white", {0.725f, 0.71f, 0.68f});
  const uint32_t red = diffuse("red", {0.63f, 0.065f, 0.05f});
  const uint32_t green = diffuse("green", {0.14f, 0.45f, 0.091f});
  Material light_material;
  light_material.name = "light";
  light_material.base_color = glm::vec3(0.78f);
  light_material.emission = {17.0f, 12.0f, 4.0f};
  const uint32_t light = add_material(s, light_material);

  // Published coordinates in millimetres.
  auto q = [&](glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 d, uint32_t m) {
    add_quad(s, a * 1e-3f, b * 1e-3f, c * 1e-3f, d * 1e-3f, m);
  };
  q({552.8f, 0, 0}, {0, 0, 0}, {0, 0, 559.2f}, {549.6f, 0, 559.2f}, white);                    // floor
  q({556, 548.8f, 0}, {556, 548.8f, 559.2f}, {0, 548.8f, 559.2f}, {0, 548.8f, 0}, white);      // ceiling
  q({549.6f, 0, 559.2f}, {0, 0, 559.2f}, {0, 548.8f, 559.2f}, {556, 548.8f, 559.2f}, white);   // back
  q({0, 0, 559.2f}, {0, 0, 0}, {0, 548.8f, 0}, {0, 548.8f, 559.2f}, green);                    // right
  q({552.8f, 0, 0}, {549.6f, 0, 559.2f}, {556, 548.8f, 559.2f}, {556, 548.8f, 0}, red);        // left
  // Light, a tenth of a millimetre below the ceiling, emitting downwards.
  q({343, 548.7f, 227}, {343, 548.7f, 332}, {213, 548.7f, 332}, {213, 548.7f, 227}, light);
  // Short block.
  q({130, 165, 65}, {82, 165, 225}, {240, 165, 272}, {290, 165, 114}, white);
  q({290, 0, 114}, {290, 165, 114}, {240, 165, 272}, {240, 0, 272}, white);
  q({130, 0, 65}, {130, 165, 65}, {290, 165, 114}, {290, 0, 114}, white);
  q({82, 0, 225}, {82, 165, 225}, {130, 165, 65}, {130, 0, 65}, white);
  q({240, 0, 272}, {240, 165, 272}, {82, 165, 225}, {82, 0, 225}, white);
  // Tall block.
  q({423, 330, 247}, {265, 330, 296}, {314, 330, 456}, {472, 330, 406}, white);
  q({423, 0, 247}, {423, 330, 247}, {472, 330, 406}, {472, 0, 406}, white);
  q({472, 0, 406}, {472, 330, 406}, {314, 330, 456}, {314, 0, 456}, white);
  q({314, 0, 456}, {314, 330, 456}, {265, 330, 296}, {265, 0, 296}, white);
  q({265, 0, 296}, {265, 330, 296}, {423, 330, 247}, {423, 0, 247}, white);

  Camera cam;
  cam.position = {0.278f, 0.273f, -0.800f};
  cam.forward = {0.0f, 0.0f, 1.0f};
  cam.up = {0.0f, 1.0f, 0.0f};
  cam.vfov = 2.0f * std::atan(12.5f / 35.0f);  // 35 mm lens on 25 mm film
  s.camera = cam;
  return s;
}

Scene make_furnace(float albedo, float radiance) {
  Scene s;
  s.name = "furnace";
  Material m;
  m.name = "furnace";
  m.base_color = glm::vec3(albedo);
  m.emission = glm::vec3(radiance);
  add_material(s, m);
  const int rings = 24, segments = 48;
  auto point = [](int i, int j) {
    float theta = float(M_PI) * i / rings, phi = 2.0f * float(M_PI) * j / segments;
    return glm::vec3(std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi));
  };
  for (int i = 0; i < rings; ++i)
    for (int j = 0; j < segments; ++j) {
      glm::vec3 a = point(i, j), b = point(i + 1, j), c = point(i + 1, j + 1), d = point(i, j + 1);
      // Wound so the front faces the centre; drop the degenerate pole triangles.
      uint32_t base = uint32_t(s.positions.size());
      for (glm::vec3 p : {a, b, c, d}) s.positions.push_back(p);
      if (i != rings - 1) { s.triangles.push_back({base, base + 1, base + 2}); s.triangle_material.push_back(0); }
      if (i != 0) { s.triangles.push_back({base, base + 2, base + 3}); s.triangle_material.push_back(0); }
    }
  Camera cam;
  cam.position = glm::vec3(0.0f);
  cam.forward = {0.0f, 0.0f, 1.0f};
  cam.vfov = 1.2f;
  s.camera = cam;
  return s;
}

Scene make_cornell_blob(int triangles) {
  Scene s = make_cornell_box();
  s.name = "cornell-blob";
  // Drop the blocks: the last 10 quads (20 triangles) of the Cornell box.
  s.triangles.resize(s.triangles.size() - 20);
  s.triangle_material.resize(s.triangles.size());
  const uint32_t white = 0;
  const int rings = std::max(8, int(std::sqrt(triangles / 4.0)));
  add_bumpy_sphere(s, {0.278f, 0.17f, 0.28f}, 0.15f, rings,
                   [](float theta, float phi) { return 1.0f + 0.08f * std::sin(7.0f * theta) * std::sin(5.0f * phi); },
                   white);
  return s;
}

namespace {

// Back and forth along x, `amplitude` metres each way, in `period` seconds.
AnimationChannel sway(double amplitude, double period) {
  AnimationChannel channel;
  channel.path = AnimationPath::Translation;
  channel.interpolation = Interpolation::Linear;
  channel.times = {0.0, 0.25 * period, 0.75 * period, period};
  channel.values = {glm::dvec4(0.0), glm::dvec4(amplitude, 0, 0, 0), glm::dvec4(-amplitude, 0, 0, 0), glm::dvec4(0.0)};
  return channel;
}

}  // namespace

Scene make_cornell_blob_moving(int triangles) {
  Scene s = make_cornell_blob(triangles);
  s.name = "cornell-blob-moving";
  const uint32_t blob = uint32_t(make_cornell_box().triangles.size()) - 20;  // after the walls and the light
  animate_triangles(s, blob, {sway(0.08, 2.0)});
  return s;
}

Scene make_large_moving(int triangles) {
  Scene s = make_large_scene(triangles);
  s.name = "large-moving";
  const uint32_t first = uint32_t(s.triangles.size());
  Material m;
  m.name = "ball";
  m.base_color = {0.7f, 0.3f, 0.2f};
  const uint32_t ball = add_material(s, m);
  add_bumpy_sphere(s, {0.278f, 0.35f, 0.28f}, 0.05f, 24, [](float, float) { return 1.0f; }, ball);
  animate_triangles(s, first, {sway(0.15, 2.0)});
  return s;
}

// "rooms-N" takes any N in 1..kMaxRooms; the list names the largest as an example.
std::vector<std::string> builtin_scene_names() {
  return {"cornell", "cornell-blob", "cornell-blob-moving", "large-moving", "furnace", "corner", "courtyard", "sunroom", "rooms", "rooms-10", "corridor", "tilted-light", "glossy-medium", "glossy", "glossy-rough", "large", "glass"};
}

bool is_builtin_scene(const std::string& name) {
  if (parse_rooms_name(name) > 0) return true;
  for (const std::string& n : builtin_scene_names())
    if (n == name) return true;
  return false;
}

Scene make_builtin_scene(const std::string& name) {
  if (name == "cornell") return make_cornell_box();
  if (name == "furnace") return make_furnace(0.5f, 1.0f);
  if (name == "cornell-blob") return make_cornell_blob(320000);
  if (name == "cornell-blob-moving") return make_cornell_blob_moving(320000);
  if (name == "large-moving") return make_large_moving();
  if (name == "corner") return make_corner_scene();
  if (name == "courtyard") return make_courtyard_scene();
  if (name == "sunroom") return make_sunroom_scene();
  if (name == "tilted-light") return make_tilted_light_scene();
  if (name == "glossy-medium") return make_glossy_medium_scene();
  if (const int rooms = parse_rooms_name(name)) return make_rooms_scene(rooms);
  if (name == "corridor") return make_corridor_scene();
  if (name == "glossy") return make_glossy_cornell();
  if (name == "glossy-rough") return make_glossy_cornell(0.3f, "glossy-rough");
  if (name == "large") return make_large_scene();
  if (name == "glass") return make_glass_cornell();
  std::string known;
  for (const std::string& n : builtin_scene_names()) known += (known.empty() ? "" : ", ") + n;
  known += " (rooms-N for N = 1.." + std::to_string(kMaxRooms) + ")";
  throw SceneError("unknown built-in scene '" + name + "' (known: " + known + ")");
}

}  // namespace igi
