#include "scene/accel.h"

#include <cstdio>
#include <stdexcept>
#include <string>

#include <pmmintrin.h>
#include <xmmintrin.h>

#include "scene/triangle.h"

namespace igi {

void enable_flush_to_zero() {
  _MM_SET_FLUSH_ZERO_MODE(_MM_FLUSH_ZERO_ON);
  _MM_SET_DENORMALS_ZERO_MODE(_MM_DENORMALS_ZERO_ON);
}

static void device_error(void*, RTCError code, const char* message) {
  std::fprintf(stderr, "embree error %d: %s\n", int(code), message ? message : "");
}

// One callback serves rtcIntersect* and rtcOccluded*, any packet width.
static void filter_hits(const RTCFilterFunctionNArguments* args) {
  const auto* accel = static_cast<const Accel*>(args->geometryUserPtr);
  for (unsigned i = 0; i < args->N; ++i) {
    if (args->valid[i] != -1) continue;
    unsigned prim = RTCHitN_primID(args->hit, args->N, i);
    unsigned geom = RTCHitN_geomID(args->hit, args->N, i);
    glm::vec2 bary(RTCHitN_u(args->hit, args->N, i), RTCHitN_v(args->hit, args->N, i));
    glm::vec3 dir(RTCRayN_dir_x(args->ray, args->N, i), RTCRayN_dir_y(args->ray, args->N, i),
                  RTCRayN_dir_z(args->ray, args->N, i));
    const bool camera_ray = RTCRayN_mask(args->ray, args->N, i) == kCameraRayMask;
    if (accel->rejects(accel->triangle_index(geom, prim), bary, dir, camera_ray)) args->valid[i] = 0;
  }
}

Accel::Accel(const Scene& scene) : scene_(scene) {
  device_ = rtcNewDevice(nullptr);
  if (!device_) throw std::runtime_error("embree: cannot create device");
  rtcSetDeviceErrorFunction(device_, device_error, nullptr);
  scene_handle_ = rtcNewScene(device_);
  rtcSetSceneBuildQuality(scene_handle_, RTC_BUILD_QUALITY_HIGH);

  std::vector<uint32_t> plain, filtered;
  for (uint32_t i = 0; i < scene.triangles.size(); ++i) {
    const Material& m = scene.materials[scene.triangle_material[i]];
    (m.alpha_mask || !m.double_sided ? filtered : plain).push_back(i);
  }
  add_geometry(plain, false);
  add_geometry(filtered, true);
  rtcCommitScene(scene_handle_);
}

void Accel::add_geometry(const std::vector<uint32_t>& triangles, bool filtered) {
  RTCGeometry geom = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
  auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(
      geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), 3 * triangles.size()));
  auto* indices = static_cast<unsigned*>(rtcSetNewGeometryBuffer(
      geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), triangles.size()));
  // Unshared vertices: simple, and the BVH cost dominates memory anyway.
  for (size_t i = 0; i < triangles.size(); ++i)
    for (int k = 0; k < 3; ++k) {
      glm::vec3 p = scene_.positions[scene_.triangles[triangles[i]][k]];
      vertices[9 * i + 3 * k + 0] = p.x;
      vertices[9 * i + 3 * k + 1] = p.y;
      vertices[9 * i + 3 * k + 2] = p.z;
      indices[3 * i + k] = unsigned(3 * i + k);
    }
  if (filtered) {
    rtcSetGeometryUserData(geom, const_cast<Accel*>(this));
    rtcSetGeometryIntersectFilterFunction(geom, filter_hits);
    rtcSetGeometryOccludedFilterFunction(geom, filter_hits);
  }
  rtcCommitGeometry(geom);
  unsigned id = rtcAttachGeometry(scene_handle_, geom);
  rtcReleaseGeometry(geom);
  if (id != geometry_triangles_.size()) throw std::logic_error("embree: unexpected geometry id");
  geometry_triangles_.push_back(triangles);
}

Accel::~Accel() {
  rtcReleaseScene(scene_handle_);
  rtcReleaseDevice(device_);
}

bool Accel::rejects(uint32_t triangle, glm::vec2 b, glm::vec3 direction, bool camera_ray) const {
  const Material& m = scene_.materials[scene_.triangle_material[triangle]];
  const glm::uvec3& t = scene_.triangles[triangle];
  if (!m.double_sided && camera_ray) {
    if (glm::dot(triangle_cross(scene_, triangle), direction) > 0.0f) return true;  // the back of a single-sided face
  }
  if (m.alpha_mask) {
    float alpha = m.base_alpha;
    if (m.base_color_texture >= 0 && !scene_.uvs.empty()) {
      glm::vec2 uv = (1.0f - b.x - b.y) * scene_.uvs[t[0]] + b.x * scene_.uvs[t[1]] + b.y * scene_.uvs[t[2]];
      alpha *= scene_.textures[m.base_color_texture].sample(uv).a;
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
  rtcIntersect1(scene_handle_, &context, &rh);
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return false;
  hit.t = rh.ray.tfar;
  hit.triangle = triangle_index(rh.hit.geomID, rh.hit.primID);
  hit.barycentric = {rh.hit.u, rh.hit.v};
  return true;
}

bool Accel::occluded(const Ray& ray) const {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRay r;
  set_rtc_ray(r, ray);
  rtcOccluded1(scene_handle_, &context, &r);
  return r.tfar < 0.0f;
}

}  // namespace igi
