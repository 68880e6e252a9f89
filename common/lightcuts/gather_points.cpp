#include "lightcuts/gather_points.h"

#include "core/gbuffer.h"

namespace igi::lightcuts {

GatherPointTracer::GatherPointTracer(const Accel& accel, const FrameSetup& frame, int samples_per_pixel,
                                     int specular_depth)
    : accel_(accel), camera_(frame, samples_per_pixel), specular_depth_(specular_depth) {}

GatherPoint GatherPointTracer::trace(int x, int y, int k, RayCounts& rays) const {
  GatherPoint g;
  const Ray ray = camera_.pixel_ray(x, y, k);
  ++rays.primary;
  Hit hit;
  if (!accel_.intersect(ray, hit)) {
    g.emitted = accel_.scene().sky(ray.direction);  // the sky (black without one)
    return g;
  }
  GSample chain;
  follow_specular_chain(accel_, ray, hit, camera_.chain_seed(x, y, k), specular_depth_, chain, rays);
  return gather_point(chain);
}

GatherPoint gather_point(const GSample& chain) {
  GatherPoint g;
  g.emitted = chain.emitted;
  g.throughput = chain.throughput;
  if (!chain.valid()) return g;
  const SurfacePoint& sp = chain.surface;
  g.surface = sp;
  g.wo = chain.wo;
  g.depth = chain.depth;
  g.shading_normal = sp.shading_normal_facing(g.wo);
  g.geometric_normal = sp.geometric_normal_facing(g.wo);
  g.cos_o = glm::dot(g.wo, g.shading_normal);
  g.shading_frame = BoundFrame(g.shading_normal);
  g.geometric_frame = BoundFrame(g.geometric_normal);
  g.back_frame = BoundFrame(-g.wo);
  const float cos_tilt = std::min(1.0f, glm::dot(g.shading_normal, g.geometric_normal));
  g.tilt_sin = g.shading_normal == g.geometric_normal ? 0.0f : std::sqrt(std::max(0.0f, 1.0f - cos_tilt * cos_tilt)) * 1.0001f;
  return g;
}

}  // namespace igi::lightcuts
