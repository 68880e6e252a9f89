// Shared-exponent display pixels (image/rgb9e5.h): the layout of GL_RGB9_E5,
// rounding to nearest, exact decoding, the range's ends, and every canonical
// word surviving a round trip, so that a tile re-encodes to its own bytes.
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "image/rgb9e5.h"

namespace igi {
namespace {

uint32_t word(uint32_t r, uint32_t g, uint32_t b, uint32_t e) { return r | g << 9 | b << 18 | e << 27; }

TEST(Rgb9e5, TheExtensionsLayoutAndRange) {
  EXPECT_EQ(to_rgb9e5({1.0f, 1.0f, 1.0f}), word(256, 256, 256, 16)) << "1 is 256 x 2^(16 - 15 - 9)";
  EXPECT_EQ(to_rgb9e5({1.0f, 0.5f, 0.0f}), word(256, 128, 0, 16));
  EXPECT_EQ(to_rgb9e5({0.0f, 0.0f, 0.0f}), 0u);
  EXPECT_EQ(to_rgb9e5({kRgb9e5Max, 0.0f, 0.0f}), word(511, 0, 0, 31));
  EXPECT_EQ(to_rgb9e5({1e30f, INFINITY, 70000.0f}), word(511, 511, 511, 31)) << "above the range: its top";
  EXPECT_EQ(to_rgb9e5({-1.0f, NAN, 2.0f}), to_rgb9e5({0.0f, 0.0f, 2.0f})) << "negatives and NaN: 0";
  EXPECT_EQ(from_rgb9e5(word(511, 0, 1, 31)), glm::vec3(kRgb9e5Max, 0.0f, 128.0f));
  EXPECT_EQ(from_rgb9e5(word(1, 0, 0, 0)), glm::vec3(std::ldexp(1.0f, -24), 0, 0)) << "the smallest step";
}

TEST(Rgb9e5, RoundsToTheNearestStepAndCarriesIntoTheExponent) {
  const float unit = std::ldexp(1.0f, -8);  // one step of the brightest channel in [1, 2)
  EXPECT_EQ(to_rgb9e5({1.0f + 0.49f * unit, 0, 0}), word(256, 0, 0, 16));
  EXPECT_EQ(to_rgb9e5({1.0f + 0.5f * unit, 0, 0}), word(257, 0, 0, 16)) << "half a step: up";
  EXPECT_EQ(to_rgb9e5({2.0f - 0.51f * unit, 0, 0}), word(511, 0, 0, 16));
  EXPECT_EQ(to_rgb9e5({2.0f - 0.5f * unit, 0, 0}), word(256, 0, 0, 17)) << "rounds up to 512: the next exponent";
  // A dim channel beside a bright one keeps the bright one's step.
  EXPECT_EQ(to_rgb9e5({1.0f, 0.3f * unit, 0.7f * unit}), word(256, 0, 1, 16));
  // Below the smallest exponent: steps of 2^-24, the brightest needs no 9th bit.
  EXPECT_EQ(to_rgb9e5({std::ldexp(3.0f, -24), 0, 0}), word(3, 0, 0, 0));
}

// The extension's encoding written out in doubles with libm, as its text reads.
uint32_t reference_rgb9e5(glm::vec3 c) {
  double v[3];
  for (int k = 0; k < 3; ++k) v[k] = c[k] > 0.0f ? std::min(double(c[k]), double(kRgb9e5Max)) : 0.0;
  const double top = std::max({v[0], v[1], v[2]});
  int e = std::max(-16, top > 0.0 ? int(std::floor(std::log2(top))) : -16) + 1 + 15;
  auto m = [](double x, int e) { return uint32_t(std::floor(x / std::exp2(e - 24) + 0.5)); };
  if (m(top, e) == 512) ++e;
  return m(v[0], e) | m(v[1], e) << 9 | m(v[2], e) << 18 | uint32_t(e) << 27;
}

TEST(Rgb9e5, EncodesAsTheExtensionsTextOverEveryFloatExponent) {
  std::mt19937 rng(17);
  for (int i = 0; i < 300000; ++i) {
    glm::vec3 c;
    for (int k = 0; k < 3; ++k) c[k] = std::bit_cast<float>(uint32_t(rng()) & (i % 2 ? 0xffffffffu : 0x4fffffffu));
    if (!std::isfinite(c.x) || !std::isfinite(c.y) || !std::isfinite(c.z)) continue;
    ASSERT_EQ(to_rgb9e5(c), reference_rgb9e5(c)) << c.x << " " << c.y << " " << c.z;
  }
}

TEST(Rgb9e5, EveryCanonicalWordDecodesExactlyAndEncodesBackToItself) {
  // Canonical: exponent 0, or a brightest mantissa of 256 or more (the encoder's words).
  std::mt19937 rng(9);
  int checked = 0;
  for (uint32_t e = 0; e < 32; ++e)
    for (uint32_t top = 0; top < 512; ++top) {
      if (e > 0 && top < 256) continue;
      for (int k = 0; k < 24; ++k) {
        uint32_t m[3] = {uint32_t(rng() % (top + 1)), uint32_t(rng() % (top + 1)), uint32_t(rng() % (top + 1))};
        m[k % 3] = top;
        const uint32_t w = word(m[0], m[1], m[2], e);
        ASSERT_EQ(to_rgb9e5(from_rgb9e5(w)), w) << std::hex << w;
        ++checked;
      }
    }
  EXPECT_GT(checked, 200000);
  // Not canonical (a smaller exponent holds it): the same colour, the canonical word.
  const uint32_t loose = word(128, 64, 0, 17);
  EXPECT_EQ(from_rgb9e5(to_rgb9e5(from_rgb9e5(loose))), from_rgb9e5(loose));
  EXPECT_EQ(to_rgb9e5(from_rgb9e5(loose)), word(256, 128, 0, 16));
}

TEST(Rgb9e5, ErrorsStayWithinHalfAStepOfTheBrightestChannel) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> exponent(-14.0f, 15.9f), share(0.0f, 1.0f);
  std::vector<float> in, out;
  for (int i = 0; i < 100000; ++i) {
    const float top = std::exp2(exponent(rng));
    float rgb[3] = {top * share(rng), top * share(rng) * share(rng), top * share(rng)};
    rgb[i % 3] = top;  // the brightest in each channel in turn
    in.insert(in.end(), rgb, rgb + 3);
  }
  const size_t n = in.size() / 3;
  std::vector<uint32_t> words(n);
  to_rgb9e5(in.data(), words.data(), n);
  out.resize(in.size());
  from_rgb9e5(words.data(), out.data(), n);
  double worst = 0.0;
  for (size_t i = 0; i < n; ++i) {
    const float top = std::max({in[3 * i], in[3 * i + 1], in[3 * i + 2]});
    ASSERT_EQ(words[i], to_rgb9e5(glm::vec3(in[3 * i], in[3 * i + 1], in[3 * i + 2]))) << "the bulk path";
    for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(double(out[3 * i + c]) - in[3 * i + c]) / top);
  }
  EXPECT_LE(worst, std::ldexp(1.0, -9)) << "half a step of 9 bits, relative to the pixel's brightest channel";
  EXPECT_GT(worst, std::ldexp(1.0, -10)) << "and the steps are that coarse (else the test measures nothing)";
}

}  // namespace
}  // namespace igi
