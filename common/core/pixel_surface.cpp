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

uint64_t trace_pixel_surfaces(const Accel& accel, const FrameSetup& frame, const TileJob& tile,
                              std::span<PixelSurface> out) {
  if (out.size() != size_t(tile.w) * size_t(tile.h)) throw std::invalid_argument("trace_pixel_surfaces: wrong size");
  const CameraFrontEnd camera(frame);
  for (int y = 0; y < tile.h; ++y)
    for (int x = 0; x < tile.w; ++x) {
      PixelSurface& s = out[size_t(y) * tile.w + x];
      s = PixelSurface{};
      const Ray ray = camera.ray(float(tile.x + x) + 0.5f, float(tile.y + y) + 0.5f);
      Hit hit;
      if (!accel.intersect(ray, hit)) continue;  // the sky: no surface to carry
      const SurfacePoint sp = surface_at(accel.scene(), hit, ray.direction);
      const glm::vec3 n = sp.shading_normal_facing(-ray.direction);
      s.depth = hit.t;
      for (int k = 0; k < 3; ++k) s.normal[k] = snorm8(n[k]);
      if (sp.material->type != MaterialType::Diffuse) s.flags = PixelSurface::kViewDependent;
    }
  return uint64_t(tile.w) * uint64_t(tile.h);
}

}  // namespace igi
