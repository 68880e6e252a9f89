#include "core/pixel_surface.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "core/camera_front_end.h"
#include "scene/surface.h"

namespace igi {
namespace {

int8_t snorm8(float v) { return static_cast<int8_t>(std::lround(std::clamp(v, -1.0f, 1.0f) * 127.0f)); }

}  // namespace

bool view_dependent(const SurfacePoint& sp) {
  switch (sp.material->type) {
    case MaterialType::Diffuse: return false;
    case MaterialType::Conductor:
    case MaterialType::MetallicRoughness: return sp.alpha < kViewDependentAlpha;
    default: return true;  // mirrors and glass
  }
}

glm::vec2 surface_film_offset(const FrameSetup& frame, int samples_per_pixel) {
  return CameraFrontEnd(frame, samples_per_pixel).subpixel(0);
}

PixelSurface pixel_surface(const Accel& accel, const Hit& hit, glm::vec3 direction) {
  const SurfacePoint sp = surface_at(accel.scene(), hit, direction);
  const glm::vec3 n = sp.shading_normal_facing(-direction);
  PixelSurface s;
  s.depth = hit.t;
  for (int k = 0; k < 3; ++k) s.normal[k] = snorm8(n[k]);
  if (view_dependent(sp)) s.flags = PixelSurface::kViewDependent;
  return s;
}

// 16-wide packets of 4 x 4 pixels on the image's own grid, every lane
// inside the image traced, as core/gbuffer.cpp's camera packets of
// sub-sample 0 are: the same rays in the same packets, whichever tile and
// whichever of the two traces them. One ray at a time took as long as the
// sharp previews' whole camera pass (Cornell box at 640x480: 141 ms a
// preview with surfaces, 63 without).
uint64_t trace_pixel_surfaces(const Accel& accel, const FrameSetup& frame, int samples_per_pixel, const TileJob& tile,
                              std::span<PixelSurface> out) {
  if (out.size() != size_t(tile.w) * size_t(tile.h)) throw std::invalid_argument("trace_pixel_surfaces: wrong size");
  const CameraFrontEnd camera(frame, samples_per_pixel);
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  for (int by = tile.y / 4 * 4; by < tile.y + tile.h; by += 4)
    for (int bx = tile.x / 4 * 4; bx < tile.x + tile.w; bx += 4) {
      alignas(64) int valid[16];
      alignas(64) RTCRayHit16 packet;
      for (int i = 0; i < 16; ++i) {
        const int x = bx + (i & 3), y = by + (i >> 2);
        valid[i] = x < frame.width && y < frame.height ? -1 : 0;
        Ray ray = camera.pixel_ray(x, y, 0);
        ray.tfar = INFINITY;
        set_rtc_lane(packet.ray, i, ray);
        packet.hit.geomID[i] = RTC_INVALID_GEOMETRY_ID;
        packet.hit.instID[0][i] = RTC_INVALID_GEOMETRY_ID;
      }
      rtcIntersect16(valid, accel.handle(), &context, &packet);
      for (int i = 0; i < 16; ++i) {
        const int x = bx + (i & 3) - tile.x, y = by + (i >> 2) - tile.y;
        if (x < 0 || y < 0 || x >= tile.w || y >= tile.h) continue;
        PixelSurface& s = out[size_t(y) * tile.w + x];
        s = PixelSurface{};
        if (!valid[i] || packet.hit.geomID[i] == RTC_INVALID_GEOMETRY_ID) continue;  // the sky: no surface to carry
        const glm::vec3 direction{packet.ray.dir_x[i], packet.ray.dir_y[i], packet.ray.dir_z[i]};
        const Hit hit{packet.ray.tfar[i],
                      accel.triangle_index(packet.hit.instID[0][i], packet.hit.geomID[i], packet.hit.primID[i]),
                      {packet.hit.u[i], packet.hit.v[i]}};
        s = pixel_surface(accel, hit, direction);
      }
    }
  return uint64_t(tile.w) * uint64_t(tile.h);
}

}  // namespace igi
