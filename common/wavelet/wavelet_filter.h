#pragma once
// Edge-avoiding A-Trous wavelet filter (Dammertz, Sewtz, Hanika, Lensch,
// HPG 2010), with the variance-guided luminance weight of SVGF (Schied et
// al., HPG 2017) estimated from one frame.
//
// igi's discontinuity buffer averages N x N pixels, exactly the VPL sets of
// the interleaving; what it leaves are blotches the size of its window. This
// filter removes them: L levels of a 5 x 5 B3-spline kernel whose taps lie
// 2^i pixels apart at level i, each tap weighted by how much q is on p's
// surface and lit like p:
//
//   w(p, q) = h(dx) h(dy) * max(0, n_p . n_q)^128
//             * exp(-|d_p - d_q| / (depth_sigma d_p |q - p|_inf)
//                   -|l_p - l_q| / (sigma_luminance sqrt(var_p) + 1e-3 l_p))
//
// with h = (1, 4, 6, 4, 1) / 16, l the luminance of the level's input and
// var_p its variance, first estimated over p's 5 x 5 window (same-surface
// neighbours, weighted by the normal and depth terms), then carried through
// the levels as SVGF does: var' = sum w^2 var / (sum w)^2. Pixels of
// different materials never mix; a pixel with no surface (depth +inf) is
// copied through and read by nobody. Values are demodulated irradiance, so
// texture does not stop the filter.
//
// Footprint: an output pixel reads wavelet_footprint(L) = 2^(L+1) pixels on
// each side (2 for the variance window, 2 (1 + 2 + ... + 2^(L-1)) for the
// levels). Taps outside the region are skipped, so as with the
// discontinuity buffer the caller clips the region to the image and gives an
// inner pixel its whole footprint on every side that is not an image edge.
//
// Determinism: every intermediate value at a pixel is a pure function of the
// data around it, computed in a fixed order, so a pixel comes out the same
// bit for bit in differently cut tiles.
#include <cstdint>
#include <span>
#include <vector>

#include <glm/vec3.hpp>

#include "core/settings.h"  // kMaxWaveletLevels, wavelet_footprint
#include "filter/discontinuity_buffer.h"  // Rect

namespace igi {

// One region, row-major, width * height entries in each vector.
struct WaveletInput {
  int x0 = 0, y0 = 0;  // image coordinates of the region's top-left pixel
  int width = 0, height = 0;
  std::vector<float> depth;        // distance from the camera, > 0; +inf: no surface
  std::vector<glm::vec3> normal;   // unit shading normal
  std::vector<uint32_t> material;  // surfaces of different materials never mix
  std::vector<glm::vec3> value;    // demodulated irradiance, finite, >= 0
};

struct WaveletSettings {
  int levels = 2;                 // 1..kMaxWaveletLevels
  float sigma_luminance = 4.0f;   // luminance edge stop, in standard deviations of the pixel's estimate
  float depth_sigma = 0.05f;      // relative depth difference allowed per pixel of distance
};

// Writes inner.w * inner.h filtered values, row-major. Throws
// std::invalid_argument on a malformed input, settings out of range, an
// inner rect outside the region or a short `out`. Allocates its own scratch;
// safe to call concurrently.
void filter_wavelet(const WaveletInput& in, const WaveletSettings& s, Rect inner, std::span<glm::vec3> out);

// The levels pass k of a progressive render uses: all L for passes 0-2, then
// one fewer each time the pass count grows fourfold (L - 1 from pass 3, L - 2
// from 15, ...), down to none. The accumulated estimate's noise halves each
// fourfold, about what one level removes, so the filter steps aside as
// passes converge and they converge to the unfiltered (unblurred) mean.
int wavelet_levels_at_pass(int levels, uint32_t pass);

}  // namespace igi
