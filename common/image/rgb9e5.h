#pragma once
// RGB9E5: three 9-bit mantissas sharing one 5-bit exponent in 32 bits, the
// layout of OpenGL's GL_RGB9_E5 (EXT_texture_shared_exponent) and DXGI's
// R9G9B9E5_SHAREDEXP: red in bits 0-8, green in 9-17, blue in 18-26, the
// exponent (bias 15) in 27-31. Display frames for slow links: linear HDR in 4
// bytes a pixel, so the window still accumulates and reprojects radiance and
// its exposure stays live. Each channel keeps 9 bits of the pixel's brightest
// one (a relative error below 2^-9 there, an absolute one below its 2^-10
// elsewhere), from 0 up to kRgb9e5Max.
//
// to_rgb9e5 is the extension's encoding, computed exactly (rounding half up,
// in double precision), so every machine gives the same bits. Negative values
// and NaN become 0, values above kRgb9e5Max (infinity too) kRgb9e5Max. It
// writes the canonical word of each colour (the smallest exponent that holds
// it); from_rgb9e5 takes any word, canonical or not, and is exact.
#include <cstddef>
#include <cstdint>

#include <glm/vec3.hpp>

namespace igi {

inline constexpr float kRgb9e5Max = 65408.0f;  // 511/512 x 2^16

uint32_t to_rgb9e5(glm::vec3 rgb);
glm::vec3 from_rgb9e5(uint32_t word);

// n pixels of 3 floats each.
void to_rgb9e5(const float* in, uint32_t* out, size_t n);
void from_rgb9e5(const uint32_t* in, float* out, size_t n);

}  // namespace igi
