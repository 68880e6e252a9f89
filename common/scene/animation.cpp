#include "scene/animation.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include <glm/gtc/quaternion.hpp>

#include "scene/triangle.h"

namespace igi {
namespace {

glm::dquat as_quat(glm::dvec4 v) { return glm::dquat(v.w, v.x, v.y, v.z); }
glm::dvec4 as_vec(glm::dquat q) { return glm::dvec4(q.x, q.y, q.z, q.w); }

}  // namespace

// glTF 2.0, Appendix C: Interpolation.
glm::dvec4 AnimationChannel::sample(double time) const {
  const bool cubic = interpolation == Interpolation::CubicSpline;
  auto value = [&](size_t key) { return values[cubic ? 3 * key + 1 : key]; };
  const size_t last = times.size() - 1;
  if (time <= times.front()) return value(0);
  if (time >= times[last]) return value(last);
  const size_t k = size_t(std::upper_bound(times.begin(), times.end(), time) - times.begin()) - 1;
  const double dt = times[k + 1] - times[k];
  const double u = (time - times[k]) / dt;
  const bool rotation = path == AnimationPath::Rotation;
  switch (interpolation) {
    case Interpolation::Step: return value(k);
    case Interpolation::Linear:
      if (rotation) return as_vec(glm::slerp(as_quat(value(k)), as_quat(value(k + 1)), u));
      return glm::mix(value(k), value(k + 1), u);
    case Interpolation::CubicSpline: {
      const double u2 = u * u, u3 = u2 * u;
      const glm::dvec4 p0 = value(k), m0 = dt * values[3 * k + 2];
      const glm::dvec4 p1 = value(k + 1), m1 = dt * values[3 * (k + 1)];
      const glm::dvec4 p = (2 * u3 - 3 * u2 + 1) * p0 + (u3 - 2 * u2 + u) * m0 + (-2 * u3 + 3 * u2) * p1 +
                           (u3 - u2) * m1;
      return rotation ? as_vec(glm::normalize(as_quat(p))) : p;
    }
  }
  return value(k);
}

// One pass over the channels, each applied to its node: O(nodes + channels).
std::vector<NodeTrs> SceneAnimation::locals(double time) const {
  std::vector<NodeTrs> trs(nodes.size());
  for (size_t i = 0; i < nodes.size(); ++i) trs[i] = nodes[i].rest;
  for (const AnimationChannel& channel : channels) {
    const glm::dvec4 v = channel.sample(time);
    NodeTrs& t = trs[channel.node];
    switch (channel.path) {
      case AnimationPath::Translation: t.translation = glm::dvec3(v); break;
      case AnimationPath::Rotation: t.rotation = as_quat(v); break;
      case AnimationPath::Scale: t.scale = glm::dvec3(v); break;
    }
  }
  return trs;
}

std::vector<glm::dmat4> SceneAnimation::world(double time) const {
  const std::vector<NodeTrs> trs = locals(time);
  std::vector<glm::dmat4> out(nodes.size());
  for (size_t i = 0; i < nodes.size(); ++i) {
    const glm::dmat4& parent = nodes[i].parent >= 0 ? out[size_t(nodes[i].parent)] : nodes[i].parent_world;
    out[i] = parent * (nodes[i].matrix ? *nodes[i].matrix : trs_matrix(trs[i]));
  }
  return out;
}

namespace {

// Where a Hermite segment's components turn (its derivative's roots in (0, 1)),
// as times: between its keys a CUBICSPLINE reaches its extremes there, not at
// the keys (a tangent of 1e30 m/s overshoots keys that are all at the origin).
void add_turning_times(const AnimationChannel& c, size_t k, std::vector<double>& out) {
  const double dt = c.times[k + 1] - c.times[k];
  const glm::dvec4 p0 = c.values[3 * k + 1], m0 = dt * c.values[3 * k + 2];
  const glm::dvec4 p1 = c.values[3 * (k + 1) + 1], m1 = dt * c.values[3 * (k + 1)];
  for (int i = 0; i < 4; ++i) {
    // p'(u) = a u^2 + b u + c
    const double a = 6 * (p0[i] - p1[i]) + 3 * (m0[i] + m1[i]), b = 6 * (p1[i] - p0[i]) - 4 * m0[i] - 2 * m1[i];
    const double cc = m0[i];
    double roots[2];
    int n = 0;
    if (std::abs(a) < 1e-300) {
      if (std::abs(b) > 1e-300) roots[n++] = -cc / b;
    } else if (const double d = b * b - 4 * a * cc; d >= 0) {
      roots[n++] = (-b - std::sqrt(d)) / (2 * a);
      roots[n++] = (-b + std::sqrt(d)) / (2 * a);
    }
    for (int r = 0; r < n; ++r)
      if (roots[r] > 0 && roots[r] < 1) out.push_back(c.times[k] + roots[r] * dt);
  }
  out.push_back(c.times[k] + 0.5 * dt);  // and the middle, for composed channels that turn elsewhere
}

}  // namespace

std::optional<SceneAnimation::OutOfRange> SceneAnimation::check_extent(double max_coordinate) const {
  std::vector<double> keys, times;
  for (const AnimationChannel& channel : channels) {
    keys.insert(keys.end(), channel.times.begin(), channel.times.end());
    if (channel.interpolation == Interpolation::CubicSpline && channel.path != AnimationPath::Rotation)
      for (size_t k = 0; k + 1 < channel.times.size(); ++k) add_turning_times(channel, k, times);
  }
  std::sort(keys.begin(), keys.end());
  keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
  times.insert(times.end(), keys.begin(), keys.end());
  std::sort(times.begin(), times.end());
  times.erase(std::unique(times.begin(), times.end()), times.end());
  auto is_key = [&](double t) { return std::binary_search(keys.begin(), keys.end(), t); };
  auto beyond = [&](glm::dvec3 p) { return !(glm::all(glm::lessThanEqual(glm::abs(p), glm::dvec3(max_coordinate)))); };
  // A part's vertices lie in the image of its object-space box: when the
  // box's corners stay in range, so do they (checked at 8 points a key).
  std::vector<Bounds> boxes(parts.size());
  for (size_t i = 0; i < parts.size(); ++i)
    for (const glm::vec3& p : parts[i].object_positions) boxes[i].extend(p);
  for (const double time : times) {
    const std::vector<glm::dmat4> worlds = world(time);
    for (size_t i = 0; i < parts.size(); ++i) {
      if (parts[i].node < 0 || boxes[i].empty()) continue;
      for (int corner = 0; corner < 8; ++corner) {
        const glm::dvec3 p(corner & 1 ? boxes[i].upper.x : boxes[i].lower.x, corner & 2 ? boxes[i].upper.y : boxes[i].lower.y,
                           corner & 4 ? boxes[i].upper.z : boxes[i].lower.z);
        const glm::dvec3 q = glm::dvec3(worlds[size_t(parts[i].node)] * glm::dvec4(p, 1.0));
        if (beyond(q)) return OutOfRange{time, is_key(time), "a moving part or light", q};
      }
    }
    for (const int node : light_node)
      if (node >= 0 && beyond(glm::dvec3(worlds[size_t(node)][3])))
        return OutOfRange{time, is_key(time), "a moving part or light", glm::dvec3(worlds[size_t(node)][3])};
    if (camera_node >= 0) {
      const glm::dmat4& w = worlds[size_t(camera_node)];
      if (beyond(glm::dvec3(w[3]))) return OutOfRange{time, is_key(time), "the camera", glm::dvec3(w[3])};
      if (is_key(time) && !camera_at_node(w, 1.0))  // between keys camera() keeps the rest camera
        return OutOfRange{time, is_key(time), "the camera's view collapses: its node, or one above it, is scaled to nothing",
                          {}};
    }
  }
  return std::nullopt;
}

Camera SceneAnimation::camera(double time, const Camera& rest) const {
  if (camera_node < 0) return rest;
  return camera_at_node(world(time)[size_t(camera_node)], rest.vfov).value_or(rest);
}

Camera scene_camera(const Scene& scene, double time) {
  if (scene.camera && scene.animation) return scene.animation->camera(time, *scene.camera);
  return scene.camera_or_auto();
}

void place_camera(Scene& scene, const Camera& camera) {
  scene.camera = camera;
  if (scene.animation && scene.animation->camera_node >= 0) {
    auto animation = std::make_shared<SceneAnimation>(*scene.animation);
    animation->camera_node = -1;
    scene.animation = std::move(animation);
  }
}

namespace {

// The light group follows the window's offset only: a translation, which
// leaves normals and winding as they are (and moves nothing at offset 0).
void pose_light_group(Scene& scene, const DynamicPart& part, glm::vec3 offset) {
  const glm::dmat4 move = glm::translate(glm::dmat4(1.0), glm::dvec3(offset));
  for (size_t i = 0; i < part.vertices.size(); ++i)
    scene.positions[part.vertices[i]] = world_point(move, glm::dvec3(part.object_positions[i]));
}

// The loader's arithmetic (gltf_geometry.cpp): positions by the world
// matrix, normals by its inverse transpose, winding mirrored with it.
void pose_node_part(Scene& scene, const DynamicPart& part, const glm::dmat4& world) {
  const glm::dmat3 linear(world);
  const bool flip = glm::determinant(linear) < 0.0;
  for (size_t i = 0; i < part.vertices.size(); ++i)
    scene.positions[part.vertices[i]] = world_point(world, glm::dvec3(part.object_positions[i]));
  if (!part.object_normals.empty()) {
    const glm::dmat3 normal_matrix = glm::transpose(glm::inverse(linear));
    for (size_t i = 0; i < part.vertices.size(); ++i)
      scene.normals[part.vertices[i]] = glm::vec3(glm::normalize(normal_matrix * glm::dvec3(part.object_normals[i])));
  }
  for (size_t i = 0; i < part.triangles.size(); ++i) {
    glm::uvec3 t = part.rest_triangles[i];
    if (flip != part.rest_flip) std::swap(t.y, t.z);
    scene.triangles[part.triangles[i]] = t;
    if (part.flat) {
      const glm::vec3 n = triangle_normal(scene, part.triangles[i]);
      for (int k = 0; k < 3; ++k) scene.normals[t[k]] = n;
    }
  }
}

}  // namespace

void pose_scene(Scene& scene, const ScenePose& pose) {
  if (!scene.animation) return;
  const SceneAnimation& animation = *scene.animation;
  const std::vector<glm::dmat4> world = animation.world(pose.time);
  for (const DynamicPart& part : animation.parts) {
    if (part.node < 0) pose_light_group(scene, part, pose.light_offset);
    else pose_node_part(scene, part, world[size_t(part.node)]);
  }
  for (size_t i = 0; i < scene.lights.size() && i < animation.rest_lights.size(); ++i) {
    PunctualLight light = animation.rest_lights[i];
    if (const int node = animation.light_node[i]; node >= 0) {
      light.position = world_point(world[size_t(node)], glm::dvec3(0.0));
      light.direction = glm::vec3(world_axis(world[size_t(node)], glm::dvec3(0.0, 0.0, -1.0)));
    }
    if (pose.light_offset != glm::vec3(0.0f)) light.position += pose.light_offset;
    scene.lights[i] = light;
  }
}

void group_area_lights(Scene& scene) {
  auto animation = scene.animation ? std::make_shared<SceneAnimation>(*scene.animation)
                                   : std::make_shared<SceneAnimation>();
  for (const DynamicPart& part : animation->parts)
    if (part.node < 0) return;  // grouped already
  std::vector<bool> moving(scene.triangles.size(), false);
  for (const DynamicPart& part : animation->parts)
    for (uint32_t t : part.triangles) moving[t] = true;
  DynamicPart group;
  for (uint32_t t = 0; t < scene.triangles.size(); ++t)
    if (!moving[t] && scene.materials[scene.triangle_material[t]].is_emissive()) group.triangles.push_back(t);
  if (animation->rest_lights.empty()) {
    animation->rest_lights = scene.lights;
    animation->light_node.assign(scene.lights.size(), -1);
  }
  if (!group.triangles.empty()) {
    // Each grouped triangle gets vertices of its own, appended: the other
    // triangles keep theirs, so moving the group moves nothing else.
    for (uint32_t t : group.triangles) {
      glm::uvec3 corners = scene.triangles[t];
      for (int k = 0; k < 3; ++k) {
        const uint32_t v = corners[k];
        corners[k] = uint32_t(scene.positions.size());
        scene.positions.push_back(scene.positions[v]);
        if (!scene.normals.empty()) scene.normals.push_back(scene.normals[v]);
        if (!scene.uvs.empty()) scene.uvs.push_back(scene.uvs[v]);
        group.vertices.push_back(corners[k]);
        group.object_positions.push_back(scene.positions[v]);
      }
      scene.triangles[t] = corners;
      group.rest_triangles.push_back(corners);
    }
    animation->parts.push_back(std::move(group));
  }
  if (animation->parts.empty() && animation->rest_lights.empty()) return;
  scene.animation = std::move(animation);
}

void animate_triangles(Scene& scene, uint32_t first_triangle, std::vector<AnimationChannel> channels) {
  auto animation = scene.animation ? std::make_shared<SceneAnimation>(*scene.animation)
                                   : std::make_shared<SceneAnimation>();
  if (animation->rest_lights.empty()) {
    animation->rest_lights = scene.lights;
    animation->light_node.assign(scene.lights.size(), -1);
  }
  const uint32_t node = uint32_t(animation->nodes.size());
  animation->nodes.push_back({"node " + std::to_string(node), -1, glm::dmat4(1.0), NodeTrs{}, std::nullopt});
  DynamicPart part;
  part.node = int(node);
  std::vector<bool> seen(scene.positions.size(), false);
  for (uint32_t t = first_triangle; t < scene.triangles.size(); ++t) {
    part.triangles.push_back(t);
    part.rest_triangles.push_back(scene.triangles[t]);
    for (int k = 0; k < 3; ++k) {
      const uint32_t v = scene.triangles[t][k];
      if (seen[v]) continue;
      seen[v] = true;
      part.vertices.push_back(v);
      part.object_positions.push_back(scene.positions[v]);
      if (!scene.normals.empty()) part.object_normals.push_back(scene.normals[v]);
    }
  }
  for (AnimationChannel& channel : channels) {
    channel.node = node;
    animation->duration = std::max(animation->duration, channel.times.back());
    animation->channels.push_back(std::move(channel));
  }
  animation->parts.push_back(std::move(part));
  scene.animation = std::move(animation);
}

double scene_time(double start, double step, uint64_t index, bool loop, double duration) {
  const double time = start + step * double(index);
  if (!loop || !(duration > 0.0)) return time;
  const double wrapped = std::fmod(time, duration);
  return wrapped < 0.0 ? wrapped + duration : wrapped;
}

}  // namespace igi
