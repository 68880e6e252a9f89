// FLIP (LDR): zero for identical images, grows with the perturbation, close
// to symmetric, near one for black against white, and blurs fine noise away
// when the viewer is further (more pixels per degree).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "image/flip.h"
#include "image/metrics.h"
#include "sampling/hash.h"

namespace igi {
namespace {

// A smooth sRGB gradient with a sharp-edged square: colour and features.
Image test_pattern(int w, int h) {
  Image image(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      glm::vec3 c(0.2f + 0.6f * float(x) / float(w), 0.3f + 0.4f * float(y) / float(h), 0.5f);
      if (x > w / 3 && x < 2 * w / 3 && y > h / 3 && y < 2 * h / 3) c = {0.9f, 0.8f, 0.2f};
      image.at(x, y) = c;
    }
  return image;
}

// Adds zero-mean uniform noise of the given amplitude, the same pattern at
// every amplitude (a deterministic hash of pixel and channel).
Image with_noise(const Image& image, float amplitude) {
  Image out = image;
  for (size_t i = 0; i < out.pixels.size(); ++i)
    for (int c = 0; c < 3; ++c) {
      const float u = float(hash(uint32_t(i), uint32_t(c)) >> 8) / float(1 << 24);
      out.pixels[i][c] = std::clamp(out.pixels[i][c] + amplitude * (2.0f * u - 1.0f), 0.0f, 1.0f);
    }
  return out;
}

TEST(Flip, IdenticalImagesGiveZero) {
  const Image a = test_pattern(64, 48);
  const FlipMap map = flip_ldr(a, a);
  for (float e : map.error) ASSERT_EQ(e, 0.0f);
  EXPECT_EQ(mean_flip(a, a), 0.0);
}

TEST(Flip, LargerPerturbationGivesLargerError) {
  const Image a = test_pattern(64, 48);
  const double small = flip_ldr(with_noise(a, 0.02f), a).mean();
  const double medium = flip_ldr(with_noise(a, 0.08f), a).mean();
  const double large = flip_ldr(with_noise(a, 0.3f), a).mean();
  std::printf("mean FLIP, noise +-0.02: %.4f, +-0.08: %.4f, +-0.3: %.4f\n", small, medium, large);
  EXPECT_GT(small, 0.0);
  EXPECT_LT(small, medium);
  EXPECT_LT(medium, large);
  EXPECT_LT(large, 1.0);
}

TEST(Flip, NearlySymmetric) {
  const Image a = test_pattern(64, 48), b = with_noise(a, 0.1f);
  const double ab = flip_ldr(b, a).mean(), ba = flip_ldr(a, b).mean();
  std::printf("FLIP(b, a) %.4f, FLIP(a, b) %.4f\n", ab, ba);
  EXPECT_NEAR(ab, ba, 0.15 * std::max(ab, ba));
}

TEST(Flip, BlackAgainstWhiteIsNearlyOne) {
  Image black(16, 16), white(16, 16);
  for (glm::vec3& p : white.pixels) p = glm::vec3(1.0f);
  // HyAB(black, white) = 100 against cmax = HyAB(green, blue): 0.967 by the remap.
  const double e = flip_ldr(black, white).mean();
  std::printf("FLIP black vs white: %.4f\n", e);
  EXPECT_NEAR(e, 0.967, 0.01);
}

TEST(Flip, FineNoiseFadesWithMorePixelsPerDegree) {
  const Image a = test_pattern(64, 48), b = with_noise(a, 0.1f);
  const double near = flip_ldr(b, a, 20.0f).mean(), far = flip_ldr(b, a, 200.0f).mean();
  std::printf("FLIP at 20 ppd %.4f, at 200 ppd %.4f\n", near, far);
  EXPECT_GT(near, far);
}

TEST(Flip, ErrorStaysWhereTheImagesDiffer) {
  const Image a = test_pattern(96, 64);
  Image b = a;
  for (int y = 5; y < 15; ++y)
    for (int x = 5; x < 15; ++x) b.at(x, y) = glm::vec3(0.0f);
  const FlipMap map = flip_ldr(b, a);
  EXPECT_GT(map.error[10 * 96 + 10], 0.3f) << "inside the change";
  EXPECT_EQ(map.error[50 * 96 + 80], 0.0f) << "far from the change";
}

// Against NVIDIA's reference implementation (flip-evaluator 1.7): image
// pairs and their mean LDR-FLIP at 67 ppd in tests/data/flip/golden.txt,
// made by make_flip_pairs.py there (noise, a 2-pixel shift, 15 % darker, a
// hue rotation, and an igi render against a pt reference).
TEST(Flip, MeanMatchesNvidiasReferenceImplementation) {
  const std::string dir = IGI_FLIP_DATA_DIR;
  std::ifstream golden(dir + "/golden.txt");
  ASSERT_TRUE(golden) << dir << "/golden.txt";
  int pairs = 0;
  for (std::string line; std::getline(golden, line);) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream fields(line);
    std::string reference, test;
    double expected = 0.0;
    ASSERT_TRUE(fields >> reference >> test >> expected) << line;
    // The PNGs hold sRGB values; read_image decodes them to linear.
    const Image ref = tonemap_for_flip(read_image(dir + "/" + reference));
    const Image img = tonemap_for_flip(read_image(dir + "/" + test));
    const double mean = flip_ldr(img, ref).mean();
    std::printf("%-16s against %-16s FLIP %.6f, reference implementation %.6f\n", test.c_str(), reference.c_str(),
                mean, expected);
    EXPECT_NEAR(mean, expected, 5e-4) << test << " against " << reference;
    ++pairs;
  }
  EXPECT_EQ(pairs, 6);
}

TEST(Flip, SizeMismatchIsAnError) {
  EXPECT_THROW(flip_ldr(Image(4, 4), Image(4, 5)), std::invalid_argument);
}

TEST(Flip, TonemapClampsAndEncodesSrgb) {
  Image linear(2, 1);
  linear.at(0, 0) = glm::vec3(4.0f);
  linear.at(1, 0) = glm::vec3(0.214f);
  const Image ldr = tonemap_for_flip(linear);
  EXPECT_FLOAT_EQ(ldr.at(0, 0).x, 1.0f);
  EXPECT_NEAR(ldr.at(1, 0).x, 0.5f, 0.01f);
}

// Two noisy references: the cross term cancels their noise, which rel_mse
// against either one adds to the figure.
TEST(RelMse, TwoIndependentReferencesCancelTheirOwnNoise) {
  const int w = 128, h = 128;
  Image truth(w, h), a(w, h), b(w, h), image(w, h);
  auto noise = [](uint32_t stream, size_t i, int c) {
    return float(hash(stream, uint32_t(i), uint32_t(c)) >> 8) / float(1 << 24) * 2.0f - 1.0f;
  };
  for (size_t i = 0; i < truth.pixels.size(); ++i)
    for (int c = 0; c < 3; ++c) {
      truth.pixels[i][c] = 0.5f;
      // References 7 % off per pixel (rms), about a 4096-spp pt render's noise on its noisier scenes.
      a.pixels[i][c] = 0.5f + 0.06f * noise(1, i, c);
      b.pixels[i][c] = 0.5f + 0.06f * noise(2, i, c);
      image.pixels[i][c] = 0.52f + 0.02f * noise(3, i, c);
    }
  const double exact = rel_mse(image, truth), one = rel_mse(image, a), two = rel_mse_two_references(image, a, b);
  std::printf("[relmse] against the truth %.5f, one noisy reference %.5f, two %.5f\n", exact, one, two);
  EXPECT_GT(one, 2.0 * exact) << "one reference adds its own noise";
  EXPECT_NEAR(two, exact, 0.1 * exact) << "two cancel it (the denominator keeps a little)";
  EXPECT_NEAR(rel_mse_two_references(truth, truth, truth), 0.0, 1e-12);
}

}  // namespace
}  // namespace igi
