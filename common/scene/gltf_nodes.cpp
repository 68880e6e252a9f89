#include "scene/gltf_nodes.h"

#include "scene/node_transform.h"

#include <cmath>
#include <numbers>
#include <optional>
#include <utility>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <tiny_gltf.h>

namespace igi {
namespace {

NodeTrs node_trs(const tinygltf::Node& node) {
  NodeTrs trs;
  if (node.translation.size() == 3) trs.translation = glm::make_vec3(node.translation.data());
  const std::vector<double>& q = node.rotation;  // glTF order: x, y, z, w
  if (q.size() == 4) trs.rotation = glm::dquat(q[3], q[0], q[1], q[2]);
  if (node.scale.size() == 3) trs.scale = glm::make_vec3(node.scale.data());
  return trs;
}

// Column-major matrix if given, else translation * rotation * scale.
glm::dmat4 local_transform(const tinygltf::Node& node) {
  if (node.matrix.size() == 16) return glm::make_mat4(node.matrix.data());
  return trs_matrix(node_trs(node));
}

// False for NaN too.
bool in_range(glm::vec3 p) {
  return glm::all(glm::lessThanEqual(glm::abs(p), glm::vec3(float(kMaxCoordinate))));
}

bool finite(glm::vec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

std::string show(glm::vec3 p) {
  return "(" + std::to_string(p.x) + ", " + std::to_string(p.y) + ", " + std::to_string(p.z) + ")";
}

std::vector<int> root_nodes(const tinygltf::Model& model, std::string& scene_name,
                            const GltfDiagnostics& diag) {
  if (!model.scenes.empty()) {
    const int scene = model.defaultScene >= 0 ? model.defaultScene : 0;
    if (size_t(scene) >= model.scenes.size())
      diag.fail("scene", "default scene " + std::to_string(scene) + " does not exist (the file has " +
                             std::to_string(model.scenes.size()) + ")");
    scene_name = model.scenes[size_t(scene)].name;
    return model.scenes[size_t(scene)].nodes;
  }
  std::vector<bool> is_child(model.nodes.size(), false);
  for (const tinygltf::Node& node : model.nodes)
    for (int child : node.children)
      if (child >= 0 && size_t(child) < model.nodes.size()) is_child[size_t(child)] = true;
  std::vector<int> roots;
  for (size_t i = 0; i < model.nodes.size(); ++i)
    if (!is_child[i]) roots.push_back(int(i));
  return roots;
}

class NodeWalker {
 public:
  NodeWalker(const tinygltf::Model& model, const std::vector<bool>& animated, double light_scale,
             GltfDiagnostics& diag)
      : model_(model), animated_(animated), light_scale_(light_scale), diag_(diag), visited_(model.nodes.size(), false) {
    out_.pose_node_of.assign(model.nodes.size(), -1);
  }

  FlattenedNodes walk();

 private:
  struct Pending {
    int node;
    int parent;  // -1 for a scene root
    glm::dmat4 parent_world;
    int pose_parent = -1;  // the moving node above, if any
  };

  void visit(const Pending& pending, std::vector<Pending>& stack);
  int add_pose_node(const Pending& pending, const tinygltf::Node& node, const std::string& name);
  void add_light(const tinygltf::Node& node, const std::string& name, const glm::dmat4& world, int pose_node);
  std::optional<PunctualLight> to_punctual(const tinygltf::Light& light, size_t index);
  void add_camera(const tinygltf::Node& node, const std::string& name, const glm::dmat4& world, int pose_node);

  const tinygltf::Model& model_;
  const std::vector<bool>& animated_;
  double light_scale_;  // file units into W/sr and W/m^2
  GltfDiagnostics& diag_;
  std::vector<bool> visited_;
  FlattenedNodes out_;
};

FlattenedNodes NodeWalker::walk() {
  std::vector<Pending> stack;
  const std::vector<int> roots = root_nodes(model_, out_.scene_name, diag_);
  for (auto it = roots.rbegin(); it != roots.rend(); ++it) stack.push_back({*it, -1, glm::dmat4(1.0)});
  while (!stack.empty()) {
    const Pending pending = stack.back();
    stack.pop_back();
    visit(pending, stack);
  }
  return std::move(out_);
}

// An explicit stack, not recursion: a deep chain of nodes cannot overflow it.
void NodeWalker::visit(const Pending& pending, std::vector<Pending>& stack) {
  const std::string referrer =
      pending.parent < 0 ? "scene nodes" : gltf_element("nodes", size_t(pending.parent)) + ".children";
  if (pending.node < 0 || size_t(pending.node) >= model_.nodes.size())
    diag_.fail(referrer, "node " + std::to_string(pending.node) + " does not exist (the file has " +
                             std::to_string(model_.nodes.size()) + ")");
  const std::string name = gltf_element("nodes", size_t(pending.node));
  if (visited_[size_t(pending.node)])
    diag_.fail(name, "reached twice from " + referrer + ": a glTF node has at most one parent and no cycles");
  visited_[size_t(pending.node)] = true;

  const tinygltf::Node& node = model_.nodes[size_t(pending.node)];
  const glm::dmat4 world = pending.parent_world * local_transform(node);
  const int pose_node = add_pose_node(pending, node, name);
  if (node.mesh >= 0) {
    if (size_t(node.mesh) >= model_.meshes.size())
      diag_.fail(name, "mesh " + std::to_string(node.mesh) + " does not exist (the file has " +
                           std::to_string(model_.meshes.size()) + ")");
    out_.instances.push_back({node.mesh, world, pose_node});
  }
  if (node.camera >= 0) add_camera(node, name, world, pose_node);
  add_light(node, name, world, pose_node);
  for (auto it = node.children.rbegin(); it != node.children.rend(); ++it)
    stack.push_back({*it, pending.node, world, pose_node});
}

// A node that moves (animated, or below an animated node) is remembered
// with what posing it needs; -1 for a static node.
int NodeWalker::add_pose_node(const Pending& pending, const tinygltf::Node& node, const std::string& name) {
  const bool animated = size_t(pending.node) < animated_.size() && animated_[size_t(pending.node)];
  if (!animated && pending.pose_parent < 0) return -1;
  PoseNode pose;
  pose.name = name;
  pose.parent = pending.pose_parent;
  if (pending.pose_parent < 0) pose.parent_world = pending.parent_world;
  if (node.matrix.size() == 16) {
    if (animated) diag_.fail(name, "animated, but has a matrix: glTF animates only translation, rotation and scale");
    pose.matrix = glm::make_mat4(node.matrix.data());
  } else {
    pose.rest = node_trs(node);
  }
  out_.pose_node_of[size_t(pending.node)] = int(out_.pose_nodes.size());
  out_.pose_nodes.push_back(std::move(pose));
  return int(out_.pose_nodes.size()) - 1;
}

void NodeWalker::add_light(const tinygltf::Node& node, const std::string& name, const glm::dmat4& world,
                           int pose_node) {
  auto ext = node.extensions.find("KHR_lights_punctual");
  if (ext == node.extensions.end()) return;
  const tinygltf::Value& reference = ext->second;
  const int index = reference.IsObject() && reference.Has("light") && reference.Get("light").IsNumber()
                        ? reference.Get("light").GetNumberAsInt() : -1;
  if (index < 0 || size_t(index) >= model_.lights.size())
    diag_.fail(name + ".extensions.KHR_lights_punctual", "expected 'light' to index one of the file's " +
                                                            std::to_string(model_.lights.size()) + " lights");
  std::optional<PunctualLight> light = to_punctual(model_.lights[size_t(index)], size_t(index));
  if (!light) return;
  light->position = world_point(world, glm::dvec3(0.0));
  if (!in_range(light->position))
    diag_.fail(name, "the transform puts light " + std::to_string(index) + " at " + show(light->position) +
                         ", expected coordinates within +-1e15 m");
  light->direction = glm::vec3(world_axis(world, glm::dvec3(0.0, 0.0, -1.0)));
  if (light->type != LightType::Point && light->direction == glm::vec3(0.0f))
    diag_.fail(name, "the transform collapses the direction of light " + std::to_string(index));
  out_.lights.push_back(*light);
  out_.light_pose_node.push_back(pose_node);
}

// Type, intensity and cones; the node gives position and direction.
std::optional<PunctualLight> NodeWalker::to_punctual(const tinygltf::Light& light, size_t index) {
  const std::string name = gltf_element("lights", index);
  PunctualLight out;
  const std::vector<double>& c = light.color;
  const glm::vec3 color = c.size() >= 3 ? glm::vec3(c[0], c[1], c[2]) : glm::vec3(1.0f);
  if (glm::any(glm::lessThan(color, glm::vec3(0.0f))) || !(light.intensity >= 0.0))
    diag_.fail(name, "color and intensity must not be negative");
  out.intensity = glm::vec3(glm::dvec3(color) * (light.intensity * light_scale_));  // radiometric: W/sr or W/m^2
  if (!finite(out.intensity))
    diag_.fail(name, "color x intensity is not finite, expected finite radiometric intensity");
  if (light.type == "point") {
    out.type = LightType::Point;
  } else if (light.type == "spot") {
    out.type = LightType::Spot;
    out.inner_cone = float(light.spot.innerConeAngle);
    out.outer_cone = float(light.spot.outerConeAngle);
    if (!(0.0f <= out.inner_cone && out.inner_cone < out.outer_cone && out.outer_cone <= std::numbers::pi / 2 + 1e-6))
      diag_.fail(name, "spot cone angles inner " + std::to_string(out.inner_cone) + ", outer " +
                           std::to_string(out.outer_cone) + ": expected 0 <= inner < outer <= pi/2");
  } else if (light.type == "directional") {
    out.type = LightType::Directional;
  } else {
    diag_.warn_once("light type " + light.type,
                    "light type '" + light.type + "' (" + name + ") unknown: light ignored");
    return std::nullopt;
  }
  if (light.range > 0.0)
    diag_.warn_once("light range",
                    "light range ignored: lights fall off with the inverse square law, without cut-off");
  return out;
}

void NodeWalker::add_camera(const tinygltf::Node& node, const std::string& name, const glm::dmat4& world,
                            int pose_node) {
  if (size_t(node.camera) >= model_.cameras.size())
    diag_.fail(name, "camera " + std::to_string(node.camera) + " does not exist (the file has " +
                         std::to_string(model_.cameras.size()) + ")");
  const std::string camera_name = gltf_element("cameras", size_t(node.camera));
  const tinygltf::Camera& camera = model_.cameras[size_t(node.camera)];
  if (camera.type != "perspective") {
    diag_.warn_once("camera " + camera.type, camera.type + " camera (" + camera_name +
                                                 ") ignored: only perspective cameras are supported");
    return;
  }
  if (out_.camera) {
    diag_.warn_once("extra cameras",
                    "cameras after the first perspective camera ignored (first ignored on " + name + ")");
    return;
  }
  if (camera.perspective.aspectRatio > 0.0)
    diag_.warn_once("aspectRatio", "camera aspectRatio ignored: the image's width and height set it");
  const double yfov = camera.perspective.yfov;
  if (!(yfov > 0.0 && yfov < std::numbers::pi))
    diag_.fail(camera_name, "yfov " + std::to_string(yfov) + ", expected in (0, pi)");
  const std::optional<Camera> out = camera_at_node(world, yfov);
  if (!out) diag_.fail(name, "the transform collapses the view of " + camera_name);
  if (!in_range(out->position))
    diag_.fail(name, "the transform puts " + camera_name + " at " + show(out->position) +
                         ", expected coordinates within +-1e15 m");
  out_.camera = out;
  out_.camera_pose_node = pose_node;
}

}  // namespace

FlattenedNodes flatten_nodes(const tinygltf::Model& model, const std::vector<bool>& animated, double light_scale,
                             GltfDiagnostics& diag) {
  return NodeWalker(model, animated, light_scale, diag).walk();
}

}  // namespace igi
