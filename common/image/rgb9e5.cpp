#include "image/rgb9e5.h"

#include <algorithm>
#include <cmath>

namespace igi {
namespace {

constexpr int kMantissaBits = 9, kBias = 15;

double clamped(float v) { return v > 0.0f ? std::min(double(v), double(kRgb9e5Max)) : 0.0; }  // NaN: 0

uint32_t mantissa(double v, int exponent) {
  return uint32_t(std::floor(std::ldexp(v, kBias + kMantissaBits - exponent) + 0.5));
}

}  // namespace

uint32_t to_rgb9e5(glm::vec3 rgb) {
  const double r = clamped(rgb.x), g = clamped(rgb.y), b = clamped(rgb.z);
  const double brightest = std::max({r, g, b});
  // floor(log2(brightest)), at least -kBias - 1 (zero included).
  int log2 = -kBias - 1;
  if (brightest > 0.0) {
    int e;
    std::frexp(brightest, &e);  // brightest = f 2^e, f in [0.5, 1)
    log2 = std::max(log2, e - 1);
  }
  int exponent = log2 + 1 + kBias;
  if (mantissa(brightest, exponent) == 1u << kMantissaBits) ++exponent;  // rounded up to the next power of two
  // kRgb9e5Max has mantissa 511 at kMaxExponent: no colour needs an exponent beyond it.
  return mantissa(r, exponent) | mantissa(g, exponent) << 9 | mantissa(b, exponent) << 18 | uint32_t(exponent) << 27;
}

glm::vec3 from_rgb9e5(uint32_t word) {
  const int shift = int(word >> 27) - kBias - kMantissaBits;
  return {std::ldexp(float(word & 511u), shift), std::ldexp(float(word >> 9 & 511u), shift),
          std::ldexp(float(word >> 18 & 511u), shift)};
}

void to_rgb9e5(const float* in, uint32_t* out, size_t n) {
  for (size_t i = 0; i < n; ++i) out[i] = to_rgb9e5(glm::vec3(in[3 * i], in[3 * i + 1], in[3 * i + 2]));
}

void from_rgb9e5(const uint32_t* in, float* out, size_t n) {
  for (size_t i = 0; i < n; ++i) {
    const glm::vec3 v = from_rgb9e5(in[i]);
    out[3 * i] = v.x;
    out[3 * i + 1] = v.y;
    out[3 * i + 2] = v.z;
  }
}

}  // namespace igi
