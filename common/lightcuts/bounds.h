#pragma once
// Upper bounds on the terms of a light's contribution over a set of
// directions, for the error bounds of Lightcuts (Walter et al. 2005, sec. 4).
//
// Every bound here holds for ALL vectors v of an axis-aligned box B that
// holds the vectors from a receiver to a light (for one receiver x and a
// cluster box L: B = L - x; for a cluster of receivers G: B = L - G, the
// Minkowski difference). Bounds may be loose, never low: a cut refines a
// cluster only while its bound says it might matter.
#include <algorithm>
#include <cmath>

#include <glm/glm.hpp>

#include "sampling/warp.h"

namespace igi::lightcuts {

struct Box {
  glm::vec3 lo{INFINITY}, hi{-INFINITY};
  void extend(glm::vec3 p) { lo = glm::min(lo, p); hi = glm::max(hi, p); }
  void extend(const Box& b) { lo = glm::min(lo, b.lo); hi = glm::max(hi, b.hi); }
  float diagonal() const { return glm::length(hi - lo); }
};

// {l - g : l in light, g in gather}.
inline Box difference(const Box& light, const Box& gather) { return {light.lo - gather.hi, light.hi - gather.lo}; }
inline Box negated(const Box& b) { return {-b.hi, -b.lo}; }

// Squared distance from the origin to the box (0 when it holds the origin).
inline float distance2(const Box& b) {
  const glm::vec3 d = glm::max(glm::max(b.lo, -b.hi), glm::vec3(0.0f));
  return glm::dot(d, d);
}

// The frame (t, b, n) around a unit axis n, with the absolute values of its
// vectors: what max_cos asks of a frame at every cluster, computed once.
struct BoundFrame : Onb {
  glm::vec3 abs_t, abs_b, abs_n;
  explicit BoundFrame(glm::vec3 axis) : Onb(axis), abs_t(glm::abs(t)), abs_b(glm::abs(b)), abs_n(glm::abs(n)) {}
};

// max over v in B of cos(v, axis), axis a unit vector (given as the frame
// around it, so callers can keep frames they use often); 1 when B holds the
// origin. The box is taken into the axis' frame (z = axis) as the box around
// its rotated corners; there, for fixed (x, y), z / |v| grows with z, so
//   cos <= z_max / sqrt(min x^2 + min y^2 + z_max^2)   (z_max > 0)
//   cos <= z_max / sqrt(max x^2 + max y^2 + z_max^2)   (z_max <= 0).
inline float max_cos(const BoundFrame& f, const Box& b) {
  const glm::vec3 c = 0.5f * (b.lo + b.hi), e = 0.5f * (b.hi - b.lo);
  const glm::vec3 lc = f.to_local(c);
  const glm::vec3 le(glm::dot(f.abs_t, e), glm::dot(f.abs_b, e), glm::dot(f.abs_n, e));
  const glm::vec3 lo = lc - le, hi = lc + le;
  // Written without branches (selects): which case holds depends on the
  // cluster, and mispredicted branches cost a cut more than both cases do.
  const float min_x = std::max(std::max(lo.x, -hi.x), 0.0f), min_y = std::max(std::max(lo.y, -hi.y), 0.0f);
  const float max_x = std::max(lo.x * lo.x, hi.x * hi.x), max_y = std::max(lo.y * lo.y, hi.y * hi.y);
  const float z = hi.z;
  const bool above = z > 0.0f;
  const float xy = above ? min_x * min_x + min_y * min_y : max_x + max_y;
  const float r2 = xy + z * z;
  const float cos = z / std::sqrt(r2);
  // Above: 1 when B meets the axis (xy = 0); below: 1 only when B holds the origin (r2 = 0).
  return above ? (xy > 0.0f ? std::min(1.0f, cos) : 1.0f) : (r2 > 0.0f ? cos : 1.0f);
}
inline float max_cos(glm::vec3 axis, const Box& b) { return max_cos(BoundFrame(axis), b); }

// A cone of unit directions: every member within half-angle theta of axis.
struct Cone {
  BoundFrame frame{glm::vec3(0.0f, 0.0f, 1.0f)};  // around the axis, frame.n
  float cos_theta = 1.0f, sin_theta = 0.0f;  // theta >= pi: cos -1, sin 0
  glm::vec3 axis() const { return frame.n; }
};

// max over v in B and n in the cone of cos(v, n), clamped at 0: the angle
// between v and the axis, less theta.
inline float max_cos(const Cone& cone, const Box& b) {
  const float c = max_cos(cone.frame, b);
  const float s = std::sqrt(std::max(0.0f, 1.0f - c * c));
  return c >= cone.cos_theta ? 1.0f : std::max(0.0f, std::min(1.0f, c * cone.cos_theta + s * cone.sin_theta));
}

// Whether some v in B lies within angle (theta + spread) of the axis, given
// cos_reach = cos(theta + spread) (-1 when that reaches pi).
inline bool within_reach(const BoundFrame& axis, float cos_reach, const Box& b) {
  return cos_reach <= -1.0f || max_cos(axis, b) >= cos_reach;
}

// The largest Fresnel factor of a metallic-roughness GGX lobe (material/metallic_roughness.h):
// (1 - metallic) w + metallic, w the coat's weight (specularFactor).
inline float specular_bound(float weight, float metallic) { return (1.0f - metallic) * weight + metallic; }

// GGX normal distribution at cos(h, n) = c, alpha the roughness.
inline float ggx_distribution(float c, float alpha) {
  const float a2 = alpha * alpha;
  const float d = c * c * (a2 - 1.0f) + 1.0f;
  return a2 / (kPi * d * d);
}

}  // namespace igi::lightcuts
