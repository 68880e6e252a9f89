#include "image/rgb9e5.h"

#include <algorithm>
#include <bit>

namespace igi {
namespace {

constexpr int kMantissaBits = 9, kBias = 15;

float clamped(float v) { return v > 0.0f ? std::min(v, kRgb9e5Max) : 0.0f; }  // NaN: 0

// 2^k as a double and as a float, from the bits (no libm call); k within both's normal range.
double pow2d(int k) { return std::bit_cast<double>(uint64_t(1023 + k) << 52); }
float pow2f(int k) { return std::bit_cast<float>(uint32_t(127 + k) << 23); }

// floor(v 2^(kBias + kMantissaBits - exponent) + 0.5): the scaling and the
// addition are exact in double (v has 24 bits, the result stays below 2^10),
// and the conversion truncates, which is floor for a value >= 0.
uint32_t mantissa(float v, int exponent) {
  return uint32_t(double(v) * pow2d(kBias + kMantissaBits - exponent) + 0.5);
}

}  // namespace

uint32_t to_rgb9e5(glm::vec3 rgb) {
  const float r = clamped(rgb.x), g = clamped(rgb.y), b = clamped(rgb.z);
  const float brightest = std::max({r, g, b});
  // floor(log2(brightest)), at least -kBias - 1 (zero included): the float's
  // exponent field, exact for every normal float (smaller ones are below 2^-16 anyway).
  const int log2 = brightest >= pow2f(-kBias - 1) ? int(std::bit_cast<uint32_t>(brightest) >> 23) - 127 : -kBias - 1;
  int exponent = log2 + 1 + kBias;
  if (mantissa(brightest, exponent) == 1u << kMantissaBits) ++exponent;  // rounded up to the next power of two
  // kRgb9e5Max has mantissa 511 at exponent 31: no colour needs one beyond it.
  return mantissa(r, exponent) | mantissa(g, exponent) << 9 | mantissa(b, exponent) << 18 | uint32_t(exponent) << 27;
}

glm::vec3 from_rgb9e5(uint32_t word) {
  const float scale = pow2f(int(word >> 27) - kBias - kMantissaBits);  // exact: 9-bit mantissas
  return {float(word & 511u) * scale, float(word >> 9 & 511u) * scale, float(word >> 18 & 511u) * scale};
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
