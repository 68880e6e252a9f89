#include "scene/suite_scenes.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "scene/builtin_scenes.h"
#include "scene/triangle.h"

namespace igi {
namespace {

uint32_t diffuse(Scene& s, const char* name, glm::vec3 albedo) {
  Material m;
  m.name = name;
  m.base_color = albedo;
  return add_material(s, m);
}

uint32_t emitter(Scene& s, const char* name, glm::vec3 radiance) {
  Material m;
  m.name = name;
  m.base_color = glm::vec3(0.78f);
  m.emission = radiance;
  return add_material(s, m);
}

Camera look_at(glm::vec3 eye, glm::vec3 target, float vfov_degrees) {
  Camera c;
  c.position = eye;
  c.forward = glm::normalize(target - eye);
  c.up = {0.0f, 1.0f, 0.0f};
  c.vfov = glm::radians(vfov_degrees);
  return c;
}

// An axis-aligned room's six faces, all double-sided, seen from inside.
void add_room_box(Scene& s, glm::vec3 lo, glm::vec3 hi, uint32_t walls, uint32_t floor, uint32_t ceiling) {
  const float x0 = lo.x, y0 = lo.y, z0 = lo.z, x1 = hi.x, y1 = hi.y, z1 = hi.z;
  add_quad(s, {x0, y0, z0}, {x0, y0, z1}, {x1, y0, z1}, {x1, y0, z0}, floor);    // normal +y
  add_quad(s, {x0, y1, z0}, {x1, y1, z0}, {x1, y1, z1}, {x0, y1, z1}, ceiling);  // normal -y
  add_quad(s, {x0, y0, z0}, {x1, y0, z0}, {x1, y1, z0}, {x0, y1, z0}, walls);    // z = z0, normal +z
  add_quad(s, {x0, y0, z1}, {x0, y1, z1}, {x1, y1, z1}, {x1, y0, z1}, walls);    // z = z1, normal -z
  add_quad(s, {x0, y0, z0}, {x0, y1, z0}, {x0, y1, z1}, {x0, y0, z1}, walls);    // x = x0, normal +x
  add_quad(s, {x1, y0, z0}, {x1, y0, z1}, {x1, y1, z1}, {x1, y1, z0}, walls);    // x = x1, normal -x
}

// Downward-facing square emitter of half-width h centred at (cx, y, cz).
void add_ceiling_light(Scene& s, float cx, float y, float cz, float h, uint32_t material) {
  add_quad(s, {cx + h, y, cz - h}, {cx + h, y, cz + h}, {cx - h, y, cz + h}, {cx - h, y, cz - h}, material);
}

// A square of side 2 half_u x 2 half_v around `center` spanned by unit axes u
// and v, its front face towards `normal`.
void add_facing_quad(Scene& s, glm::vec3 center, glm::vec3 u, glm::vec3 v, glm::vec3 normal, uint32_t material) {
  if (glm::dot(glm::cross(u, v), normal) < 0.0f) std::swap(u, v);
  add_quad(s, center - u - v, center + u - v, center + u + v, center - u + v, material);
}

// Floor, ceiling and walls of a plan of square cells (`cell` metres, x to
// the right, z down the rows): '#' is solid, anything else open. Every
// face looks into its open cell.
void add_floor_plan(Scene& s, const std::vector<std::string>& plan, float cell, float height, uint32_t walls,
                    uint32_t floor, uint32_t ceiling) {
  auto open = [&](int x, int z) {
    return z >= 0 && z < int(plan.size()) && x >= 0 && x < int(plan[size_t(z)].size()) && plan[size_t(z)][size_t(x)] != '#';
  };
  const float h = 0.5f * cell;
  const glm::vec3 ex(h, 0, 0), ey(0, 0.5f * height, 0), ez(0, 0, h);
  for (int z = 0; z < int(plan.size()); ++z)
    for (int x = 0; x < int(plan[size_t(z)].size()); ++x) {
      if (!open(x, z)) continue;
      const glm::vec3 c((float(x) + 0.5f) * cell, 0.5f * height, (float(z) + 0.5f) * cell);
      add_facing_quad(s, c - ey, ex, ez, {0, 1, 0}, floor);
      add_facing_quad(s, c + ey, ex, ez, {0, -1, 0}, ceiling);
      if (!open(x - 1, z)) add_facing_quad(s, c - ex, ey, ez, {1, 0, 0}, walls);
      if (!open(x + 1, z)) add_facing_quad(s, c + ex, ey, ez, {-1, 0, 0}, walls);
      if (!open(x, z - 1)) add_facing_quad(s, c - ez, ex, ey, {0, 0, 1}, walls);
      if (!open(x, z + 1)) add_facing_quad(s, c + ez, ex, ey, {0, 0, -1}, walls);
    }
}

}  // namespace

void group_by_material(Scene& s) {
  std::vector<uint32_t> order(s.triangles.size());
  std::iota(order.begin(), order.end(), 0u);
  std::stable_sort(order.begin(), order.end(),
                   [&](uint32_t a, uint32_t b) { return s.triangle_material[a] < s.triangle_material[b]; });
  std::vector<uint32_t> remap(s.positions.size(), ~0u);
  Scene out;
  for (uint32_t t : order) {
    glm::uvec3 tri;
    for (int k = 0; k < 3; ++k) {
      const uint32_t v = s.triangles[t][k];
      if (remap[v] == ~0u) {
        remap[v] = uint32_t(out.positions.size());
        out.positions.push_back(s.positions[v]);
        if (!s.normals.empty()) out.normals.push_back(s.normals[v]);
        if (!s.uvs.empty()) out.uvs.push_back(s.uvs[v]);
      }
      tri[k] = remap[v];
    }
    out.triangles.push_back(tri);
    out.triangle_material.push_back(s.triangle_material[t]);
  }
  s.positions = std::move(out.positions);
  s.normals = std::move(out.normals);
  s.uvs = std::move(out.uvs);
  s.triangles = std::move(out.triangles);
  s.triangle_material = std::move(out.triangle_material);
}

Scene make_corner_scene() {
  Scene s;
  s.name = "corner";
  const uint32_t walls = diffuse(s, "walls", {0.75f, 0.75f, 0.75f});
  const uint32_t floor = diffuse(s, "floor", {0.6f, 0.55f, 0.5f});
  add_room_box(s, {0, 0, 0}, {4, 2.5f, 4}, walls, floor, walls);
  // The spot's cone covers about a metre around the corner (4, 0, 4): the
  // rest of the room sees only light that bounced there first.
  PunctualLight spot;
  spot.type = LightType::Spot;
  spot.position = {2.2f, 1.6f, 2.2f};
  spot.direction = glm::normalize(glm::vec3(4.0f, 0.0f, 4.0f) - spot.position);
  spot.intensity = glm::vec3(40.0f, 36.0f, 30.0f);
  spot.inner_cone = glm::radians(14.0f);
  spot.outer_cone = glm::radians(20.0f);
  s.lights.push_back(spot);
  s.camera = look_at({0.4f, 1.8f, 0.6f}, {4.0f, 0.5f, 3.6f}, 60.0f);
  group_by_material(s);
  return s;
}

// An axis-aligned block's top and four sides, facing out.
void add_block(Scene& s, glm::vec3 lo, glm::vec3 hi, uint32_t material) {
  const glm::vec3 c = 0.5f * (lo + hi), h = 0.5f * (hi - lo);
  const glm::vec3 x(h.x, 0, 0), y(0, h.y, 0), z(0, 0, h.z);
  add_facing_quad(s, c + y, x, z, {0, 1, 0}, material);
  add_facing_quad(s, c + x, y, z, {1, 0, 0}, material);
  add_facing_quad(s, c - x, y, z, {-1, 0, 0}, material);
  add_facing_quad(s, c + z, x, y, {0, 0, 1}, material);
  add_facing_quad(s, c - z, x, y, {0, 0, -1}, material);
}

Scene make_courtyard_scene() {
  Scene s;
  s.name = "courtyard";
  const uint32_t ground = diffuse(s, "ground", {0.5f, 0.48f, 0.45f});
  const uint32_t white = diffuse(s, "white", glm::vec3(0.75f));
  const uint32_t red = diffuse(s, "red", {0.7f, 0.15f, 0.1f});
  Material metal;
  metal.name = "metal";
  metal.type = MaterialType::Conductor;
  metal.base_color = {0.95f, 0.93f, 0.88f};
  metal.alpha = 0.02f;
  const uint32_t ball = add_material(s, metal);
  add_facing_quad(s, {0, 0, 0}, {8, 0, 0}, {0, 0, 8}, {0, 1, 0}, ground);
  add_block(s, {-2.5f, 0.0f, -2.0f}, {-0.5f, 3.0f, -1.0f}, white);
  add_block(s, {0.8f, 0.0f, -0.6f}, {2.0f, 1.2f, 0.6f}, red);
  add_bumpy_sphere(s, {-0.2f, 0.7f, 1.0f}, 0.7f, 24, [](float, float) { return 1.0f; }, ball);
  s.environment = glm::vec3(1.0f);
  s.camera = look_at({1.5f, 2.2f, 7.0f}, {-0.3f, 0.8f, -0.5f}, 50.0f);
  group_by_material(s);
  return s;
}

Scene make_sunroom_scene() {
  Scene s;
  s.name = "sunroom";
  const uint32_t walls = diffuse(s, "walls", glm::vec3(0.75f));
  const uint32_t ground = diffuse(s, "ground", {0.45f, 0.42f, 0.38f});
  // The ground of 16 x 16 m is the room's floor too; the room stands in
  // its middle, closed but for a window in the wall at z = 0.
  add_facing_quad(s, {2, 0, 2}, {8, 0, 0}, {0, 0, 8}, {0, 1, 0}, ground);
  const float x1 = 4.0f, y1 = 2.5f, z1 = 4.0f;
  add_facing_quad(s, {2, y1, 2}, {2, 0, 0}, {0, 0, 2}, {0, -1, 0}, walls);                 // ceiling
  add_facing_quad(s, {2, 0.5f * y1, z1}, {2, 0, 0}, {0, 0.5f * y1, 0}, {0, 0, -1}, walls);  // back
  add_facing_quad(s, {0, 0.5f * y1, 2}, {0, 0.5f * y1, 0}, {0, 0, 2}, {1, 0, 0}, walls);    // left
  add_facing_quad(s, {x1, 0.5f * y1, 2}, {0, 0.5f * y1, 0}, {0, 0, 2}, {-1, 0, 0}, walls);  // right
  // The window wall, around an opening x in [1.5, 2.5], y in [1.0, 1.8].
  const glm::vec3 in(0, 0, 1);
  add_facing_quad(s, {0.75f, 0.5f * y1, 0}, {0.75f, 0, 0}, {0, 0.5f * y1, 0}, in, walls);
  add_facing_quad(s, {3.25f, 0.5f * y1, 0}, {0.75f, 0, 0}, {0, 0.5f * y1, 0}, in, walls);
  add_facing_quad(s, {2.0f, 0.5f, 0}, {0.5f, 0, 0}, {0, 0.5f, 0}, in, walls);
  add_facing_quad(s, {2.0f, 2.15f, 0}, {0.5f, 0, 0}, {0, 0.35f, 0}, in, walls);
  PunctualLight sun;
  sun.type = LightType::Directional;
  sun.direction = glm::normalize(glm::vec3(0.25f, -0.55f, 0.8f));  // through the window onto the floor
  sun.intensity = glm::vec3(100.0f, 95.0f, 85.0f);
  s.lights.push_back(sun);
  s.camera = look_at({3.5f, 1.7f, 3.6f}, {1.2f, 0.7f, 0.6f}, 60.0f);
  group_by_material(s);
  return s;
}

Scene make_tilted_light_scene() {
  Scene s;
  s.name = "tilted-light";
  const uint32_t walls = diffuse(s, "walls", glm::vec3(0.8f));
  const uint32_t floor = diffuse(s, "floor", glm::vec3(0.5f));
  add_room_box(s, {0, 0, 0}, {4, 3, 4}, walls, floor, walls);
  // A 0.2 m square, one-sided, facing down and towards the corner x = z = 4:
  // the walls beside the corner see it at 75-80 degrees from its normal.
  const uint32_t lamp = emitter(s, "lamp", {100.0f, 85.0f, 70.0f});
  add_quad(s, {3.168f, 2.650f, 3.310f}, {3.310f, 2.650f, 3.168f}, {3.432f, 2.750f, 3.290f},
           {3.290f, 2.750f, 3.432f}, lamp);
  s.camera = look_at({0.5f, 1.6f, 0.5f}, {4.0f, 1.8f, 4.0f}, 60.0f);
  group_by_material(s);
  return s;
}

Scene make_glossy_medium_scene() {
  Scene s = make_tilted_light_scene();
  s.name = "glossy-medium";
  Material metal;
  metal.name = "metal";
  metal.type = MaterialType::Conductor;
  metal.base_color = {0.95f, 0.93f, 0.88f};
  metal.alpha = 0.25f;
  const uint32_t floor = uint32_t(std::find_if(s.materials.begin(), s.materials.end(),
                                               [](const Material& m) { return m.name == "floor"; }) -
                                  s.materials.begin());
  const uint32_t metal_id = add_material(s, metal);
  for (uint32_t& m : s.triangle_material)
    if (m == floor) m = metal_id;
  // Lower than tilted-light's view: half of it is the floor and the lit corner's reflection in it.
  s.camera = look_at({0.5f, 1.6f, 0.5f}, {3.6f, 0.4f, 3.6f}, 60.0f);
  group_by_material(s);
  return s;
}

Scene make_rooms_scene(int n) {
  if (n < 1 || n > kMaxRooms)
    throw SceneError("rooms scene: N = " + std::to_string(n) + ", expected 1.." + std::to_string(kMaxRooms));
  Scene s;
  s.name = n == 4 ? "rooms" : "rooms-" + std::to_string(n);
  const float room = 4.0f, height = 2.5f, door_half = 0.5f, door_top = 2.0f;
  const float size = room * float(n);
  const uint32_t walls = diffuse(s, "walls", {0.7f, 0.7f, 0.7f});
  const uint32_t floor = diffuse(s, "floor", {0.5f, 0.45f, 0.4f});
  const uint32_t ceiling = diffuse(s, "ceiling", {0.8f, 0.8f, 0.8f});
  const uint32_t lamp = emitter(s, "lamp", {12.0f, 10.0f, 7.0f});
  add_room_box(s, {0, 0, 0}, {size, height, size}, walls, floor, ceiling);
  // Inner walls: a wall of n segments at every room boundary, each segment
  // with a centred doorway (two full-height pieces and a lintel).
  for (int k = 1; k < n; ++k)
    for (int j = 0; j < n; ++j) {
      const float c = room * float(k), a = room * float(j), m = a + 0.5f * room, b = a + room;
      // Wall x = c, spanning z in [a, b].
      add_quad(s, {c, 0, a}, {c, 0, m - door_half}, {c, height, m - door_half}, {c, height, a}, walls);
      add_quad(s, {c, 0, m + door_half}, {c, 0, b}, {c, height, b}, {c, height, m + door_half}, walls);
      add_quad(s, {c, door_top, m - door_half}, {c, door_top, m + door_half}, {c, height, m + door_half},
               {c, height, m - door_half}, walls);
      // Wall z = c, spanning x in [a, b].
      add_quad(s, {a, 0, c}, {m - door_half, 0, c}, {m - door_half, height, c}, {a, height, c}, walls);
      add_quad(s, {m + door_half, 0, c}, {b, 0, c}, {b, height, c}, {m + door_half, height, c}, walls);
      add_quad(s, {m - door_half, door_top, c}, {m + door_half, door_top, c}, {m + door_half, height, c},
               {m - door_half, height, c}, walls);
    }
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      add_ceiling_light(s, room * (float(i) + 0.5f), height - 1e-3f, room * (float(j) + 0.5f), 0.3f, lamp);
  // From the first room, down the column of doorways at x = 2 and slightly
  // sideways, so a few rooms show and most lights are hidden.
  s.camera = look_at({1.0f, 1.5f, 0.3f}, {2.6f, 1.0f, std::max(8.0f, size)}, 60.0f);
  group_by_material(s);
  return s;
}

Scene make_corridor_scene() {
  Scene s;
  s.name = "corridor";
  const uint32_t walls = diffuse(s, "walls", {0.8f, 0.8f, 0.8f});
  const uint32_t floor = diffuse(s, "floor", {0.6f, 0.55f, 0.5f});
  const uint32_t ceiling = diffuse(s, "ceiling", {0.85f, 0.85f, 0.85f});
  const uint32_t lamp = emitter(s, "lamp", {kCorridorLamp, 0.9f * kCorridorLamp, 0.7f * kCorridorLamp});
  // Room A (camera) at the top left, a corridor 2 m wide down and then
  // right, room B (lamp) at the bottom right. No straight line leaves A
  // through its door (x 2..4, z = 5) and reaches B: down the first leg to
  // the second (x = 4, z 7..9) it needs a slope of at least 1 in z per x,
  // along the second at most 1 per 2.
  const std::vector<std::string> plan = {
      "##############",  // z = 0
      "#....#########",
      "#....#########",
      "#....#########",
      "#....#########",
      "##..##########",  // z = 5: A's door
      "##..####....##",
      "##..........##",  // z = 7, 8: the corridor's second leg, open into B
      "##..........##",
      "########....##",
      "##############",
  };
  const float height = 2.5f;
  add_floor_plan(s, plan, 1.0f, height, walls, floor, ceiling);
  add_ceiling_light(s, 10.0f, height - 1e-3f, 8.0f, 0.4f, lamp);
  s.camera = look_at({1.5f, 1.6f, 1.4f}, {3.2f, 1.0f, 8.0f}, 60.0f);
  group_by_material(s);
  return s;
}

Scene make_glossy_cornell(float alpha, const std::string& name) {
  Scene s = make_cornell_box();
  s.name = name;
  Material metal;
  metal.name = "metal";
  metal.type = MaterialType::Conductor;
  metal.base_color = {0.95f, 0.93f, 0.88f};
  metal.alpha = alpha;
  const uint32_t floor = add_material(s, metal);
  s.triangle_material[0] = s.triangle_material[1] = floor;  // the floor is the first quad
  group_by_material(s);
  return s;
}

Scene make_large_scene(int triangles) {
  Scene s = make_cornell_box();
  s.name = "large";
  s.triangles.resize(s.triangles.size() - 20);  // the blocks are the last 10 quads
  s.triangle_material.resize(s.triangles.size());
  const uint32_t clay = diffuse(s, "clay", {0.6f, 0.6f, 0.55f});
  // 4 r (r - 1) triangles per sphere of r rings and 2 r segments.
  const double per_sphere = std::ceil(triangles / 9.0);
  const int rings = int(std::ceil(0.5 * (1.0 + std::sqrt(1.0 + per_sphere))));
  for (int gi = 0; gi < 3; ++gi)
    for (int gj = 0; gj < 3; ++gj) {
      const float radius = 0.06f + 0.01f * float((gi + 2 * gj) % 3);
      const glm::vec3 center(0.1f + 0.175f * gi, radius, 0.12f + 0.16f * gj);
      const float lobes = 3.0f + float(gi + gj);
      add_bumpy_sphere(s, center, radius, rings,
                       [lobes](float theta, float phi) { return 1.0f + 0.1f * std::sin(lobes * 2.0f * theta) * std::sin(lobes * phi); },
                       clay);
    }
  group_by_material(s);
  return s;
}

namespace {

// Per-vertex normals for a scene built of flat quads: each quad has vertices
// of its own, so a vertex takes its triangle's face normal.
void add_face_normals(Scene& s) {
  s.normals.assign(s.positions.size(), glm::vec3(0.0f));
  for (const glm::uvec3& t : s.triangles) {
    const glm::vec3 n = triangle_normal(s.positions[t[0]], s.positions[t[1]], s.positions[t[2]]);
    for (int k = 0; k < 3; ++k) s.normals[t[k]] = n;
  }
}

// A UV sphere of `rings` rings and 2 x rings segments, outward-facing, with
// its exact normals at the vertices (smooth shading: a ball lens, not facets).
void add_smooth_sphere(Scene& s, glm::vec3 center, float radius, int rings, uint32_t material) {
  const uint32_t first_vertex = uint32_t(s.positions.size());
  add_bumpy_sphere(s, center, radius, rings, [](float, float) { return 1.0f; }, material);
  s.normals.resize(s.positions.size());
  for (uint32_t v = first_vertex; v < s.positions.size(); ++v) s.normals[v] = glm::normalize(s.positions[v] - center);
}

}  // namespace

Scene make_glass_cornell() {
  Scene s = make_cornell_box();
  s.name = "glass";
  // Triangles 12-21 are the short block, 22-31 the tall block (builtin_scenes.cpp).
  s.triangles.erase(s.triangles.begin() + 12, s.triangles.begin() + 22);
  s.triangle_material.erase(s.triangle_material.begin() + 12, s.triangle_material.begin() + 22);
  Material mirror;
  mirror.name = "mirror";
  mirror.type = MaterialType::Mirror;
  mirror.base_color = glm::vec3(0.95f);
  const uint32_t mirror_id = add_material(s, mirror);
  for (size_t t = 12; t < s.triangles.size(); ++t) s.triangle_material[t] = mirror_id;
  add_face_normals(s);
  Material glass;
  glass.name = "glass";
  glass.type = MaterialType::Glass;
  glass.base_color = glm::vec3(1.0f);
  glass.ior = 1.5f;
  const uint32_t glass_id = add_material(s, glass);
  // A ball lens focuses 1.5 radii from its centre: hung at that height, the
  // ceiling light's image falls on the floor, a little towards the camera
  // (the light is behind and to the right of the ball), where no part of
  // the ball hides it.
  const float radius = 0.09f;
  add_smooth_sphere(s, {0.185f, 1.5f * radius, 0.17f}, radius, 32, glass_id);
  group_by_material(s);
  return s;
}

int suite_room(const std::string& name, glm::vec3 p) {
  if (const int n = parse_rooms_name(name)) {
    const int i = std::clamp(int(std::floor(p.x / 4.0f)), 0, n - 1), j = std::clamp(int(std::floor(p.z / 4.0f)), 0, n - 1);
    return i * n + j;
  }
  if (name == "corridor") return p.z < 5.0f ? 0 : p.x < 8.0f ? 1 : 2;  // the plan of make_corridor_scene()
  return 0;
}

int parse_rooms_name(const std::string& name) {
  if (name == "rooms") return 4;
  const std::string prefix = "rooms-";
  if (name.rfind(prefix, 0) != 0 || name.size() == prefix.size() || name.size() > prefix.size() + 2) return 0;
  int n = 0;
  for (size_t i = prefix.size(); i < name.size(); ++i) {
    if (name[i] < '0' || name[i] > '9') return 0;
    n = 10 * n + (name[i] - '0');
  }
  return n >= 1 && n <= kMaxRooms ? n : 0;
}

}  // namespace igi
