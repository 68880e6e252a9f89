#pragma once
// IEEE-754 binary16 ("half") <-> binary32, for display frames on the wire.
//
// to_half rounds to nearest, ties to even: the rounding of F16C's vcvtps2ph
// with _MM_FROUND_TO_NEAREST_INT, which the bulk conversion uses where the
// build has it. So a worker with F16C and one without give the same bits, and
// tiles stay bit-identical whatever machine renders them. Values of magnitude
// 65520 and more become infinity (callers that need finite halves clamp to
// kHalfMax first); NaN stays NaN. from_half is exact.
#include <cstddef>
#include <cstdint>

namespace igi {

inline constexpr float kHalfMax = 65504.0f;  // the largest finite half

uint16_t to_half(float value);
float from_half(uint16_t half);

// n values; F16C where the build targets it, else the scalar functions above (same bits).
void to_half(const float* in, uint16_t* out, size_t n);
void from_half(const uint16_t* in, float* out, size_t n);

// The scalar paths, whatever the build: tests compare them with the bulk ones.
void to_half_scalar(const float* in, uint16_t* out, size_t n);
void from_half_scalar(const uint16_t* in, float* out, size_t n);

}  // namespace igi
