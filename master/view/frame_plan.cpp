#include "view/frame_plan.h"

#include <algorithm>
#include <cmath>

#include "core/passes.h"
#include "scene/animation.h"

namespace igi {
namespace {

struct SinCos {
  double sin = 0.0, cos = 1.0;
};

// sin and cos without the maths library, whose last bit differs from machine
// to machine (another glibc, its dispatch for another CPU): a master on a
// login node must plan the very cameras its workers' one process would. Only
// +, -, x and floor, which IEEE 754 rounds alike everywhere: x less whole
// quarter turns (pi/2 in two parts, the second for what the first's 33 bits
// miss, so k x the first is exact), then Taylor series to r^17 and r^16,
// whose next terms are below 1e-19 for |r| <= pi/4.
SinCos sin_cos(double x) {
  constexpr double kTwoOverPi = 0.63661977236758134308;
  constexpr double kHalfPiHigh = 1.57079632673412561417e+00;
  constexpr double kHalfPiLow = 6.07710050650619224932e-11;
  const double k = std::floor(x * kTwoOverPi + 0.5);
  const double r = (x - k * kHalfPiHigh) - k * kHalfPiLow;
  const double r2 = r * r;
  double s = 0.0, c = 0.0;
  // Nested: sin r = r (1 - r^2/(3 2) (1 - r^2/(5 4) (1 - ...))), cos r = 1 - r^2/(2 1) (1 - r^2/(4 3) (...)).
  for (int n = 17; n >= 3; n -= 2) s = r2 * (1.0 - s) / double(n * (n - 1));
  for (int n = 16; n >= 2; n -= 2) c = r2 * (1.0 - c) / double(n * (n - 1));
  s = r * (1.0 - s);
  c = 1.0 - c;
  switch (int64_t(k) & 3) {
    case 0: return {s, c};
    case 1: return {c, -s};
    case 2: return {-s, -c};
    default: return {-c, s};
  }
}

}  // namespace

double camera_path_angle(const CameraPath& path, int i) {
  constexpr double kTurn = 2.0 * 3.14159265358979323846;
  const double frames = std::max(path.frames, 1);
  switch (path.kind) {
    case CameraPath::Kind::None: return 0.0;
    case CameraPath::Kind::Orbit:
      return path.orbit_step_degrees != 0.0 ? path.orbit_step_degrees * (kTurn / 360.0) * i : kTurn * i / frames;
    case CameraPath::Kind::Swing: return path.swing_degrees * (kTurn / 360.0) * sin_cos(kTurn * i / frames).sin;
  }
  return 0.0;
}

FrameSetup plan_frame(const RenderOptions& render, const CameraPath& camera_path, const Scene& scene, int i,
                      bool progressive) {
  FrameSetup f;
  f.frame_id = uint64_t(i);
  f.width = render.width;
  f.height = render.height;
  f.seed = render.seed;
  const bool pt = render.settings.method == MethodKind::PathTracer;
  const bool animated = scene.animation && scene.animation->animated();
  progressive = progressive && !animated;  // each frame of an animation stands at a time of its own
  f.sample_count = pt ? uint32_t(render.samples) : 1;
  if (progressive) f = progressive_pass(f, render.settings.method, uint32_t(i), f.sample_count);  // core/passes.h
  f.pose.light_offset = render.light_offset;
  if (animated)
    f.pose.time = scene_time(render.time, render.time_step, uint64_t(i), render.loop, scene.animation->duration);
  f.camera = scene_camera(scene, f.pose.time);  // where an animated camera stands then
  const double angle = camera_path_angle(camera_path, i);
  if (angle != 0.0) {
    const Camera& c = f.camera;
    const glm::vec3 forward = glm::normalize(c.forward);
    const float along = glm::dot(scene.bounds().center() - c.position, forward);
    const glm::vec3 pivot = c.position + std::max(along, 0.0f) * forward;
    const SinCos a = sin_cos(angle);
    const float sin = float(a.sin), cos = float(a.cos);
    const glm::mat3 r(glm::vec3(cos, 0, -sin), glm::vec3(0, 1, 0), glm::vec3(sin, 0, cos));
    f.camera.position = pivot + r * (c.position - pivot);
    f.camera.forward = r * c.forward;
    f.camera.up = r * c.up;
  }
  return f;
}

}  // namespace igi
