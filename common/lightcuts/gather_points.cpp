#include "lightcuts/gather_points.h"

#include <cmath>

#include "material/bsdf.h"
#include "sampling/hash.h"

namespace igi::lightcuts {

GatherPointTracer::GatherPointTracer(const Accel& accel, const FrameSetup& frame, int samples_per_pixel,
                                     int specular_depth)
    : accel_(accel), camera_(frame.camera, frame.width, frame.height), frame_(frame),
      side_(std::max(1, int(std::lround(std::sqrt(double(samples_per_pixel)))))), specular_depth_(specular_depth) {}

GatherPoint GatherPointTracer::trace(int x, int y, int k, RayCounts& rays) const {
  GatherPoint g;
  const float fx = float(x) + (float(k % side_) + frame_.jitter_x) / float(side_);
  const float fy = float(y) + (float(k / side_) + frame_.jitter_y) / float(side_);
  Ray ray{camera_.origin, glm::normalize(camera_.direction(fx, fy))};
  ++rays.primary;
  Hit hit;
  if (!accel_.intersect(ray, hit)) return g;
  const Scene& scene = accel_.scene();
  const uint32_t chain_seed = hash(hash(uint32_t(x), uint32_t(y), frame_.seed), uint32_t(k));
  float travelled = 0.0f;
  for (int depth = 0;; ++depth) {
    const SurfacePoint sp = surface_at(scene, hit, ray.direction);
    travelled += hit.t;
    g.emitted += g.throughput * sp.emitted();
    if (!sp.material->is_specular()) {
      g.surface = sp;
      g.wo = -ray.direction;
      g.depth = travelled;
      const bool front = glm::dot(g.wo, sp.geometric_normal) >= 0.0f;
      g.shading_normal = front ? sp.shading_normal : -sp.shading_normal;
      g.geometric_normal = front ? sp.geometric_normal : -sp.geometric_normal;
      g.cos_o = glm::dot(g.wo, g.shading_normal);
      g.shading_frame = Frame(g.shading_normal);
      g.geometric_frame = Frame(g.geometric_normal);
      g.back_frame = Frame(-g.wo);
      const float cos_tilt = std::min(1.0f, glm::dot(g.shading_normal, g.geometric_normal));
      g.tilt_sin = g.shading_normal == g.geometric_normal ? 0.0f : std::sqrt(std::max(0.0f, 1.0f - cos_tilt * cos_tilt)) * 1.0001f;
      return g;
    }
    if (depth + 1 >= specular_depth_) return g;
    const float u_lobe = float(hash(chain_seed, uint32_t(depth)) >> 8) * 0x1p-24f;
    auto bs = bsdf_sample(sp, -ray.direction, glm::vec2(0.5f), u_lobe);
    if (!bs) return g;
    g.throughput *= bs->weight;
    ray = Ray{offset_origin(sp, bs->wi), bs->wi};
    ++rays.secondary;
    if (!accel_.intersect(ray, hit)) return g;
  }
}

}  // namespace igi::lightcuts
