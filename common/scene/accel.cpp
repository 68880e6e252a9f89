#include "scene/accel.h"

#include <algorithm>
#include <array>
#include <cstdio>
#include <map>
#include <stdexcept>
#include <string>
#include <sys/types.h>

#include <pmmintrin.h>
#include <xmmintrin.h>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "sampling/sobol.h"
#include "sampling/warp.h"
#include "scene/animation.h"
#include "scene/triangle.h"

namespace igi {

void enable_flush_to_zero() {
  _MM_SET_FLUSH_ZERO_MODE(_MM_FLUSH_ZERO_ON);
  _MM_SET_DENORMALS_ZERO_MODE(_MM_DENORMALS_ZERO_ON);
}

// The triangles' areas (as Distribution1D weighs them) and their running sum,
// kept between updates: update() recomputes the moving triangles' and the sum
// from the first of them on, so a posed scene samples exactly what the same
// pose loaded static samples (the sums are the same additions in the same
// order) without touching the static millions.
void Accel::measure_areas(const std::vector<uint32_t>& changed) {
  size_t first = areas_.size();
  if (areas_.size() != scene_.triangles.size()) {
    areas_.resize(scene_.triangles.size());
    area_sums_.resize(scene_.triangles.size());
    for (size_t t = 0; t < areas_.size(); ++t) areas_[t] = glm::length(triangle_cross(scene_, uint32_t(t)));
    first = 0;
  } else {
    for (uint32_t t : changed) {
      areas_[t] = glm::length(triangle_cross(scene_, t));
      first = std::min(first, size_t(t));
    }
  }
  double sum = first > 0 ? area_sums_[first - 1] : 0.0;
  for (size_t t = first; t < areas_.size(); ++t) area_sums_[t] = sum += std::max(0.0f, areas_[t]);
}

// Distribution1D::sample over areas_, bit for bit: upper_bound over the
// normalised sums (divided as compared, not stored), zero-area triangles skipped.
uint32_t Accel::sample_by_area(float u) const {
  const double total = area_sums_.back();
  auto it = std::upper_bound(area_sums_.begin(), area_sums_.end(), double(u),
                             [total](double x, double sum) { return x < sum / total; });
  uint32_t i = uint32_t(std::min<size_t>(it - area_sums_.begin(), area_sums_.size() - 1));
  while (i > 0 && areas_[i] <= 0.0f) --i;
  while (i + 1 < areas_.size() && areas_[i] <= 0.0f) ++i;
  return i;
}

// Accel::mean_chord(): see the header.
float Accel::measure_mean_chord() const {
  const Scene& scene = scene_;
  const float diagonal = scene.bounds().empty() ? 1.0f : std::max(1e-6f, scene.bounds().diagonal());
  if (area_sums_.empty() || !(float(area_sums_.back()) > 0.0f)) return diagonal;
  constexpr uint32_t kRays = 4096, kSeed = 0x63686f72u;  // "chor"
  // Each ray's length (or none) in its own slot, on as many threads as TBB
  // has, then summed in ray order: the same sum however the rays were shared.
  std::array<float, kRays> lengths;
  tbb::parallel_for(tbb::blocked_range<uint32_t>(0, kRays, 256), [&](const tbb::blocked_range<uint32_t>& rays) {
    // Traced as the render threads trace (FTZ/DAZ on), whatever this thread's mode.
    const unsigned ftz = _MM_GET_FLUSH_ZERO_MODE(), daz = _MM_GET_DENORMALS_ZERO_MODE();
    enable_flush_to_zero();
    for (uint32_t i = rays.begin(); i < rays.end(); ++i) {
      SampleStream u(i, kSeed);
      const uint32_t t = sample_by_area(u.next_1d());
      const glm::vec2 b = uniform_triangle(u.next_2d());
      const glm::vec3 local = cosine_hemisphere(u.next_2d());
      const glm::uvec3& tri = scene.triangles[t];
      const glm::vec3 p0 = scene.positions[tri[0]], p1 = scene.positions[tri[1]], p2 = scene.positions[tri[2]];
      const glm::vec3 n = triangle_normal(p0, p1, p2) * (i % 2 ? -1.0f : 1.0f);
      const glm::vec3 p = (1.0f - b.x - b.y) * p0 + b.x * p1 + b.y * p2;
      const float scale = std::max(std::max(std::abs(p.x), std::abs(p.y)), std::abs(p.z));
      Hit hit;
      lengths[i] = intersect(Ray{p + (2e-5f * scale + 1e-7f) * n, Onb(n).to_world(local)}, hit) ? hit.t : -1.0f;
    }
    _MM_SET_FLUSH_ZERO_MODE(ftz);
    _MM_SET_DENORMALS_ZERO_MODE(daz);
  });
  double sum = 0.0;
  uint32_t hits = 0;
  for (float length : lengths)
    if (length >= 0.0f) sum += length, ++hits;
  return hits > 0 ? std::max(1e-6f, float(sum / hits)) : diagonal;
}

static void device_error(void*, RTCError code, const char* message) {
  std::fprintf(stderr, "embree error %d: %s\n", int(code), message ? message : "");
}

static const char* error_name(RTCError code) {
  switch (code) {
    case RTC_ERROR_NONE: return "no error";
    case RTC_ERROR_INVALID_ARGUMENT: return "invalid argument";
    case RTC_ERROR_INVALID_OPERATION: return "invalid operation";
    case RTC_ERROR_OUT_OF_MEMORY: return "out of memory";
    case RTC_ERROR_UNSUPPORTED_CPU: return "the CPU lacks the instructions asked for";
    case RTC_ERROR_CANCELLED: return "cancelled";
    default: return "unknown error";
  }
}

// Embree says a call failed through a null handle or the device's error code
// (read and cleared here): either ends the build with an error naming `what`.
static void check_embree(RTCDevice device, bool ok, const std::string& what) {
  const RTCError code = rtcGetDeviceError(device);
  if (ok && code == RTC_ERROR_NONE) return;
  const RTCError reported = code == RTC_ERROR_NONE ? RTC_ERROR_UNKNOWN : code;  // a null handle, no code
  throw std::runtime_error("embree: cannot " + what + ": " + error_name(reported));
}

// Counts what the device allocates and frees; refuses an allocation past the
// limit before it happens (Embree may call this from many threads at once).
static bool monitor_memory(void* user, ssize_t bytes, bool post) {
  auto& budget = *static_cast<EmbreeMemoryBudget*>(user);
  const int64_t used = budget.used.fetch_add(bytes) + bytes;
  if (bytes <= 0 || post || used <= budget.limit) return true;
  budget.used.fetch_sub(bytes);  // refused: the allocation will not happen
  return false;
}

// Embree picks its kernels by the CPU, and kernels of different widths round
// differently (AVX2 and up fuse multiply-adds; a wider BVH meets ties in
// another order): a cluster of mixed machines would trace different hits.
// Pinning one ISA (CMake's IGI_EMBREE_ISA, carried in the build id) makes
// every machine that has it trace alike, AVX-512 ones included; a machine
// without it gets this error instead of different pixels.
static RTCDevice new_device(EmbreeMemoryBudget& budget) {
  const std::string config = std::string("isa=") + IGI_EMBREE_ISA;
  RTCDevice device = rtcNewDevice(config.c_str());
  check_embree(nullptr, device != nullptr, "create a device with " + config + " (configure with "
               "-DIGI_EMBREE_ISA=sse4.2 for every machine of a cluster that lacks it)");
  rtcSetDeviceErrorFunction(device, device_error, nullptr);
  if (budget.limit > 0) rtcSetDeviceMemoryMonitorFunction(device, monitor_memory, &budget);
  return device;
}

// Whether Embree keeps lane i's candidate hit (Accel::rejects).
static void judge_hit(const RTCFilterFunctionNArguments* args, unsigned i) {
  const auto* accel = static_cast<const Accel*>(args->geometryUserPtr);
  unsigned prim = RTCHitN_primID(args->hit, args->N, i);
  unsigned geom = RTCHitN_geomID(args->hit, args->N, i);
  unsigned inst = RTCHitN_instID(args->hit, args->N, i, 0);
  glm::vec2 bary(RTCHitN_u(args->hit, args->N, i), RTCHitN_v(args->hit, args->N, i));
  glm::vec3 dir(RTCRayN_dir_x(args->ray, args->N, i), RTCRayN_dir_y(args->ray, args->N, i),
                RTCRayN_dir_z(args->ray, args->N, i));
  const bool camera_ray = RTCRayN_mask(args->ray, args->N, i) == kCameraRayMask;
  if (accel->rejects(accel->triangle_index(inst, geom, prim), bary, dir, camera_ray)) args->valid[i] = 0;
}

// Alpha masks: every ray, rtcIntersect* and rtcOccluded*, any packet width.
static void filter_hits(const RTCFilterFunctionNArguments* args) {
  for (unsigned i = 0; i < args->N; ++i)
    if (args->valid[i] == -1) judge_hit(args, i);
}

// Single-sided opaque faces turn away camera rays only (from their backs):
// other rays' hits stand without a look at the triangle.
static void filter_camera_hits(const RTCFilterFunctionNArguments* args) {
  for (unsigned i = 0; i < args->N; ++i)
    if (args->valid[i] == -1 && RTCRayN_mask(args->ray, args->N, i) == kCameraRayMask) judge_hit(args, i);
}

Accel::Accel(const Scene& scene, size_t memory_limit, Empty) : scene_(scene) { budget_.limit = int64_t(memory_limit); }

// Delegating: once the empty Accel exists, a throw from this body runs the
// destructor, which releases whatever Embree objects were made.
Accel::Accel(const Scene& scene, size_t memory_limit) : Accel(scene, memory_limit, Empty{}) {
  device_ = new_device(budget_);
  top_ = rtcNewScene(device_);
  check_embree(device_, top_ != nullptr, "create the top-level scene");

  // Which group each triangle belongs to: 0 static, then one per moving node
  // (the light group's node is -1), in the order the parts name them.
  std::vector<uint32_t> group_of(scene.triangles.size(), 0);
  std::map<int, uint32_t> group_of_node;
  if (scene.animation)
    for (const DynamicPart& part : scene.animation->parts) {
      const uint32_t group = group_of_node.emplace(part.node, uint32_t(1 + group_of_node.size())).first->second;
      for (uint32_t t : part.triangles) group_of[t] = group;
    }
  std::vector<std::vector<uint32_t>> triangles(1 + group_of_node.size());
  for (uint32_t t = 0; t < scene.triangles.size(); ++t) triangles[group_of[t]].push_back(t);
  add_group(triangles[0], RTC_BUILD_QUALITY_HIGH);
  for (size_t g = 1; g < triangles.size(); ++g) add_group(triangles[g], RTC_BUILD_QUALITY_LOW);
  if (groups_.size() == 1) {
    // Nothing moves: trace the static scene itself, no instance in between.
    rtcReleaseGeometry(groups_[0].instance);
    groups_[0].instance = nullptr;
    rtcReleaseScene(top_);
    top_ = groups_[0].scene;
    rtcRetainScene(top_);
  } else {
    rtcCommitScene(top_);
    check_embree(device_, true, "build the top-level BVH over " + std::to_string(groups_.size()) + " parts");
  }
  measure_areas({});
  mean_chord_ = measure_mean_chord();
}

// One triangle geometry of a group, committed: its vertices written, and the
// filter callbacks that `filters` names (alpha masks, single-sided faces). `g` is already the
// group's, so that a throw leaves its handle to the destructor.
void Accel::build_triangles(Geometry& g, const std::vector<uint32_t>& triangles, bool moving, Filters filters) {
  const std::string what = std::to_string(triangles.size()) + " triangles";
  g.triangles = triangles;
  g.handle = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
  check_embree(device_, g.handle != nullptr, "create a geometry of " + what);
  g.vertices = static_cast<float*>(rtcSetNewGeometryBuffer(g.handle, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                           3 * sizeof(float), 3 * triangles.size()));
  // An empty buffer may come back null (a geometry of no triangles: nothing filtered).
  check_embree(device_, g.vertices != nullptr || triangles.empty(), "allocate the vertices of " + what);
  auto* indices = static_cast<unsigned*>(rtcSetNewGeometryBuffer(
      g.handle, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), triangles.size()));
  check_embree(device_, indices != nullptr || triangles.empty(), "allocate the indices of " + what);
  // Unshared vertices: simple, and the BVH cost dominates memory anyway.
  for (size_t i = 0; i < 3 * triangles.size(); ++i) indices[i] = unsigned(i);
  write_vertices(g);
  // A moving part's BVH is refitted to its posed vertices (Embree honours
  // REFIT in a LOW-quality scene): tight boxes under translation, looser
  // under rotation and deformation.
  if (moving) rtcSetGeometryBuildQuality(g.handle, RTC_BUILD_QUALITY_REFIT);
  if (filters != Filters::None) rtcSetGeometryUserData(g.handle, const_cast<Accel*>(this));
  if (filters == Filters::CameraHits) rtcSetGeometryIntersectFilterFunction(g.handle, filter_camera_hits);
  if (filters == Filters::AllHits) {
    rtcSetGeometryIntersectFilterFunction(g.handle, filter_hits);
    rtcSetGeometryOccludedFilterFunction(g.handle, filter_hits);
  }
  rtcCommitGeometry(g.handle);
  check_embree(device_, true, "commit a geometry of " + what);
}

void Accel::add_group(const std::vector<uint32_t>& triangles, RTCBuildQuality quality) {
  RTCScene scene = rtcNewScene(device_);
  check_embree(device_, scene != nullptr, "create a scene");
  // The group's from here, so that the destructor releases what a throw leaves.
  Group& added = groups_.emplace_back();
  added.scene = scene;
  rtcSetSceneBuildQuality(added.scene, quality);
  const bool moving = groups_.size() > 1;
  if (moving) rtcSetSceneFlags(added.scene, RTC_SCENE_FLAG_DYNAMIC);
  // Shadow rays never cull back faces, so only alpha-masked triangles need
  // the occluded callback: on single-sided faces it cost 5-10 % of a frame
  // and changed nothing (cornell-blob exported with every material
  // single-sided, 320x240, 4 passes, one thread: 3.05 and 3.18 s with it,
  // 2.89 and 2.89 s without, the same image bit for bit).
  std::vector<uint32_t> lists[3];  // by Filters
  for (uint32_t t : triangles) {
    const Material& m = scene_.materials[scene_.triangle_material[t]];
    const Filters filters = m.alpha_mask ? Filters::AllHits : m.culls_back_faces() ? Filters::CameraHits : Filters::None;
    lists[int(filters)].push_back(t);
  }
  for (int f = 0; f < 3; ++f) {
    build_triangles(added.geometries.emplace_back(), lists[f], moving, Filters(f));
    if (rtcAttachGeometry(added.scene, added.geometries.back().handle) != added.geometries.size() - 1)
      throw std::logic_error("embree: unexpected geometry id");
  }
  rtcCommitScene(added.scene);
  check_embree(device_, true, "build the BVH of " + std::to_string(triangles.size()) + " triangles");

  added.instance = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_INSTANCE);
  check_embree(device_, added.instance != nullptr, "create an instance");
  rtcSetGeometryInstancedScene(added.instance, added.scene);
  const float identity[12] = {1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0};
  rtcSetGeometryTransform(added.instance, 0, RTC_FORMAT_FLOAT3X4_COLUMN_MAJOR, identity);
  rtcCommitGeometry(added.instance);
  check_embree(device_, true, "commit an instance");
  if (rtcAttachGeometry(top_, added.instance) != groups_.size() - 1)
    throw std::logic_error("embree: unexpected instance id");
}

void Accel::write_vertices(const Geometry& geometry) const {
  float* out = geometry.vertices;
  for (uint32_t t : geometry.triangles)
    for (int k = 0; k < 3; ++k) {
      const glm::vec3 p = scene_.positions[scene_.triangles[t][k]];
      *out++ = p.x, *out++ = p.y, *out++ = p.z;
    }
}

// The order Embree asks for: the instanced scene, then its instance, then the top.
void Accel::update() {
  if (groups_.size() < 2) return;
  for (size_t i = 1; i < groups_.size(); ++i) {
    Group& group = groups_[i];
    for (Geometry& g : group.geometries) {
      write_vertices(g);
      rtcUpdateGeometryBuffer(g.handle, RTC_BUFFER_TYPE_VERTEX, 0);
      rtcCommitGeometry(g.handle);
    }
    rtcCommitScene(group.scene);
    rtcCommitGeometry(group.instance);
  }
  rtcCommitScene(top_);
  check_embree(device_, true, "rebuild the moving parts' BVHs");
  // A posed scene measures as the same pose loaded static (the clamp follows it).
  if (moving_triangles_.empty())  // the moving groups never change: gathered on the first update
    for (size_t i = 1; i < groups_.size(); ++i)
      for (const Geometry& g : groups_[i].geometries)
        moving_triangles_.insert(moving_triangles_.end(), g.triangles.begin(), g.triangles.end());
  measure_areas(moving_triangles_);
  mean_chord_ = measure_mean_chord();
}

// Null handles are those a failed construction never made.
Accel::~Accel() {
  if (top_) rtcReleaseScene(top_);
  for (Group& group : groups_) {
    if (group.instance) rtcReleaseGeometry(group.instance);
    for (Geometry& g : group.geometries)
      if (g.handle) rtcReleaseGeometry(g.handle);
    rtcReleaseScene(group.scene);
  }
  if (device_) rtcReleaseDevice(device_);
}

bool Accel::rejects(uint32_t triangle, glm::vec2 b, glm::vec3 direction, bool camera_ray) const {
  const Material& m = scene_.materials[scene_.triangle_material[triangle]];
  const glm::uvec3& t = scene_.triangles[triangle];
  if (m.culls_back_faces() && camera_ray) {
    if (glm::dot(triangle_cross(scene_, triangle), direction) > 0.0f) return true;  // the back of a single-sided face
  }
  if (m.alpha_mask) {
    float alpha = m.base_alpha;
    if (m.base_color_texture.used() && !scene_.uvs.empty()) {
      glm::vec2 uv = (1.0f - b.x - b.y) * scene_.uvs[t[0]] + b.x * scene_.uvs[t[1]] + b.y * scene_.uvs[t[2]];
      alpha *= scene_.textures[size_t(m.base_color_texture.index)].sample(m.base_color_texture.uv(uv)).a;
    }
    if (alpha < m.alpha_cutoff) return true;
  }
  return false;
}

bool Accel::intersect(const Ray& ray, Hit& hit) const {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRayHit rh;
  set_rtc_ray(rh.ray, ray);
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(top_, &context, &rh);
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return false;
  hit.t = rh.ray.tfar;
  hit.triangle = triangle_index(rh.hit.instID[0], rh.hit.geomID, rh.hit.primID);
  hit.barycentric = {rh.hit.u, rh.hit.v};
  return true;
}

bool Accel::occluded(const Ray& ray) const {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRay r;
  set_rtc_ray(r, ray);
  rtcOccluded1(top_, &context, &r);
  return r.tfar < 0.0f;
}

void Accel::occluded16(std::span<const Ray> rays, std::span<bool> occluded) const {
  if (rays.size() > 16 || occluded.size() < rays.size())
    throw std::invalid_argument("Accel::occluded16: more than 16 rays, or fewer answers than rays");
  if (rays.empty()) return;
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
  alignas(64) RTCRay16 r;
  alignas(64) int valid[16];
  for (size_t i = 0; i < 16; ++i) {
    valid[i] = i < rays.size() ? -1 : 0;
    const Ray& ray = rays[i < rays.size() ? i : 0];  // unused lanes: a copy, masked off
    r.org_x[i] = ray.origin.x; r.org_y[i] = ray.origin.y; r.org_z[i] = ray.origin.z;
    r.dir_x[i] = ray.direction.x; r.dir_y[i] = ray.direction.y; r.dir_z[i] = ray.direction.z;
    r.tnear[i] = ray.tnear;
    r.tfar[i] = ray.tfar;
    r.mask[i] = ray.mask;
    r.time[i] = 0.0f;
    r.id[i] = 0;
    r.flags[i] = 0;
  }
  rtcOccluded16(valid, top_, &context, &r);
  for (size_t i = 0; i < rays.size(); ++i) occluded[i] = r.tfar[i] < 0.0f;
}

}  // namespace igi
