#pragma once
// Method `pt`: unidirectional path tracing with next-event estimation and
// multiple importance sampling (power heuristic) against BSDF sampling, and
// Russian roulette. The accuracy reference for every other method.
#include "core/method.h"
#include "scene/surface.h"

namespace igi {

class PathTracer final : public Method {
 public:
  PathTracer(const SceneContext& context, const RenderSettings& settings);
  void begin_frame(const FrameSetup& frame) override;
  void render_tile(const TileJob& job, std::span<glm::vec3> out, RayCounts& rays) const override;

  // Radiance along `ray`; `sample` addresses the path's random numbers.
  glm::vec3 radiance(Ray ray, uint32_t sample_index, uint32_t pixel_seed, RayCounts& rays) const;

 private:
  glm::vec3 next_event(const SurfacePoint& sp, glm::vec3 wo, glm::vec3 throughput, float u_light,
                       glm::vec2 u_light_point, RayCounts& rays) const;

  SceneContext context_;
  RenderSettings settings_;
  FrameSetup frame_;
};

}  // namespace igi
