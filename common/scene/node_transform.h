#pragma once
// A glTF node's local transform and what a world matrix does to points and
// axes: one place for the loader (rest pose) and for posing an animated scene
// at a time, so both round identically and a posed frame equals the same
// pose loaded from a static file, bit for bit.
#include <cmath>
#include <optional>

#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>

#include "scene/camera.h"

namespace igi {

// Translation, rotation (unit quaternion, glm's (w, x, y, z)) and scale;
// the identity by default.
struct NodeTrs {
  glm::dvec3 translation{0.0};
  glm::dquat rotation{1.0, 0.0, 0.0, 0.0};
  glm::dvec3 scale{1.0};
};

// translation * rotation * scale, column vectors (glTF's order). The
// rotation is normalised here: key frames and files need not be exactly unit.
inline glm::dmat4 trs_matrix(const NodeTrs& trs) {
  glm::dmat4 m = glm::translate(glm::dmat4(1.0), trs.translation);
  m *= glm::mat4_cast(glm::normalize(trs.rotation));
  return glm::scale(m, trs.scale);
}

inline glm::vec3 world_point(const glm::dmat4& world, glm::dvec3 local) {
  return glm::vec3(world * glm::dvec4(local, 1.0));
}

// Where a local axis points in world space; zero-length if the transform
// collapses it.
inline glm::dvec3 world_axis(const glm::dmat4& world, glm::dvec3 local) {
  const glm::dvec3 axis = glm::dmat3(world) * local;
  const double length = glm::length(axis);
  return length > 0.0 && std::isfinite(length) ? axis / length : glm::dvec3(0.0);
}

// A glTF perspective camera at a node: it looks down the node's -z with its
// +y up, re-orthogonalised (a sheared or non-uniformly scaled parent may tilt
// up). None when the transform collapses the view.
inline std::optional<Camera> camera_at_node(const glm::dmat4& world, double yfov) {
  const glm::dvec3 forward = world_axis(world, glm::dvec3(0.0, 0.0, -1.0));
  const glm::dvec3 up = world_axis(world, glm::dvec3(0.0, 1.0, 0.0));
  const glm::dvec3 true_up = up - glm::dot(up, forward) * forward;
  if (forward == glm::dvec3(0.0) || !(glm::length(true_up) >= 1e-9)) return std::nullopt;
  Camera out;
  out.position = world_point(world, glm::dvec3(0.0));
  out.forward = glm::vec3(forward);
  out.up = glm::vec3(glm::normalize(true_up));
  out.vfov = float(yfov);
  return out;
}

}  // namespace igi
