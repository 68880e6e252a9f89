#include "methods/path_tracer.h"

#include <cmath>

#include "core/camera_front_end.h"
#include "material/bsdf.h"
#include "sampling/hash.h"
#include "sampling/sobol.h"
#include "sampling/warp.h"
#include "scene/surface.h"
#include "sampling/pixel_samples.h"

namespace igi {
namespace {

// Dimensions per path vertex: light choice, light point (2), BSDF lobe, BSDF direction (2), roulette.
constexpr uint32_t kDimsPerBounce = 10;  // SampleStream gives every 1D draw a pair of its own

}  // namespace

PathTracer::PathTracer(const SceneContext& context, const RenderSettings& settings)
    : context_(context), settings_(settings) {}

void PathTracer::begin_frame(const FrameSetup& frame) { frame_ = frame; }

void PathTracer::render_tile(const TileJob& job, std::span<glm::vec3> out, RayCounts& rays) const {
  const CameraFrontEnd camera(frame_);
  for (int y = job.y; y < job.y + job.h; ++y)
    for (int x = job.x; x < job.x + job.w; ++x) {
      const uint32_t pixel_seed = PixelSamples{frame_.seed}.pixel(x, y);
      glm::dvec3 sum(0.0);
      for (uint32_t i = 0; i < frame_.sample_count; ++i) {
        const uint32_t index = frame_.sample_begin + i;
        glm::vec2 jitter = sample_2d(index, 0, pixel_seed);
        const Ray ray = camera.ray(float(x) + jitter.x, float(y) + jitter.y);
        ++rays.primary;
        sum += glm::dvec3(radiance(ray, index, pixel_seed, rays));
      }
      // Per-pass mean; passes are combined by the caller as sums.
      out[size_t(y - job.y) * job.w + (x - job.x)] = glm::vec3(sum / double(frame_.sample_count));
    }
}

// Next-event estimation: a light sample, weighted against the BSDF's, times `throughput`.
glm::vec3 PathTracer::next_event(const SurfacePoint& sp, glm::vec3 wo, glm::vec3 throughput, float u_light,
                                 glm::vec2 u_light_point, RayCounts& rays) const {
  LightSample ls = context_.lights.sample(sp.position, u_light, u_light_point);
  glm::vec3 f = ls.pdf > 0.0f ? bsdf_eval(sp, wo, ls.direction) : glm::vec3(0.0f);
  if (f == glm::vec3(0.0f)) return glm::vec3(0.0f);
  const Ray shadow = shadow_ray(sp, ls.direction, ls.position, ls.distance);
  ++rays.shadow;
  if (context_.accel.occluded(shadow)) return glm::vec3(0.0f);
  float cos_i = std::abs(glm::dot(ls.direction, sp.shading_normal));
  float w = ls.delta ? 1.0f : power_heuristic(ls.pdf, bsdf_pdf(sp, wo, ls.direction));
  return throughput * f * ls.radiance * (cos_i * w / ls.pdf);
}

glm::vec3 PathTracer::radiance(Ray ray, uint32_t sample_index, uint32_t pixel_seed, RayCounts& rays) const {
  const Scene& scene = context_.scene;
  glm::vec3 result(0.0f), throughput(1.0f);
  bool specular_bounce = true;  // the camera "bounce": emission counts in full
  float bsdf_pdf_prev = 0.0f;
  glm::vec3 prev_position = ray.origin;
  const int max_depth = depth_limit(settings_.path_depth);
  for (int depth = 0; depth < max_depth; ++depth) {
    Hit hit;
    // Camera rays and what mirrors and glass show of them skip the back of
    // single-sided faces; after a diffuse or glossy bounce every face is opaque.
    ray.mask = specular_bounce ? kCameraRayMask : kOpaqueRayMask;
    if (!context_.accel.intersect(ray, hit)) {
      // Out of the scene: the environment, weighted against its light samples.
      if (scene.has_environment()) {
        const float w =
            specular_bounce ? 1.0f : power_heuristic(bsdf_pdf_prev, context_.lights.pdf_environment(ray.direction));
        result += throughput * scene.sky(ray.direction) * w;
      }
      break;
    }
    SurfacePoint sp = surface_at(scene, hit, ray.direction);
    const glm::vec3 wo = -ray.direction;

    // Emission found by the BSDF sample, weighted against light sampling.
    glm::vec3 le = sp.emitted();
    if (le != glm::vec3(0.0f)) {
      float w = 1.0f;
      if (!specular_bounce)
        w = power_heuristic(bsdf_pdf_prev, context_.lights.pdf_area(hit.triangle, prev_position, sp.position));
      result += throughput * le * w;
    }

    SampleStream u(sample_index, pixel_seed, 2 + kDimsPerBounce * uint32_t(depth));
    const float u_light = u.next_1d();
    const glm::vec2 u_light_point = u.next_2d();
    const float u_lobe = u.next_1d();
    const glm::vec2 u_bsdf = u.next_2d();
    const float u_roulette = u.next_1d();

    if (!sp.material->is_specular()) result += next_event(sp, wo, throughput, u_light, u_light_point, rays);

    auto bs = bsdf_sample(sp, wo, u_bsdf, u_lobe);
    if (!bs) break;
    throughput *= bs->weight;
    specular_bounce = bs->specular;
    bsdf_pdf_prev = bs->pdf;
    prev_position = sp.position;
    if (depth >= 3) {  // Russian roulette on the path's throughput
      float q = std::min(0.95f, max_component(throughput));
      if (u_roulette >= q) break;
      throughput /= q;
    }
    ray = Ray{offset_origin(sp, bs->wi), bs->wi};
    ++rays.secondary;
  }
  return result;
}

}  // namespace igi
