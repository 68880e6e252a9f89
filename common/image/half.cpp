#include "image/half.h"

#include <bit>

#if defined(__F16C__)
#include <immintrin.h>
#endif

namespace igi {

// Bits of a float: sign 1, exponent 8 (bias 127), mantissa 23. Of a half:
// sign 1, exponent 5 (bias 15), mantissa 10. A half's exponent is the
// float's minus 112 (127 - 15).
uint16_t to_half(float value) {
  const uint32_t bits = std::bit_cast<uint32_t>(value);
  const uint16_t sign = uint16_t((bits >> 16) & 0x8000u);
  const uint32_t magnitude = bits & 0x7fffffffu;
  if (magnitude >= 0x7f800000u)  // infinity, or NaN (kept quiet, with what fits of its payload)
    return sign | 0x7c00u | (magnitude > 0x7f800000u ? 0x200u | ((magnitude >> 13) & 0x3ffu) : 0u);
  if (magnitude >= 0x477ff000u) return sign | 0x7c00u;  // >= 65520: rounds to infinity
  if (magnitude >= 0x38800000u) {                         // >= 2^-14: a normal half
    const uint32_t rebiased = magnitude - (112u << 23);
    // Drop 13 mantissa bits, ties to even; a carry may step the exponent up, which is right.
    return uint16_t(sign | ((rebiased + 0xfffu + ((rebiased >> 13) & 1u)) >> 13));
  }
  if (magnitude < 0x33000000u) return sign;  // below 2^-25 (half the smallest subnormal): zero
  // A subnormal half counts units of 2^-24: the 24-bit mantissa shifted right by 126 - exponent.
  const uint32_t exponent = magnitude >> 23;
  const uint32_t mantissa = (magnitude & 0x7fffffu) | 0x800000u;
  const uint32_t shift = 126u - exponent;  // 14 .. 24
  uint32_t units = mantissa >> shift;
  const uint32_t rest = mantissa & ((1u << shift) - 1u), halfway = 1u << (shift - 1u);
  if (rest > halfway || (rest == halfway && (units & 1u))) ++units;  // may become 0x400: the smallest normal
  return uint16_t(sign | units);
}

float from_half(uint16_t half) {
  const uint32_t sign = uint32_t(half & 0x8000u) << 16;
  const uint32_t exponent = (half >> 10) & 0x1fu, mantissa = half & 0x3ffu;
  if (exponent == 0) {  // zero or subnormal: mantissa x 2^-24, exact in float
    const float magnitude = float(mantissa) * 0x1p-24f;
    return std::bit_cast<float>(sign | std::bit_cast<uint32_t>(magnitude));
  }
  if (exponent == 31) return std::bit_cast<float>(sign | 0x7f800000u | (mantissa << 13));
  return std::bit_cast<float>(sign | ((exponent + 112u) << 23) | (mantissa << 13));
}

void to_half_scalar(const float* in, uint16_t* out, size_t n) {
  for (size_t i = 0; i < n; ++i) out[i] = to_half(in[i]);
}

void from_half_scalar(const uint16_t* in, float* out, size_t n) {
  for (size_t i = 0; i < n; ++i) out[i] = from_half(in[i]);
}

#if defined(__F16C__)

void to_half(const float* in, uint16_t* out, size_t n) {
  size_t i = 0;
  for (; i + 8 <= n; i += 8) {
    const __m128i h = _mm256_cvtps_ph(_mm256_loadu_ps(in + i), _MM_FROUND_TO_NEAREST_INT | _MM_FROUND_NO_EXC);
    _mm_storeu_si128(reinterpret_cast<__m128i*>(out + i), h);
  }
  to_half_scalar(in + i, out + i, n - i);
}

void from_half(const uint16_t* in, float* out, size_t n) {
  size_t i = 0;
  for (; i + 8 <= n; i += 8)
    _mm256_storeu_ps(out + i, _mm256_cvtph_ps(_mm_loadu_si128(reinterpret_cast<const __m128i*>(in + i))));
  from_half_scalar(in + i, out + i, n - i);
}

#else

void to_half(const float* in, uint16_t* out, size_t n) { to_half_scalar(in, out, n); }
void from_half(const uint16_t* in, float* out, size_t n) { from_half_scalar(in, out, n); }

#endif

}  // namespace igi
