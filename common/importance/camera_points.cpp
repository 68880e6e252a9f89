#include "importance/camera_points.h"

#include "sampling/hash.h"
#include "sampling/sobol.h"

namespace igi::importance {

GSample trace_camera_point(const Accel& accel, const CameraFrontEnd& camera, uint32_t index, uint32_t seed,
                           int specular_depth, RayCounts& rays) {
  GSample g;
  const glm::vec2 film = sample_2d(index, 0, seed);
  const Ray ray = camera.ray(film.x * float(camera.frame().width), film.y * float(camera.frame().height));
  ++rays.primary;
  Hit hit;
  if (accel.intersect(ray, hit)) follow_specular_chain(accel, ray, hit, hash(seed, index), specular_depth, g, rays);
  return g;
}

}  // namespace igi::importance
