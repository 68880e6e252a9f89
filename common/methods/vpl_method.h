#pragma once
// Methods `ir` and `igi`: shading from virtual point lights.
//  ir:  every pixel sums all S x M VPLs; no filter.
//  igi: pixel (x, y) sums only set (x mod N) + N (y mod N) of M VPLs; the
//       discontinuity buffer then averages demodulated irradiance over the
//       N x N window, so each pixel sees all sets at 1/S of the cost.
// With a clamp, optional bias compensation (methods/bias_compensation.h)
// adds back the clamped light before the filter.
// Shadow rays go out in 16-wide packets that share one VPL (coherent).
#include "methods/method.h"
#include "methods/ray_log.h"
#include "methods/shadow_batch.h"
#include "methods/gbuffer.h"
#include "vpl/vpl.h"

namespace igi {

class VplMethod final : public Method {
 public:
  VplMethod(const SceneContext& context, const RenderSettings& settings);
  void begin_frame(const FrameSetup& frame) override;
  void render_tile(const TileJob& job, std::span<glm::vec3> out, RayCounts& rays) const override;
  uint64_t frame_state_hash() const override { return vpls_.hash; }
  const VplSets& vpls() const { return vpls_; }
  // Benchmarks only: record every packet traced from now on (one thread only).
  void record_rays(RayLog* log) { log_ = log; }

 private:
  bool interleaved() const { return settings_.method == MethodKind::Igi; }
  void collect_set_pixels(const std::vector<GSample>& gbuffer, const Region& region, int set,
                          PixelBatch& batch) const;
  void shade(const std::vector<GSample>& gbuffer, const Region& region,
             std::vector<glm::vec3>& irradiance, RayCounts& rays) const;
  void filter_or_crop(const std::vector<GSample>& gbuffer, const Region& region, const TileJob& job,
                      std::vector<glm::vec3>& irradiance, std::vector<glm::vec3>& filtered) const;

  SceneContext context_;
  RenderSettings settings_;
  FrameSetup frame_;
  VplSets vpls_;
  float clamp_bound_ = INFINITY;
  double fixed_scale_ = 0x1p32;
  RayLog* log_ = nullptr;
};

}  // namespace igi
