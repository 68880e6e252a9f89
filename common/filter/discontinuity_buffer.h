#pragma once
// Discontinuity buffer (Wald et al. 2002, "Interactive Global Illumination").
//
// IGI shades each pixel with one of N x N interleaved VPL sets, so neighbours
// see different light samples. The filter averages *demodulated irradiance*
// (radiance divided by the centre's albedo; the caller remodulates once) over
// the N x N window around each pixel, which holds each set once, but only
// over neighbours on the same surface, so geometric edges stay sharp. (A
// window of 2 floor(N/2) + 1 would hold some sets twice for even N, and
// their double weight printed an N-periodic grid on every wall.)
//
// Definition, for an inner pixel p of a region, with a = floor(N/2) and
// b = N - 1 - a (a = b for odd N):
//   p invalid (depth = +inf)  ->  out_p = value_p
//   otherwise                 ->  out_p = sum_{q in S_p} value_q / |S_p|,
//   S_p = { q in region : q.x - p.x and q.y - p.y in [-a, b], q valid,
//           dot(n_p, n_q) >= normal_cos, |d_q - d_p| <= depth_ratio * d_p }.
// p is always in S_p. Windows are clipped to the region, which the caller
// clips to the image; so an inner pixel needs a pixels of border on every
// side that is not an image edge, else its window is silently cut short.
//
// Determinism: out_p is a pure function of the data in p's window and the
// settings, never of the region's size or offset, so the same pixel filtered
// in differently cut tiles is bit-identical (a cluster's tiles must seam).
//
// Threading: the functions are pure; call them concurrently on distinct
// outputs. Each call allocates its own scratch.
#include <cstdint>
#include <span>
#include <vector>

#include <glm/vec3.hpp>

namespace igi {

// One tile region, row-major, width * height entries in each vector.
struct FilterInput {
  int x0 = 0, y0 = 0;  // image coordinates of the region's top-left pixel
  int width = 0, height = 0;
  std::vector<float> depth;       // distance from the camera, > 0; +inf marks "no surface" (never NaN)
  std::vector<glm::vec3> normal;  // unit shading normal (ignored where depth is +inf)
  std::vector<glm::vec3> value;   // demodulated irradiance, finite, >= 0
};

struct FilterSettings {
  // The window is n x n pixels, n = N for N x N VPL sets, so it holds each
  // set once: [p - n/2, p - n/2 + n - 1] each way (centred for odd n; one
  // pixel more before p than after for even n).
  int window = 3;
  float normal_cos = 0.9f;   // q counts only if dot(n_p, n_q) >= normal_cos ...
  float depth_ratio = 0.05f; // ... and |d_q - d_p| <= depth_ratio * d_p (scale-free)
  // Fixed-point scale of the running sums: value * fixed_scale is rounded to
  // an integer, so one quantum is 1 / fixed_scale. See filter_fixed_scale().
  double fixed_scale = 0x1p32;
};

// Image coordinates; must lie inside the region.
struct Rect {
  int x = 0, y = 0, w = 0, h = 0;
};

// How many inner pixels took each path. Invalid pixels (copied through)
// count as exact.
struct FilterStats {
  uint64_t fast_pixels = 0, exact_pixels = 0;
};

// The reference: evaluates the definition above pixel by pixel, O(window)
// each, summing the window row-major in double. `out` receives inner.w *
// inner.h values, row-major. Throws std::invalid_argument on a malformed
// input, an inner rect outside the region or a short `out`.
void filter_brute_force(const FilterInput& in, const FilterSettings& s, Rect inner, std::span<glm::vec3> out);

// The same result in constant time per pixel where a whole window lies on
// one surface (box sums of int64 fixed-point values, exact up to one
// quantum); other pixels are evaluated exactly like filter_brute_force, bit
// for bit. Same contract and errors as filter_brute_force; `stats`, if given,
// is overwritten.
void filter_discontinuity(const FilterInput& in, const FilterSettings& s, Rect inner, std::span<glm::vec3> out,
                          FilterStats* stats = nullptr);

// The discontinuity buffer twice: F(F(in)), each pass with the window and
// the same-surface test above. On a surface the kernel is a tent of 2 n - 1
// pixels, the box convolved with itself, which still weighs every set alike
// (each box holds each set once), but reconstructs a set's lattice of pixels
// linearly where one box alone repeated each of its pixels over an n x n
// square: a VPL close to a wall, seen by one set, showed as a staircase of
// squares (BreakfastRoom's walls beside its window), and a spike the
// hand-over keeps filtered as one square. An inner pixel needs twice the
// window's reach of border (core/tiling.h). Pure and tile-invariant as F is.
void filter_tent(const FilterInput& in, const FilterSettings& s, Rect inner, std::span<glm::vec3> out);

// A fixed_scale for a frame whose demodulated irradiance is typically
// `typical_value`: 2^(24 - round(log2(typical))), so a typical value keeps 24
// bits (float precision) and values up to ~2^24 x typical fit the sums before
// they saturate. The exponent is clamped to [-32, 64]; a typical value that
// is zero, negative or not finite gives the default 2^32.
double filter_fixed_scale(double typical_value);

// Passes hand the filter over to the pixels' own sums. The window's blur
// (irradiance averaged over N x N neighbours on a surface) is a bias that
// more passes would not remove, so progressive pass k (0-based) takes
//   w_k filtered + (1 - w_k) unfiltered,  w_k = min(1, sqrt(K / (k + 1))),
// K = kFilterFullPasses: the first K passes are filtered in full, and the
// mean of n passes carries a blur of weight mean(w) ~ 2 sqrt(K / n), whose
// square falls as 1 / n, as the noise does. By pass k every pixel has seen k
// independent sets of its own, so the unfiltered part's noise averages out
// too. A moving view (pass 0) is filtered in full.
//
// Spikes are not handed over: the part of a value above the spike level
// stays filtered at every pass (filter_handed_over). A VPL close to a surface,
// which the relaxing clamp (core/clamp.h) lets through, would otherwise land
// whole on one pixel (rooms at 128x128, 256 passes, relMSE against pt: 0.00069
// with the spikes handed over, 0.00023 with them filtered, 0.00015 with every
// pass filtered in full, whose FLIP is higher, 0.0213 against 0.0191). The level is the frame's typical demodulated
// irradiance (one set's flux over the scene diagonal squared) times
// ((k + 1) / K)^(1/4): it rises as the clamp's distance falls, so the spikes'
// blur vanishes too.
constexpr uint32_t kFilterFullPasses = 16;
float filter_weight_at_pass(uint32_t pass);
float filter_spike_level(float typical_value, uint32_t pass);

// The discontinuity buffer at hand-over weight w < 1 and spike level L: with
// h = max(u - L, 0) per channel and F the tent above,
//   out = w F(u - h) + (1 - w) (u - h) + F(h).
// w >= 1 is filter_tent itself. Pure and tile-invariant as it is
// (the split is per pixel, L one number for the frame); `in` is not changed.
void filter_handed_over(const FilterInput& in, const FilterSettings& s, Rect inner, float weight, float spike_level,
                        std::span<glm::vec3> out);

}  // namespace igi
