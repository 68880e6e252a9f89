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

// A ray as Embree takes it: alone, or as lane k of a 16-wide packet (flags
// and time 0: no motion blur).
inline void set_rtc_ray(RTCRay& r, const Ray& ray) {
  r.org_x = ray.origin.x; r.org_y = ray.origin.y; r.org_z = ray.origin.z;
  r.dir_x = ray.direction.x; r.dir_y = ray.direction.y; r.dir_z = ray.direction.z;
  r.tnear = ray.tnear; r.tfar = ray.tfar;
  r.mask = ray.mask; r.flags = 0; r.time = 0.0f;
}
inline void set_rtc_lane(RTCRay16& r, int k, const Ray& ray) {
  r.org_x[k] = ray.origin.x; r.org_y[k] = ray.origin.y; r.org_z[k] = ray.origin.z;
  r.dir_x[k] = ray.direction.x; r.dir_y[k] = ray.direction.y; r.dir_z[k] = ray.direction.z;
  r.tnear[k] = ray.tnear; r.tfar[k] = ray.tfar;
  r.mask[k] = ray.mask; r.flags[k] = 0; r.time[k] = 0.0f;
}

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
