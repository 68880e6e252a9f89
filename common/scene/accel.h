#pragma once
// Embree BVH over a Scene, in two levels: the static triangles in one
// instanced scene, built once at high quality and never rebuilt, and each
// moving part of scene/animation.h (an animated node, the light group) in an
// instanced scene of its own that update() rebuilds from the posed vertices.
// A scene where nothing moves is traced single-level, with no instance.
// Packets are traced incoherent (Embree's default): igi's packets replayed
// with the coherent flag ran at 0.68x on cornell-blob (igi-bench prints it).
// Every instance has the identity transform: parts are posed in world space,
// so a posed scene traces exactly as the same scene loaded static, and hits
// and normals need no instance transform. Between update() calls the
// structure is read-only: every query method is thread-safe.
//
// Triangles that need per-hit decisions (alpha masks, single-sided faces)
// live in a second geometry with an intersection filter, so the common opaque
// double-sided case runs with no callback at all.
//
// Threads that trace must call enable_flush_to_zero() first (Embree asks for
// FTZ/DAZ; the renderer's thread pool does it).
//
// Single-sided faces: glTF's doubleSided is about display, so only camera
// rays (and the mirror and glass chains they pass through) skip the back of a
// single-sided face, and never of glass (Material::culls_back_faces): a ray
// that refracted into a single-sided glass sphere must refract out of it. Shadow rays, light paths and diffuse bounces find it
// opaque like any other face, or light would leak through the walls of
// interiors, which exporters write single-sided. A ray says which it is by
// its mask (Embree passes it to the filter): kCameraRayMask culls,
// kOpaqueRayMask (all bits, the default) does not.
#include <atomic>
#include <cstdint>
#include <span>
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

// Embree's memory for one Accel, counted by its device; an allocation past a
// non-zero limit fails (Embree's RTC_ERROR_OUT_OF_MEMORY, then our exception).
struct EmbreeMemoryBudget {
  std::atomic<int64_t> used{0};
  int64_t limit = 0;  // bytes; 0: no limit
};

class Accel {
 public:
  // Throws std::runtime_error naming what Embree could not do (out of memory,
  // a CPU without the pinned ISA); memory_limit bounds Embree's memory (0: none).
  explicit Accel(const Scene& scene, size_t memory_limit = 0);
  ~Accel();
  Accel(const Accel&) = delete;
  Accel& operator=(const Accel&) = delete;

  // Re-reads the moving parts' vertices from the scene (after pose_scene)
  // and rebuilds their BVHs and the top level. Not while tracing.
  void update();

  bool intersect(const Ray& ray, Hit& hit) const;
  // Shadow rays: whatever their mask, they find single-sided faces opaque
  // from both sides (only alpha masks let them through).
  bool occluded(const Ray& ray) const;
  // Up to 16 shadow rays as one Embree packet (coherent): occluded[i] for
  // rays[i]. Embree may answer a ray that grazes an edge differently with
  // other rays beside it, so a caller keeps which rays share a packet a pure
  // function of what it renders, never of the tiling (methods/shadow_batch.h
  // traces ray by ray for that reason).
  void occluded16(std::span<const Ray> rays, std::span<bool> occluded) const;

  // The scene's length scale, measured as built and again by each update()
  // (so a posed scene has the value of the same pose loaded static): the
  // mean length of chords through its free space, from 4,096 cosine-
  // distributed rays leaving points spread over the surfaces by area, half
  // from each side, counting the rays that hit (4 V / S for a closed room,
  // Cauchy's formula; about a room in a building of many). Deterministic.
  // The scene's diagonal when no ray hits. The VPL clamp is relative to it
  // (core/clamp.h).
  float mean_chord() const { return mean_chord_; }

  RTCScene handle() const { return top_; }
  const Scene& scene() const { return scene_; }
  // Maps an Embree hit (instID[0], geomID, primID) back to Scene::triangles.
  uint32_t triangle_index(unsigned inst_id, unsigned geom_id, unsigned prim_id) const {
    const Group& group = groups_[inst_id == RTC_INVALID_GEOMETRY_ID ? 0 : inst_id];
    return group.geometries[geom_id].triangles[prim_id];
  }
  // Whether the filtered triangle is transparent at this hit: its alpha mask,
  // or, for a camera ray, the back of a single-sided face seen from `direction`.
  bool rejects(uint32_t triangle, glm::vec2 barycentric, glm::vec3 direction, bool camera_ray) const;

 private:
  struct Geometry {
    RTCGeometry handle = nullptr;
    std::vector<uint32_t> triangles;  // Scene::triangles of each primitive
    float* vertices = nullptr;        // Embree's buffer, three unshared vertices per triangle
  };
  // One instanced scene: the static triangles, or one moving node's.
  struct Group {
    RTCScene scene = nullptr;
    RTCGeometry instance = nullptr;
    std::vector<Geometry> geometries;  // in Filters order
  };
  // Which hits a geometry's filter callbacks judge: none (double-sided and
  // opaque), camera rays' (single-sided: they skip back faces; every other
  // ray, shadow rays included, finds both sides), or every ray's (alpha masks).
  enum class Filters { None, CameraHits, AllHits };
  struct Empty {};
  Accel(const Scene& scene, size_t memory_limit, Empty);  // no Embree object yet
  void add_group(const std::vector<uint32_t>& triangles, RTCBuildQuality quality);
  void build_triangles(Geometry& g, const std::vector<uint32_t>& triangles, bool moving, Filters filters);
  void write_vertices(const Geometry& geometry) const;
  void measure_areas(const std::vector<uint32_t>& changed);  // all of them on the first call
  uint32_t sample_by_area(float u) const;
  float measure_mean_chord() const;

  const Scene& scene_;
  EmbreeMemoryBudget budget_;  // before the device, which reports to it
  RTCDevice device_ = nullptr;
  RTCScene top_ = nullptr;
  std::vector<Group> groups_;  // index = instance id; 0 is the static group
  float mean_chord_ = 1.0f;
  std::vector<float> areas_;        // per Scene::triangles, as posed
  std::vector<double> area_sums_;   // running sums of areas_ (negative counted as 0)
  std::vector<uint32_t> moving_triangles_;  // of groups_[1...], whose areas update() measures again
};

}  // namespace igi
