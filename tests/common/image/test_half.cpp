// Half floats on the wire: rounding to nearest even, exact widening, and the
// same bits from the F16C path (where the build has it) as from the scalar one,
// so tiles stay bit-identical on workers with and without F16C.
#include <bit>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "image/half.h"
#include "scene/accel.h"

namespace igi {
namespace {

bool is_nan_half(uint16_t h) { return (h & 0x7c00u) == 0x7c00u && (h & 0x3ffu) != 0; }

TEST(Half, EveryHalfWidensExactlyAndNarrowsBackToItself) {
  for (uint32_t h = 0; h < 0x10000u; ++h) {
    if (is_nan_half(uint16_t(h))) continue;
    EXPECT_EQ(to_half(from_half(uint16_t(h))), h) << std::hex << h;
  }
  EXPECT_EQ(from_half(0x3c00), 1.0f);
  EXPECT_EQ(from_half(0x7bff), kHalfMax);
  EXPECT_EQ(from_half(0x0001), std::ldexp(1.0f, -24)) << "the smallest subnormal";
  EXPECT_TRUE(std::isinf(from_half(0x7c00)));
  EXPECT_TRUE(std::isnan(from_half(0x7e00)));
}

TEST(Half, RoundsToNearestTiesToEven) {
  EXPECT_EQ(to_half(1.0f), 0x3c00);
  EXPECT_EQ(to_half(1.0f + std::ldexp(1.0f, -11)), 0x3c00) << "a tie goes to the even mantissa";
  EXPECT_EQ(to_half(1.0f + 3 * std::ldexp(1.0f, -11)), 0x3c02) << "a tie goes to the even mantissa, up";
  EXPECT_EQ(to_half(1.0f + std::ldexp(1.0f, -11) + std::ldexp(1.0f, -20)), 0x3c01) << "above the tie: up";
  EXPECT_EQ(to_half(65519.0f), 0x7bff) << "below 65520 rounds to 65504";
  EXPECT_EQ(to_half(65520.0f), 0x7c00) << "65520 is a tie with 65536: even, which is infinity";
  EXPECT_EQ(to_half(std::ldexp(1.0f, -25)), 0x0000) << "half the smallest subnormal: a tie, to zero";
  EXPECT_EQ(to_half(std::nextafter(std::ldexp(1.0f, -25), 1.0f)), 0x0001);
  EXPECT_EQ(to_half(3 * std::ldexp(1.0f, -25)), 0x0002) << "1.5 units: a tie, to the even 2";
  EXPECT_EQ(to_half(std::ldexp(1.0f, -14)), 0x0400) << "the smallest normal";
  EXPECT_EQ(to_half(std::ldexp(1023.5f, -24)), 0x0400) << "a subnormal rounding up into the normals";
  EXPECT_EQ(to_half(-0.0f), 0x8000);
  EXPECT_EQ(to_half(-2.5f), 0xc100);
  EXPECT_EQ(to_half(INFINITY), 0x7c00);
}

// Floats spread over every exponent a half can hold and beyond, signs both ways.
std::vector<float> probe_floats() {
  std::vector<float> values;
  std::mt19937 rng(12);  // 32-bit draws
  for (int i = 0; i < 200000; ++i) {
    const uint32_t exponent = 90 + rng() % 60;  // 2^-37 .. 2^22
    values.push_back(std::bit_cast<float>(uint32_t((rng() & 0x807fffffu) | exponent << 23)));
  }
  for (uint32_t h = 0; h < 0x7c00u; ++h) {  // every half and the exact midpoints between neighbours
    const float a = from_half(uint16_t(h)), b = from_half(uint16_t(h + 1));
    values.insert(values.end(), {a, -a, 0.5f * (a + b), std::nextafter(0.5f * (a + b), 0.0f)});
  }
  return values;
}

TEST(Half, TheBulkPathGivesTheScalarBitsWithFlushToZeroOn) {
  enable_flush_to_zero();  // as render threads run
  const std::vector<float> values = probe_floats();
  std::vector<uint16_t> bulk(values.size()), scalar(values.size());
  to_half(values.data(), bulk.data(), values.size());
  to_half_scalar(values.data(), scalar.data(), values.size());
  size_t differ = 0;
  for (size_t i = 0; i < values.size(); ++i) differ += bulk[i] != scalar[i];
  EXPECT_EQ(differ, 0u);
  std::vector<uint16_t> every(0x10000);
  for (uint32_t h = 0; h < 0x10000u; ++h) every[h] = uint16_t(h);
  std::vector<float> wide(every.size()), wide_scalar(every.size());
  from_half(every.data(), wide.data(), every.size());
  from_half_scalar(every.data(), wide_scalar.data(), every.size());
  for (uint32_t h = 0; h < 0x10000u; ++h) {
    if (is_nan_half(uint16_t(h))) continue;
    EXPECT_EQ(std::bit_cast<uint32_t>(wide[h]), std::bit_cast<uint32_t>(wide_scalar[h])) << h;
  }
}

}  // namespace
}  // namespace igi
