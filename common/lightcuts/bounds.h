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

// max over v in B of cos(v, axis), axis a unit vector (given as the frame
// around it, so callers can keep frames they use often); 1 when B holds the
// origin. The box is taken into the axis' frame (z = axis) as the box around
// its rotated corners; there, for fixed (x, y), z / |v| grows with z, so
//   cos <= z_max / sqrt(min x^2 + min y^2 + z_max^2)   (z_max > 0)
//   cos <= z_max / sqrt(max x^2 + max y^2 + z_max^2)   (z_max <= 0).
inline float max_cos(const Onb& f, const Box& b) {
  const glm::vec3 c = 0.5f * (b.lo + b.hi), e = 0.5f * (b.hi - b.lo);
  const glm::vec3 lc = f.to_local(c);
  const glm::vec3 le(glm::dot(glm::abs(f.t), e), glm::dot(glm::abs(f.b), e), glm::dot(glm::abs(f.n), e));
  const glm::vec3 lo = lc - le, hi = lc + le;
  auto min_sq = [](float a, float b) { return a > 0.0f ? a * a : b < 0.0f ? b * b : 0.0f; };
  auto max_sq = [](float a, float b) { return std::max(a * a, b * b); };
  const float z = hi.z;
  if (z > 0.0f) {
    const float xy = min_sq(lo.x, hi.x) + min_sq(lo.y, hi.y);
    return xy > 0.0f ? std::min(1.0f, z / std::sqrt(xy + z * z)) : 1.0f;
  }
  const float xy = max_sq(lo.x, hi.x) + max_sq(lo.y, hi.y);
  return xy + z * z > 0.0f ? z / std::sqrt(xy + z * z) : 1.0f;
}
inline float max_cos(glm::vec3 axis, const Box& b) { return max_cos(Onb(axis), b); }

// A cone of unit directions: every member within half-angle theta of axis.
struct Cone {
  Onb frame{glm::vec3(0.0f, 0.0f, 1.0f)};  // around the axis, frame.n
  float cos_theta = 1.0f, sin_theta = 0.0f;  // theta >= pi: cos -1, sin 0
  glm::vec3 axis() const { return frame.n; }
};

// max over v in B and n in the cone of cos(v, n), clamped at 0: the angle
// between v and the axis, less theta.
inline float max_cos(const Cone& cone, const Box& b) {
  const float c = max_cos(cone.frame, b);
  if (c >= cone.cos_theta) return 1.0f;
  const float s = std::sqrt(std::max(0.0f, 1.0f - c * c));
  return std::max(0.0f, std::min(1.0f, c * cone.cos_theta + s * cone.sin_theta));
}

// Whether some v in B lies within angle (theta + spread) of the axis, given
// cos_reach = cos(theta + spread) (-1 when that reaches pi).
inline bool within_reach(const Onb& axis, float cos_reach, const Box& b) {
  return cos_reach <= -1.0f || max_cos(axis, b) >= cos_reach;
}

// GGX normal distribution at cos(h, n) = c, alpha the roughness.
inline float ggx_distribution(float c, float alpha) {
  const float a2 = alpha * alpha;
  const float d = c * c * (a2 - 1.0f) + 1.0f;
  return a2 / (kPi * d * d);
}

}  // namespace igi::lightcuts
