// The discontinuity buffer against its definition: the constant-time filter
// matches the brute force on scenes with edges, takes the fast path where the
// surface is smooth, keeps edges sharp, cancels interleaved noise exactly,
// and gives bit-identical pixels however the image is cut into tiles.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <functional>
#include <limits>
#include <stdexcept>
#include <vector>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "filter/discontinuity_buffer.h"
#include "sampling/hash.h"

namespace igi {
namespace {

constexpr float kNoSurface = std::numeric_limits<float>::infinity();

// What a scene holds at an image pixel; scenes are functions of image
// coordinates, so any region of them can be cut out.
struct Sample {
  float depth;
  glm::vec3 normal;
  glm::vec3 value;
};
using Scene = std::function<Sample(int x, int y)>;

float uniform(int x, int y, uint32_t seed) { return float(hash(uint32_t(x), uint32_t(y), seed) >> 8) * 0x1p-24f; }

glm::vec3 noisy_value(int x, int y) {
  return glm::vec3(0.5f) + glm::vec3(uniform(x, y, 1), uniform(x, y, 2), uniform(x, y, 3));
}

const glm::vec3 kUp(0.0f, 0.0f, 1.0f);

// The region (x0, y0, w, h) of a scene.
FilterInput cut(const Scene& scene, int x0, int y0, int w, int h) {
  FilterInput in;
  in.x0 = x0, in.y0 = y0, in.width = w, in.height = h;
  for (int y = y0; y < y0 + h; ++y)
    for (int x = x0; x < x0 + w; ++x) {
      const Sample s = scene(x, y);
      in.depth.push_back(s.depth);
      in.normal.push_back(s.normal);
      in.value.push_back(s.value);
    }
  return in;
}

// --- Scenes, 48 x 40 unless said otherwise -----------------------------

// Two fronto-parallel planes at depths 4 and 8, the step at x = 20.
Sample depth_step(int x, int y) { return {x < 20 ? 4.0f : 8.0f, kUp, noisy_value(x, y)}; }

// Two planes meeting at x = 24 at an angle (cos 0.8 < 0.9), depth continuous.
Sample crease(int x, int y) {
  const glm::vec3 n = x < 24 ? kUp : glm::vec3(0.6f, 0.0f, 0.8f);
  return {6.0f + 0.01f * float(std::abs(x - 24)), n, noisy_value(x, y)};
}

// A disc of surface in front of background (no surface).
Sample disc(int x, int y) {
  const float dx = float(x) - 22.5f, dy = float(y) - 18.5f;
  if (dx * dx + dy * dy > 15.0f * 15.0f) return {kNoSurface, glm::vec3(0.0f), glm::vec3(0.2f, 0.3f, 0.4f)};
  return {5.0f, kUp, noisy_value(x, y)};
}

// A gently curved surface: depth and normal vary slowly, the value smoothly.
Sample smooth(int x, int y) {
  const float u = 0.07f * float(x), v = 0.05f * float(y);
  const glm::vec3 n = glm::normalize(glm::vec3(0.15f * std::sin(u), 0.15f * std::cos(v), 1.0f));
  return {5.0f + 0.3f * std::sin(u) * std::cos(v), n, glm::vec3(1.0f + 0.5f * std::sin(u + v))};
}

// Random depth jitter and normals, often incompatible with neighbours.
Sample rough(int x, int y) {
  const glm::vec3 n = glm::normalize(glm::vec3(uniform(x, y, 4) - 0.5f, uniform(x, y, 5) - 0.5f, 1.2f));
  return {5.0f + 0.6f * uniform(x, y, 6), n, noisy_value(x, y)};
}

// All of the above in one image: quadrants, a disc of background.
Sample combined(int x, int y) {
  const float dx = float(x) - 50.0f, dy = float(y) - 12.0f;
  if (dx * dx + dy * dy < 8.0f * 8.0f) return disc(1000, 1000);  // background
  if (y >= 30 && x >= 40) return rough(x, y);
  if (x < 25) return depth_step(x, y);
  if (y < 30) return smooth(x, y);
  return crease(x - 8, y);
}

// --- Helpers -------------------------------------------------------------

struct Tile {
  int x, y, w, h;
};

// Filters `tile` of an image_w x image_h image: the region is the tile
// grown by window / 2 on every side, clipped to the image, as the renderer cuts it.
using Filter = std::function<void(const FilterInput&, const FilterSettings&, Rect, std::span<glm::vec3>)>;

std::vector<glm::vec3> filter_tile(const Filter& filter, const Scene& scene, int image_w, int image_h, Tile tile,
                                   const FilterSettings& s) {
  const int r = s.window / 2;
  const int x0 = std::max(tile.x - r, 0), y0 = std::max(tile.y - r, 0);
  const int x1 = std::min(tile.x + tile.w + r, image_w), y1 = std::min(tile.y + tile.h + r, image_h);
  const FilterInput in = cut(scene, x0, y0, x1 - x0, y1 - y0);
  std::vector<glm::vec3> out(size_t(tile.w) * tile.h);
  filter(in, s, Rect{tile.x, tile.y, tile.w, tile.h}, out);
  return out;
}

Filter fast(FilterStats* stats = nullptr) {
  return [stats](const FilterInput& in, const FilterSettings& s, Rect inner, std::span<glm::vec3> out) {
    filter_discontinuity(in, s, inner, out, stats);
  };
}
const Filter brute = filter_brute_force;

FilterSettings with_window(int n) {
  FilterSettings s;
  s.window = n;
  return s;
}

// |a - b| <= 1e-5 |b| + one fixed-point quantum, per channel.
::testing::AssertionResult agree(const std::vector<glm::vec3>& fast_out, const std::vector<glm::vec3>& reference,
                                 double fixed_scale) {
  for (size_t i = 0; i < reference.size(); ++i)
    for (int c = 0; c < 3; ++c) {
      const double a = fast_out[i][c], b = reference[i][c];
      if (std::abs(a - b) > 1e-5 * std::abs(b) + 1.0 / fixed_scale)
        return ::testing::AssertionFailure() << "pixel " << i << " channel " << c << ": fast " << a
                                             << ", brute force " << b;
    }
  return ::testing::AssertionSuccess();
}

// --- Tests ---------------------------------------------------------------

TEST(DiscontinuityBuffer, FastMatchesBruteForceOnScenesWithEdges) {
  const struct {
    const char* name;
    Scene scene;
  } scenes[] = {{"depth step", depth_step}, {"crease", crease}, {"disc on background", disc},
                {"smooth", smooth},         {"rough", rough},   {"combined", combined}};
  // The whole image (every window clipped somewhere), tiles at the corners
  // (clipped on two sides) and one inside.
  const Tile tiles[] = {{0, 0, 48, 40}, {0, 0, 16, 16}, {13, 9, 20, 17}, {30, 25, 18, 15}, {0, 20, 9, 20}};
  for (const auto& [name, scene] : scenes)
    for (int n = 1; n <= 9; ++n)
      for (const Tile& tile : tiles) {
        SCOPED_TRACE(::testing::Message() << name << ", window " << n << ", tile at " << tile.x << "," << tile.y);
        const FilterSettings s = with_window(n);
        FilterStats stats;
        const auto out = filter_tile(fast(&stats), scene, 48, 40, tile, s);
        EXPECT_TRUE(agree(out, filter_tile(brute, scene, 48, 40, tile, s), s.fixed_scale));
        EXPECT_EQ(stats.fast_pixels + stats.exact_pixels, uint64_t(tile.w) * tile.h);
      }
}

TEST(DiscontinuityBuffer, FastMatchesBruteForceWithAFrameScale) {
  // Large values with the scale chosen for them: quanta stay relative.
  const Scene bright = [](int x, int y) {
    Sample s = combined(x, y);
    s.value *= 3.0e6f;
    return s;
  };
  for (int n = 2; n <= 9; ++n) {
    FilterSettings s = with_window(n);
    s.fixed_scale = filter_fixed_scale(3.0e6);
    const Tile all{0, 0, 70, 52};
    const auto out = filter_tile(fast(), bright, 70, 52, all, s);
    EXPECT_TRUE(agree(out, filter_tile(brute, bright, 70, 52, all, s), s.fixed_scale)) << "window " << n;
  }
}

TEST(DiscontinuityBuffer, FastPathIsTakenOnAPlaneAndExactPathAtEdges) {
  const Scene plane = [](int x, int y) {
    return Sample{5.0f + 0.01f * float(x) + 0.02f * float(y), kUp, noisy_value(x, y)};
  };
  const Scene step = [](int x, int y) { return Sample{x < 32 ? 4.0f : 8.0f, kUp, noisy_value(x, y)}; };
  for (int n = 2; n <= 9; ++n) {
    const int a = n / 2, b = n - 1 - a;  // the window's reach before and after a pixel
    FilterStats stats;
    filter_tile(fast(&stats), plane, 64, 48, {0, 0, 64, 48}, with_window(n));
    EXPECT_GT(double(stats.fast_pixels), 0.9 * 64 * 48) << "window " << n;
    // Exactly the n - 1 columns whose windows straddle the step need the
    // exact path, and there the result is the brute force's, bit for bit.
    const auto out = filter_tile(fast(&stats), step, 64, 48, {0, 0, 64, 48}, with_window(n));
    EXPECT_EQ(stats.exact_pixels, uint64_t((n - 1) * 48)) << "window " << n;
    EXPECT_EQ(stats.fast_pixels, uint64_t((64 - (n - 1)) * 48)) << "window " << n;
    const auto reference = filter_tile(brute, step, 64, 48, {0, 0, 64, 48}, with_window(n));
    for (int y = 0; y < 48; ++y)
      for (int x = 32 - b; x < 32 + a; ++x) ASSERT_EQ(out[size_t(y) * 64 + x], reference[size_t(y) * 64 + x]);
  }
}

TEST(DiscontinuityBuffer, StepBetweenPlanesStaysSharp) {
  // Interleaved noise of the N x N VPL sets whose every column sums to
  // zero, so any window spanning N rows averages it away, however many of
  // its columns lie on this side of the step.
  for (int n = 2; n <= 6; ++n) {
    const int a = n / 2, b = n - 1 - a;
    const Scene step = [n](int x, int y) {
      const float noise = 0.1f * (float(y % n) - 0.5f * float(n - 1)) * float(1 + x % n);
      return Sample{x < 20 ? 4.0f : 8.0f, kUp, glm::vec3((x < 20 ? 1.0f : 5.0f) + noise)};
    };
    for (const Filter& filter : {fast(), brute}) {
      const auto out = filter_tile(filter, step, 40, 30, {0, 0, 40, 30}, with_window(n));
      for (int y = a; y < 30 - b; ++y)
        for (int x = 0; x < 40; ++x) {
          const float side_mean = x < 20 ? 1.0f : 5.0f;
          const glm::vec3 v = out[size_t(y) * 40 + x];
          for (int c = 0; c < 3; ++c)
            ASSERT_NEAR(v[c], side_mean, 1e-5 * side_mean) << "window " << n << " at " << x << "," << y;
        }
    }
  }
}

TEST(DiscontinuityBuffer, InterleavedNoiseOnAPlaneBecomesFlat) {
  // value = base + noise(x mod N, y mod N), the N^2 noise values summing to
  // 0: every whole window holds each set once, even N included (a window of
  // 2 floor(N/2) + 1 held a row and a column of sets twice, a grid of
  // period N).
  for (int n : {2, 3, 4, 5, 6, 8}) {
    std::vector<float> noise(size_t(n) * n);
    float total = 0.0f;
    for (int i = 0; i + 1 < n * n; ++i) total += noise[i] = 0.8f * (uniform(i, 0, 7) - 0.5f);
    noise.back() = -total;
    const glm::vec3 base(1.0f, 2.0f, 0.5f);
    const Scene plane = [&](int x, int y) { return Sample{5.0f, kUp, base + noise[(y % n) * n + x % n]}; };
    const FilterSettings s = with_window(n);
    FilterStats stats;
    const auto out = filter_tile(fast(&stats), plane, 30, 30, {0, 0, 30, 30}, s);
    EXPECT_EQ(stats.exact_pixels, 0u);
    const int a = n / 2, b = n - 1 - a;
    for (int y = a; y < 30 - b; ++y)  // windows not clipped by the image
      for (int x = a; x < 30 - b; ++x)
        for (int c = 0; c < 3; ++c)
          ASSERT_NEAR(out[size_t(y) * 30 + x][c], base[c], 1e-6 * base[c] + 1.0 / s.fixed_scale)
              << "window " << n << " at " << x << "," << y;
  }
}

TEST(DiscontinuityBuffer, TilesOfAnySizeGiveBitIdenticalPixels) {
  const int w = 70, h = 52;
  for (int n = 2; n <= 7; ++n) {
    const FilterSettings s = with_window(n);
    FilterStats stats;
    const std::vector<glm::vec3> whole = filter_tile(fast(&stats), combined, w, h, {0, 0, w, h}, s);
    ASSERT_GT(stats.fast_pixels, 0u);
    ASSERT_GT(stats.exact_pixels, 0u);
    // Tilings of different tile sizes, the first row and column of tiles cut short.
    const Tile tilings[] = {{0, 0, 16, 16}, {5, 3, 23, 11}, {2, 9, 7, 30}, {0, 0, 41, 52}};
    for (const Tile& t : tilings) {
      std::vector<glm::vec3> assembled(whole.size(), glm::vec3(-1.0f));
      for (int ty = -t.y; ty < h; ty += t.h)
        for (int tx = -t.x; tx < w; tx += t.w) {
          const Tile tile{std::max(tx, 0), std::max(ty, 0), std::min(tx + t.w, w) - std::max(tx, 0),
                          std::min(ty + t.h, h) - std::max(ty, 0)};
          const auto out = filter_tile(fast(), combined, w, h, tile, s);
          for (int y = 0; y < tile.h; ++y)
            std::copy_n(&out[size_t(y) * tile.w], tile.w, &assembled[size_t(tile.y + y) * w + tile.x]);
        }
      EXPECT_EQ(std::memcmp(assembled.data(), whole.data(), whole.size() * sizeof(glm::vec3)), 0)
          << "window " << n << ", tiles " << t.w << "x" << t.h;
    }
  }
}

TEST(DiscontinuityBuffer, PixelsWithoutSurfaceAreCopied) {
  const Tile all{0, 0, 48, 40};
  for (const Filter& filter : {fast(), brute}) {
    const auto out = filter_tile(filter, disc, 48, 40, all, with_window(5));
    for (int y = 0; y < 40; ++y)
      for (int x = 0; x < 48; ++x)
        if (disc(x, y).depth == kNoSurface) {
          ASSERT_EQ(out[size_t(y) * 48 + x], disc(x, y).value) << x << "," << y;
        }
  }
}

TEST(DiscontinuityBuffer, PixelAlwaysCountsItselfUnderStrictThresholds) {
  // With normal_cos = 1 no two distinct random normals agree, and rounding
  // puts dot(n_p, n_p) below 1 for many; p must still average over itself.
  FilterSettings s = with_window(5);
  s.normal_cos = 1.0f;
  s.depth_ratio = 0.0f;
  int self_dot_below_one = 0;
  for (int y = 0; y < 20; ++y)
    for (int x = 0; x < 20; ++x) {
      const glm::vec3 n = rough(x, y).normal;
      self_dot_below_one += n.x * n.x + n.y * n.y + n.z * n.z < 1.0f;
    }
  ASSERT_GT(self_dot_below_one, 0);
  for (const Filter& filter : {fast(), brute}) {
    const auto out = filter_tile(filter, rough, 20, 20, {0, 0, 20, 20}, s);
    for (int y = 0; y < 20; ++y)
      for (int x = 0; x < 20; ++x) ASSERT_EQ(out[size_t(y) * 20 + x], rough(x, y).value) << x << "," << y;
  }
}

TEST(DiscontinuityBuffer, FastPathRoundsValuesToTheNearestQuantum) {
  // With fixed_scale 4 the quantum is 0.25: a constant value v comes out as
  // llround(4 v) / 4 (halves away from zero).
  const struct {
    float value, quantised;
  } cases[] = {{0.3f, 0.25f}, {0.4f, 0.5f}, {0.375f, 0.5f}, {0.6f, 0.5f}, {2.0f, 2.0f}};
  for (const auto& c : cases) {
    const float value = c.value, quantised = c.quantised;
    const Scene plane = [value](int, int) { return Sample{5.0f, kUp, glm::vec3(value)}; };
    FilterSettings s = with_window(3);
    s.fixed_scale = 4.0;
    FilterStats stats;
    const auto out = filter_tile(fast(&stats), plane, 8, 8, {0, 0, 8, 8}, s);
    EXPECT_EQ(stats.fast_pixels, 64u);
    for (const glm::vec3& v : out) ASSERT_EQ(v, glm::vec3(quantised)) << "value " << value;
  }
}

TEST(DiscontinuityBuffer, FixedScaleKeeps24BitsOfATypicalValue) {
  EXPECT_EQ(filter_fixed_scale(1.0), 0x1p24);
  EXPECT_EQ(filter_fixed_scale(3.0), 0x1p22);  // log2 3 = 1.58 rounds to 2
  EXPECT_EQ(filter_fixed_scale(0.1), 0x1p27);  // log2 0.1 = -3.32 rounds to -3
  EXPECT_EQ(filter_fixed_scale(1e-30), 0x1p64);
  EXPECT_EQ(filter_fixed_scale(1e30), 0x1p-32);
  EXPECT_EQ(filter_fixed_scale(0.0), 0x1p32);
  EXPECT_EQ(filter_fixed_scale(std::nan("")), 0x1p32);
}

TEST(DiscontinuityBuffer, RejectsMalformedArguments) {
  const FilterInput in = cut(smooth, 10, 10, 8, 8);
  std::vector<glm::vec3> out(64);
  const FilterSettings s;
  EXPECT_THROW(filter_discontinuity(in, s, Rect{9, 10, 8, 8}, out), std::invalid_argument);   // outside
  EXPECT_THROW(filter_discontinuity(in, s, Rect{10, 10, 8, 9}, out), std::invalid_argument);  // too tall
  EXPECT_THROW(filter_brute_force(in, s, Rect{10, 10, 8, 8}, std::span(out).first(63)), std::invalid_argument);
  FilterInput short_depth = in;
  short_depth.depth.pop_back();
  EXPECT_THROW(filter_discontinuity(short_depth, s, Rect{10, 10, 8, 8}, out), std::invalid_argument);
  EXPECT_NO_THROW(filter_discontinuity(in, s, Rect{12, 11, 3, 4}, out));
}

// The hand-over: full weight for the first K passes, then sqrt(K / (k + 1)),
// so the mean weight over n passes, the blur the mean carries, falls as
// 1 / sqrt(n) and its square as 1 / n.
TEST(FilterHandover, TheFirstPassesAreFilteredInFullAndTheBlurVanishesAfter) {
  const uint32_t k_full = kFilterFullPasses;
  for (uint32_t k = 0; k < k_full; ++k) EXPECT_EQ(filter_weight_at_pass(k), 1.0f) << "pass " << k;
  for (uint32_t k = k_full; k < 4096; ++k) {
    EXPECT_LT(filter_weight_at_pass(k), filter_weight_at_pass(k - 1)) << "pass " << k;
    EXPECT_NEAR(filter_weight_at_pass(k), std::sqrt(double(k_full) / (k + 1.0)), 1e-6);
  }
  auto mean_weight = [](uint32_t n) {
    double sum = 0.0;
    for (uint32_t k = 0; k < n; ++k) sum += filter_weight_at_pass(k);
    return sum / n;
  };
  EXPECT_EQ(mean_weight(k_full), 1.0);
  EXPECT_LT(mean_weight(16 * k_full), 0.5);
  EXPECT_NEAR(mean_weight(1024 * k_full) * std::sqrt(1024.0), 2.0, 0.1) << "~ 2 sqrt(K / n)";
}

// One interleaved set's lattice (every 4th pixel each way, 4 x 4 sets), its
// values a ramp in x: one box of the window holds one lattice pixel, so it
// repeats each over a 4 x 4 square (steps of 4 x the ramp's slope every 4
// pixels: the blocks a first pass showed); the tent, the box twice, rebuilds
// the ramp linearly (a step of the slope at every pixel) and keeps its mean.
// Its second pass reads the first's over twice the window's reach: tiles cut
// as the renderer cuts them agree bit for bit.
TEST(DiscontinuityBuffer, TheTentRebuildsOneSetsLatticeLinearly) {
  constexpr int kSets = 4;
  constexpr float kSlope = 0.01f;
  const Scene lattice = [](int x, int y) {
    const bool on = x % kSets == 0 && y % kSets == 0;
    return Sample{5.0f, kUp, glm::vec3(on ? float(kSets * kSets) * (0.5f + kSlope * float(x)) : 0.0f)};
  };
  FilterSettings fs;
  fs.window = kSets;
  const FilterInput in = cut(lattice, 0, 0, 48, 40);
  const Rect inner{8, 8, 32, 24};
  std::vector<glm::vec3> box(size_t(inner.w) * inner.h), tent(box.size());
  filter_discontinuity(in, fs, inner, box);
  filter_tent(in, fs, inner, tent);
  float box_step = 0.0f, tent_error = 0.0f;
  for (int y = 0; y < inner.h; ++y)
    for (int x = 1; x < inner.w; ++x) {
      const size_t i = size_t(y) * inner.w + x;
      box_step = std::max(box_step, box[i].x - box[i - 1].x);
      tent_error = std::max(tent_error, std::abs(tent[i].x - tent[i - 1].x - kSlope));
      EXPECT_FLOAT_EQ(tent[i].x, tent[size_t(x)].x) << "row " << y;  // flat in y
    }
  EXPECT_NEAR(box_step, kSets * kSlope, 1e-4f);
  EXPECT_LT(tent_error, 1e-4f);
  // Tiles with the renderer's border (two reaches) give the whole's pixels.
  const int border = 2 * (kSets / 2);
  for (const Tile t : {Tile{8, 8, 5, 7}, Tile{13, 8, 27, 24}, Tile{8, 15, 32, 17}}) {
    const FilterInput region = cut(lattice, t.x - border, t.y - border, t.w + 2 * border, t.h + 2 * border);
    std::vector<glm::vec3> part(size_t(t.w) * t.h);
    filter_tent(region, fs, Rect{t.x, t.y, t.w, t.h}, part);
    for (int y = 0; y < t.h; ++y)
      for (int x = 0; x < t.w; ++x) {
        const size_t whole = size_t(t.y - inner.y + y) * inner.w + size_t(t.x - inner.x + x);
        ASSERT_EQ(0, std::memcmp(&part[size_t(y) * t.w + x], &tent[whole], sizeof(glm::vec3)));
      }
  }
}

// The hand-over on a plane with a depth step, noisy values and one spike:
// w F(u - h) + (1 - w)(u - h) + F(h), F the tent, checked against the tent
// called on the parts; no spikes gives the plain blend; weight 1 is the tent
// bit for bit; the spike's excess is spread, not dropped; tiles agree bit for bit.
TEST(FilterHandover, BlendsTheLowerPartAndKeepsTheSpikesFiltered) {
  const int kSpikeX = 13, kSpikeY = 17;
  const Scene scene = [&](int x, int y) {
    Sample s = depth_step(x, y);
    if (x == kSpikeX && y == kSpikeY) s.value = glm::vec3(40.0f, 1.0f, 25.0f);
    return s;
  };
  const FilterInput in = cut(scene, 0, 0, 48, 40);
  FilterSettings fs;
  fs.window = 6;
  const Rect inner{3, 3, 42, 34};
  const size_t n = size_t(inner.w) * inner.h;
  auto run = [&](const FilterInput& input, float w, float level) {
    std::vector<glm::vec3> out(n);
    filter_handed_over(input, fs, inner, w, level, out);
    return out;
  };
  auto filtered = [&](const FilterInput& input) {
    std::vector<glm::vec3> out(n);
    filter_tent(input, fs, inner, out);
    return out;
  };
  auto at = [&](const FilterInput& input, size_t i) {
    return input.value[size_t(inner.y + int(i) / inner.w) * input.width + size_t(inner.x + int(i) % inner.w)];
  };
  // Weight 1: the tent itself.
  const std::vector<glm::vec3> full = filtered(in), one = run(in, 1.0f, 2.0f);
  EXPECT_EQ(0, std::memcmp(full.data(), one.data(), n * sizeof(glm::vec3)));
  // A level above every value: the plain blend.
  const std::vector<glm::vec3> plain = run(in, 0.25f, INFINITY);
  for (size_t i = 0; i < n; ++i)
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(plain[i][c], 0.25f * full[i][c] + 0.75f * at(in, i)[c], 1e-5f);
  // Level 2: the values of the plane lie in [0.5, 1.5], the spike's red and blue above.
  FilterInput low = in, high = in;
  for (size_t p = 0; p < in.value.size(); ++p)
    for (int c = 0; c < 3; ++c) {
      high.value[p][c] = std::max(in.value[p][c] - 2.0f, 0.0f);
      low.value[p][c] = in.value[p][c] - high.value[p][c];
    }
  const std::vector<glm::vec3> split = run(in, 0.25f, 2.0f), f_low = filtered(low), f_high = filtered(high);
  double out_sum = 0.0, in_sum = 0.0;
  for (size_t i = 0; i < n; ++i) {
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(split[i][c], 0.25f * f_low[i][c] + 0.75f * at(low, i)[c] + f_high[i][c], 1e-5f) << i;
    out_sum += split[i].x;
    in_sum += at(in, i).x;
  }
  const size_t spike = size_t(kSpikeY - inner.y) * inner.w + size_t(kSpikeX - inner.x);
  EXPECT_LT(split[spike].x, 3.0f) << "the spike is spread over its window, not handed over whole";
  EXPECT_GT(split[spike - 1].x, 1.5f) << "its neighbours take their share";
  EXPECT_NEAR(out_sum, in_sum, 0.01 * in_sum) << "spread, not dropped";
  EXPECT_EQ(in.value[size_t(kSpikeY) * in.width + kSpikeX].x, 40.0f) << "the input is left as it was";
  // Tiles: the same pixels from a region cut elsewhere.
  const FilterInput other = cut(scene, 2, 5, 36, 26);  // the tent's border: two reaches of the window
  const Rect part{8, 11, 24, 14};
  std::vector<glm::vec3> tile(size_t(part.w) * part.h);
  filter_handed_over(other, fs, part, 0.25f, 2.0f, tile);
  for (int y = 0; y < part.h; ++y)
    for (int x = 0; x < part.w; ++x) {
      const glm::vec3 a = tile[size_t(y) * part.w + x];
      const glm::vec3 b = split[size_t(part.y - inner.y + y) * inner.w + size_t(part.x - inner.x + x)];
      ASSERT_EQ(0, std::memcmp(&a, &b, sizeof a)) << "pixel " << part.x + x << ", " << part.y + y;
    }
}

}  // namespace
}  // namespace igi
