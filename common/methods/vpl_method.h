#pragma once
// Methods `ir` and `igi`: shading from virtual point lights.
//  ir:  every pixel sums all S x M VPLs; no filter.
//  igi: pixel (x, y) sums only set (x mod N) + N (y mod N) of M VPLs; the
//       discontinuity buffer then averages demodulated irradiance over the
//       N x N window, so each pixel sees all sets at 1/S of the cost.
// Around that core, per tile:
//  - anti-aliasing by VPL groups: S sub-samples per pixel, each shaded by its
//    own group of the pixel's light paths (core/subpixel.h);
//  - GGX lobes sharper than the glossy threshold gather their light with
//    rays instead of taking VPL light (methods/glossy_gather.h); VPLs light
//    the rest of such a surface (a metallic-roughness surface's diffuse base);
//  - exact point, spot and directional lights, once per sub-sample, added
//    after the filter (core/direct_lights.h);
//  - with a clamp, optional bias compensation (methods/bias_compensation.h)
//    adds back the clamped light before the filter;
//  - glass seen from the camera splits into reflection and refraction
//    layers (core/gbuffer.h), each filtered on its own;
//  - with --wavelet, the edge-avoiding wavelet filter after the
//    discontinuity buffer, once per pixel (wavelet/wavelet_filter.h);
//  - with --vpl-draws K, each shading point draws K VPLs of all sets from
//    a light tree instead of its set's group (methods/vpl_draws.h);
//  - with --caustics, the caustic photon map (photons/caustic_map.h): light
//    that reached a diffuse surface through mirrors or glass, which no
//    shadow ray can carry, added after the filter like the exact lights.
// Shadow rays go one at a time (methods/shadow_batch.cpp says why); camera
// rays in 16-wide packets on the image's 4 x 4 grid (core/gbuffer.cpp).
#include <array>
#include <optional>

#include "core/gbuffer.h"
#include "core/method.h"
#include "core/ray_log.h"
#include "core/vpl.h"
#include "filter/discontinuity_buffer.h"
#include "methods/glossy_gather.h"
#include "methods/shadow_batch.h"
#include "methods/vpl_draws.h"
#include "photons/caustic_map.h"

namespace igi {

// The parts of an ir or igi frame, for benchmarks that ask where its time
// and rays go (igi-bench --defaults).
enum class FramePart {
  Vpls,          // begin_frame: light paths, importance probes, bidirectional VPLs
  Caustics,      // begin_frame: the caustic photon map
  Camera,        // camera rays and mirror and glass chains (the G-buffer)
  GlossyGather,  // gather rays of sharp glossy sub-samples
  VplLight,      // shadow rays to the VPLs and their shading
  ExactLights,   // point, spot and directional lights
  Compensation,  // bias compensation's hemisphere rays
  Filter,        // discontinuity buffer, wavelet, resolve (caustic look-ups included)
  Count
};
const char* frame_part_name(FramePart part);

struct FrameParts {
  std::array<double, size_t(FramePart::Count)> seconds{};  // elapsed (the bench renders on one thread)
  std::array<RayCounts, size_t(FramePart::Count)> rays{};
};

class VplMethod final : public Method {
 public:
  // Throws std::invalid_argument when the settings are out of range (settings_error()).
  VplMethod(const SceneContext& context, const RenderSettings& settings);
  void begin_frame(const FrameSetup& frame) override;
  void render_tile(const TileJob& job, std::span<glm::vec3> out, RayCounts& rays) const override;
  bool render_tile_with_surfaces(const TileJob& job, std::span<glm::vec3> out, std::span<PixelSurface> surfaces,
                                 RayCounts& rays) const override;
  // The VPL sets' hash, and the caustic map's folded in when there is one.
  uint64_t frame_state_hash() const override;
  const VplSets& vpls() const { return vpls_; }
  const CausticMap* caustics() const { return caustics_ ? &*caustics_ : nullptr; }
  // Rays begin_frame() traced for light importance and bidirectional IR (not the light paths).
  const RayCounts& setup_rays() const { return setup_rays_; }
  // Benchmarks only: record every packet traced from now on (one thread only).
  void record_rays(RayLog* log) { log_ = log; }
  // Benchmarks only: add each part's time and rays to `parts` from now on
  // (one thread only; the timing itself costs about 1 % of a frame).
  void record_parts(FrameParts* parts) { parts_ = parts; }

 private:
  struct Scratch;
  bool interleaved() const { return settings_.method == MethodKind::Igi; }
  VplShading vpl_shading() const;
  void collect_set_samples(const GBuffer& gbuffer, std::span<const uint8_t> rotation, int set, int group,
                           PixelBatch& batch) const;
  void shade_vpls(const GBuffer& gbuffer, const GlossyHits& hits, Scratch& scratch, RayCounts& rays) const;
  void shade_drawn(const GBuffer& gbuffer, const GlossyHits& hits, Scratch& scratch, RayCounts& rays) const;
  void shade_exact(const GBuffer& gbuffer, const TileJob& job, const GlossyHits& hits, Scratch& scratch,
                   RayCounts& rays) const;
  void combine(const GBuffer& gbuffer, const GlossyHits& hits, Scratch& scratch) const;
  void filter_layer(const GBuffer& gbuffer, int layer, const Rect& core, Scratch& scratch) const;
  void wavelet_pass(const GBuffer& gbuffer, const Rect& core, const TileJob& job, Scratch& scratch) const;
  void resolve(const GBuffer& gbuffer, const Rect& core, const TileJob& job, const Scratch& scratch,
               std::span<glm::vec3> out) const;
  Rect light(const GBuffer& gbuffer, const TileJob& job, Scratch& scratch, RayCounts& rays) const;
  void render(const TileJob& job, std::span<glm::vec3> out, std::span<PixelSurface> surfaces, RayCounts& rays) const;
  void render_lattice_tile(const TileJob& job, std::span<glm::vec3> out, std::span<PixelSurface> surfaces,
                           Scratch& scratch, RayCounts& rays) const;
  glm::vec3 caustic(const GSample& g) const { return caustics_ ? caustics_->radiance(g) : glm::vec3(0.0f); }

  SceneContext context_;
  RenderSettings settings_;
  FrameSetup frame_;
  VplSets vpls_;
  RayCounts setup_rays_;
  std::vector<Vpl> exact_;  // point, spot and directional lights (core/direct_lights.h)
  std::optional<CausticMap> caustics_;
  std::optional<VplDraws> draws_;  // --vpl-draws: the light tree over this frame's VPLs
  float clamp_bound_ = INFINITY;
  int wavelet_levels_ = 0;  // this pass's (wavelet_levels_at_pass)
  float filter_weight_ = 1.0f;  // this pass's share of the filtered value (filter_weight_at_pass)
  double fixed_scale_ = 0x1p32;
  float spike_level_ = INFINITY;  // demodulated irradiance above which a handed-over pass still filters
  RayLog* log_ = nullptr;
  FrameParts* parts_ = nullptr;
};

}  // namespace igi
