// The sampler is addressable and stratified: values are pure functions of
// (index, dimension, seed), and every power-of-two prefix of each 2D
// projection is a (0,m,2)-net.
#include <algorithm>
#include <numeric>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "sampling/sobol.h"

namespace igi {
namespace {

TEST(Sampler, SecondSobolDimensionMatchesItsGeneratorMatrix) {
  // The byte tables must equal the XOR of columns v_0 = 2^31, v_{k+1} = v_k ^ (v_k >> 1).
  auto by_definition = [](uint32_t index) {
    uint32_t r = 0;
    for (uint32_t v = 1u << 31; index; index >>= 1, v ^= v >> 1)
      if (index & 1u) r ^= v;
    return r;
  };
  uint32_t x = 12345;
  for (int i = 0; i < 100000; ++i) {
    x = x * 1664525u + 1013904223u;
    ASSERT_EQ(sobol_dim1(x), by_definition(x));
    ASSERT_EQ(sobol_dim1(uint32_t(i)), by_definition(uint32_t(i)));
  }
  EXPECT_EQ(sobol_dim0(1), 1u << 31);
}

TEST(Sampler, ValuesAreInUnitInterval) {
  for (uint32_t i = 0; i < 4096; ++i)
    for (uint32_t d = 0; d < 8; ++d) {
      float v = sample_1d(i, d, 7);
      EXPECT_GE(v, 0.0f);
      EXPECT_LT(v, 1.0f);
    }
}

TEST(Sampler, RevisitingInAnotherOrderGivesTheSameValues) {
  struct Key { uint32_t index, dim, seed; };
  std::vector<Key> keys;
  for (uint32_t i = 0; i < 64; ++i)
    for (uint32_t d = 0; d < 12; ++d)
      for (uint32_t s : {0u, 1u, 0xdeadbeefu}) keys.push_back({i, d, s});
  std::vector<float> forward;
  for (const Key& k : keys) forward.push_back(sample_1d(k.index, k.dim, k.seed));
  std::vector<size_t> order(keys.size());
  std::iota(order.begin(), order.end(), 0);
  std::shuffle(order.begin(), order.end(), std::mt19937(42));
  for (size_t o : order) {
    const Key& k = keys[o];
    EXPECT_EQ(sample_1d(k.index, k.dim, k.seed), forward[o]);
  }
  // A stream walks the same dimensions.
  SampleStream stream(5, 1, 2);
  EXPECT_EQ(stream.next_2d(), sample_2d(5, 2, 1));
  EXPECT_EQ(stream.next_1d(), sample_1d(5, 4, 1));
}

// Every elementary interval [a/2^k, (a+1)/2^k) x [b/2^(m-k), (b+1)/2^(m-k))
// holds exactly one of the first 2^m points.
bool is_net(uint32_t m, uint32_t dim, uint32_t seed) {
  const uint32_t n = 1u << m;
  for (uint32_t k = 0; k <= m; ++k) {
    std::vector<int> count(n, 0);
    for (uint32_t i = 0; i < n; ++i) {
      glm::vec2 p = sample_2d(i, dim, seed);
      uint32_t cx = uint32_t(p.x * float(1u << k)), cy = uint32_t(p.y * float(1u << (m - k)));
      ++count[(cx << (m - k)) | cy];
    }
    if (std::any_of(count.begin(), count.end(), [](int c) { return c != 1; })) return false;
  }
  return true;
}

TEST(Sampler, PowerOfTwoPrefixesAreStratifiedIn2D) {
  for (uint32_t seed : {0u, 3u, 12345u})
    for (uint32_t dim : {0u, 2u, 10u, 40u})
      for (uint32_t m = 0; m <= 10; ++m) EXPECT_TRUE(is_net(m, dim, seed)) << "m=" << m << " dim=" << dim << " seed=" << seed;
}

TEST(Sampler, DifferentSeedsAndDimensionsDecorrelate) {
  // Pearson correlation between two dimension pairs and between two seeds.
  auto correlation = [](auto fa, auto fb) {
    const int n = 4096;
    double sa = 0, sb = 0, sab = 0, saa = 0, sbb = 0;
    for (int i = 0; i < n; ++i) {
      double a = fa(i), b = fb(i);
      sa += a; sb += b; sab += a * b; saa += a * a; sbb += b * b;
    }
    double cov = sab / n - sa / n * sb / n;
    return cov / std::sqrt((saa / n - sa * sa / n / n) * (sbb / n - sb * sb / n / n));
  };
  EXPECT_LT(std::abs(correlation([](int i) { return sample_1d(i, 0, 1); }, [](int i) { return sample_1d(i, 2, 1); })), 0.05);
  EXPECT_LT(std::abs(correlation([](int i) { return sample_1d(i, 0, 1); }, [](int i) { return sample_1d(i, 0, 2); })), 0.05);
}

TEST(Sampler, MeanConvergesFasterThanRandom) {
  // Integrating f(x, y) = x * y (exact 1/4) with 1024 stratified points is far
  // better than the ~1/sqrt(n) error of independent random points.
  double sum = 0;
  for (uint32_t i = 0; i < 1024; ++i) { glm::vec2 p = sample_2d(i, 4, 99); sum += p.x * p.y; }
  EXPECT_NEAR(sum / 1024, 0.25, 2e-4);
}

}  // namespace
}  // namespace igi
