#pragma once
// Bias compensation for clamped VPLs (Kollig and Keller 2004/2006).
//
// Clamping G = cos_x cos_y / r^2 at b keeps only b / G of the light of a VPL
// closer than the clamp distance; the missing share (G - b) / G is light that
// travels a short hop to x. It is estimated by continuing the eye path: at x
// draw n directions with density cos_x / pi, trace each at most
// sqrt(|cos_x| / b) (beyond that G <= b: the clamp cut nothing), and at the
// hit y take L(y -> x) from the same clamped VPL estimate the pixel uses:
//   L_comp(x) = albedo_x / n * sum_k L(y_k -> x) max(0, (G_k - b) / G_k)
// since f cos / pdf = albedo for a Lambertian x. Values here are demodulated
// (albedo_x left out), like the VPL sums they are added to.
//
// A GGX receiver (rough enough to take VPL light) is clamped on f G, its
// lobe with albedo 1 times G, at b / pi (core/clamp.h), so the clamp cuts
// its sharp peak at any distance, not only close VPLs: there wi is drawn
// from the lobe, weighted f cos / pdf, traced at most sqrt(pi f cos_x / b),
// and the cut share is 1 - (b / pi) / (f G). On glossy-medium (a GGX 0.25
// floor beside a small bright lamp), 128x128 against pt, seed 1: mean 0.980
// -> 0.998 at one pass and 0.980 -> 0.991 at 16; relMSE 0.0154 -> 0.0024 and
// 0.0087 -> 0.0011; FLIP 0.090 -> 0.067 and 0.066 -> 0.048.
//
// Two levels: L(y -> x) is itself clamped, and its own missing share is
// estimated the same way from y, one more short hop (a second sample
// dimension of the same sequence); the third order is left out. In the
// furnace at a clamp that cuts 2/3 everywhere: 1.922 against the two-level
// analytic 1.926 and the exact 2 (one level: 1.778). The second level costs
// 1-3 % of a frame (640x480, Cornell box, corner, glossy-medium) and took
// the corner scene's mean at 256 passes from 0.995 to 0.998 of pt.
// Emission at y IS added, unlike pbrt-v2's igi: there direct light is
// computed apart and never clamped, so Le(y) would count it twice. Here the
// direct light of emissive triangles reaches x only through Area VPLs, which
// are clamped like the rest (core/vpl.h), so Le(y) over the short hop is
// exactly the direct light the clamp cut. Point and spot lights are never
// clamped and have no surface a ray could hit. Measured in the furnace
// (tests/common/methods/test_bias_compensation.cpp): with Le(y) one level gives 1.775
// against its analytic 1.778; without it 1.440.
//
// With anti-aliasing (core/subpixel.h) the pixel's n samples are shared
// out over its S sub-samples (n / S each, at least one), so a pixel costs
// about the same at any S, and L(y -> x) is the sub-sample's own group's
// estimate scaled by the group count, like its VPL sum. Exact point, spot and directional lights
// (never clamped, core/direct_lights.h) light y too: their light reflected
// over the short hop is what the clamp cut from the VPLs their paths left on y.
//
// Random numbers: sample_2d(k n / S + i, level - 1, PixelSamples{frame seed}.sequence(x, y, b))
// in GLOBAL pixel coordinates (x, y), sub-sample k, glass branch b of G-buffer
// layer l = b S + k (core/gbuffer.h), so a pixel's compensation is the
// same in whatever tile, thread or process renders it. All methods are const
// and thread-safe.
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "core/frame.h"
#include "core/gbuffer.h"
#include "core/vpl.h"
#include "core/vpl_contribution.h"
#include "scene/accel.h"

namespace igi {

class BiasCompensation {
 public:
  // igi (interleaved): a pixel uses its own set; ir: all sets, scaled 1 / S.
  // The references must outlive the object (one tile's work).
  // `log`, if given, records the shadow packets (benchmarks and tests; one thread only).
  BiasCompensation(const Accel& accel, const VplShading& shading, const VplSets& vpls,
                   std::span<const Vpl> exact_lights, bool interleaved, int samples, RayLog* log = nullptr)
      : accel_(accel), shading_(shading), vpls_(vpls), exact_(exact_lights), interleaved_(interleaved),
        bound_(shading.clamp_bound), samples_(samples), log_(log) {}

  // Off without samples or without a finite clamp (then nothing is missing).
  bool enabled() const { return samples_ > 0 && bound_ < INFINITY && !vpls_.vpls.empty(); }

  // Adds the compensation to `irradiance`, one demodulated entry per
  // layer sample of the G-buffer (sub-samples and glass branches), indexed
  // like its layers (border pixels included: the filter reads them).
  void add(const GBuffer& gbuffer, uint32_t frame_seed, std::vector<glm::vec3>& irradiance, RayCounts& rays) const;

 private:
  // A short hop's hit: the point, the hop's weight (f cos / pdf) times the
  // share the clamp cut there, and where its light goes.
  struct Hop {
    GSample y;
    glm::vec3 weight;
    float cut = 0.0f;
    uint32_t owner;  // level 1: the layer sample; level 2: its level-1 hop
    int set, group;
  };
  // The hop from sp, seen from wo, with the sample index's dimension
  // `level` - 1; false when it finds nothing the clamp cut.
  bool hop(const SurfacePoint& sp, glm::vec3 wo, uint32_t index, uint32_t seed, int level, Hop& out,
           RayCounts& rays) const;
  struct Scratch;  // per-thread buffers (bias_compensation.cpp)
  // L(y -> x) of every hop: the clamped VPL estimate of its group, in
  // packets of 16 hops to one VPL (methods/shadow_batch.h), and the exact lights.
  void radiance_towards(std::span<const Hop* const> hops, std::vector<glm::vec3>& radiance, RayCounts& rays) const;

  static constexpr int kLevels = 2;

  const Accel& accel_;
  const VplShading& shading_;
  const VplSets& vpls_;
  std::span<const Vpl> exact_;
  bool interleaved_;
  float bound_;
  int samples_;
  RayLog* log_;
};

}  // namespace igi
