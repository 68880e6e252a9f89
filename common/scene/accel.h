#pragma once
// Embree BVH over a Scene. Built once, then read-only: every query method is
// thread-safe. Triangles that need per-hit decisions (alpha masks, single-sided
// faces) live in a second geometry with an intersection filter, so the common
// opaque double-sided case runs with no callback at all.
//
// Threads that trace must call enable_flush_to_zero() first (Embree asks for
// FTZ/DAZ; the renderer's thread pool does it).
//
// Single-sided faces: glTF's doubleSided is about display, so only camera
// rays (and the mirror and glass chains they pass through) skip the back of a
// single-sided face. Shadow rays, light paths and diffuse bounces find it
// opaque like any other face, or light would leak through the walls of
// interiors, which exporters write single-sided. A ray says which it is by
// its mask (Embree passes it to the filter): kCameraRayMask culls,
// kOpaqueRayMask (all bits, the default) does not.
#include <cstdint>
#include <vector>

#include <embree3/rtcore.h>
#include <glm/glm.hpp>

#include "scene/scene.h"

namespace igi {

inline constexpr unsigned kOpaqueRayMask = ~0u;
inline constexpr unsigned kCameraRayMask = ~0u >> 1;  // bit 31 clear: cull single-sided back faces

struct Ray {
  glm::vec3 origin;
  glm::vec3 direction;
  float tnear = 0.0f;
  float tfar = 1e30f;
  unsigned mask = kOpaqueRayMask;
};

struct Hit {
  float t = 0.0f;
  uint32_t triangle = 0;  // index into Scene::triangles
  glm::vec2 barycentric{0.0f};  // Embree's (u, v): p = (1-u-v) p0 + u p1 + v p2
};

void enable_flush_to_zero();

class Accel {
 public:
  explicit Accel(const Scene& scene);
  ~Accel();
  Accel(const Accel&) = delete;
  Accel& operator=(const Accel&) = delete;

  bool intersect(const Ray& ray, Hit& hit) const;
  bool occluded(const Ray& ray) const;

  RTCScene handle() const { return scene_handle_; }
  const Scene& scene() const { return scene_; }
  // Maps an Embree (geomID, primID) pair back to Scene::triangles.
  uint32_t triangle_index(unsigned geom_id, unsigned prim_id) const {
    return geometry_triangles_[geom_id][prim_id];
  }
  // Whether the filtered triangle is transparent at this hit: its alpha mask,
  // or, for a camera ray, the back of a single-sided face seen from `direction`.
  bool rejects(uint32_t triangle, glm::vec2 barycentric, glm::vec3 direction, bool camera_ray) const;

 private:
  void add_geometry(const std::vector<uint32_t>& triangles, bool filtered);

  const Scene& scene_;
  RTCDevice device_ = nullptr;
  RTCScene scene_handle_ = nullptr;
  std::vector<std::vector<uint32_t>> geometry_triangles_;
};

}  // namespace igi
