// A pixel's random numbers are addressed, not drawn from a state
// (common/sampling/pixel_samples.h): pbrt's ConsistentValues test, here.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <random>
#include <set>
#include <tuple>
#include <vector>

#include "sampling/pixel_samples.h"

namespace igi {
namespace {

// (x, y, sequence, sample index, dimension)
using Address = std::tuple<int, int, uint32_t, uint32_t, uint32_t>;

glm::vec2 value_at(const PixelSamples& p, const Address& a) {
  const auto [x, y, s, index, dimension] = a;
  return sample_2d(index, dimension, s == 0 ? p.pixel(x, y) : p.sequence(x, y, s));
}

// Every address visited pixel by pixel, then again in a shuffled order by
// another PixelSamples of the same seed: the same value at every address.
TEST(PixelSamples, ConsistentValuesInAnyOrder) {
  std::vector<Address> addresses;
  for (int y = -2; y < 6; ++y)
    for (int x = 0; x < 8; ++x)
      for (uint32_t s = 0; s < 3; ++s)
        for (uint32_t index = 0; index < 8; ++index)
          for (uint32_t dimension = 0; dimension < 8; dimension += 2) addresses.emplace_back(x, y, s, index, dimension);
  const PixelSamples first{12345u};
  std::map<Address, glm::vec2> seen;
  for (const Address& a : addresses) seen[a] = value_at(first, a);
  std::mt19937 shuffle(7);
  std::shuffle(addresses.begin(), addresses.end(), shuffle);
  const PixelSamples again{12345u};
  for (const Address& a : addresses) ASSERT_EQ(value_at(again, a), seen.at(a));
  EXPECT_EQ(again.sample_2d(3, 4, 5, 2), sample_2d(5, 2, first.pixel(3, 4)));
}

// Pixels, their sequences, tags and frame seeds lead to different seeds: no
// two pixels of a 64 x 64 image, nor two sequences of one, share their numbers.
TEST(PixelSamples, EveryPixelAndSequenceHasItsOwnSeed) {
  std::set<uint32_t> seeds;
  size_t count = 0;
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x) {
      const PixelSamples p{99u};
      for (uint32_t seed : {p.pixel(x, y), p.sequence(x, y, 0), p.sequence(x, y, 1), p.sequence(x, y, 1, 0x676c6f73u),
                            p.drawn(x, y, 0)}) {
        seeds.insert(seed);
        ++count;
      }
    }
  EXPECT_GE(seeds.size(), count - 4) << "a few 32-bit collisions at most";
  EXPECT_NE(PixelSamples{1u}.pixel(5, 5), PixelSamples{2u}.pixel(5, 5));
  EXPECT_NE(PixelSamples{1u}.pixel(5, 6), PixelSamples{1u}.pixel(6, 5)) << "x and y are not interchangeable";
}

}  // namespace
}  // namespace igi
