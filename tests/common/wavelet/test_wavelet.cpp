// The edge-avoiding wavelet filter (common/wavelet/): its definition on
// synthetic regions, and igi / ir with --wavelet whole, tiled and at
// progressive passes.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <stdexcept>

#include "scene/load_scene.h"
#include "support/image_compare.h"
#include "support/render_fixture.h"
#include "wavelet/wavelet_filter.h"

namespace igi {
namespace {

// Two walls meeting at x = 24 (normals +z and +x), noisy values around 1 on
// the left and 4 on the right, one pixel with no surface.
WaveletInput two_walls(int width, int height, uint32_t seed = 7) {
  WaveletInput in;
  in.width = width;
  in.height = height;
  uint32_t state = seed;
  auto noise = [&state] {
    state = state * 1664525u + 1013904223u;
    return float(state >> 8) / float(1 << 24) - 0.5f;  // [-0.5, 0.5)
  };
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const bool left = x < 24;
      in.depth.push_back(x == 5 && y == 5 ? INFINITY : 3.0f + 0.01f * float(x));
      in.normal.push_back(left ? glm::vec3(0, 0, 1) : glm::vec3(1, 0, 0));
      in.material.push_back(0);
      const float base = left ? 1.0f : 4.0f;
      in.value.push_back(glm::vec3(base * (1.0f + 0.6f * noise())));
    }
  return in;
}

// The part of `in` inside [x0, x0 + w) x [y0, y0 + h), as a region of its own.
WaveletInput crop(const WaveletInput& in, int x0, int y0, int w, int h) {
  WaveletInput out;
  out.x0 = in.x0 + x0;
  out.y0 = in.y0 + y0;
  out.width = w;
  out.height = h;
  for (int y = y0; y < y0 + h; ++y)
    for (int x = x0; x < x0 + w; ++x) {
      const size_t p = size_t(y) * in.width + x;
      out.depth.push_back(in.depth[p]);
      out.normal.push_back(in.normal[p]);
      out.material.push_back(in.material[p]);
      out.value.push_back(in.value[p]);
    }
  return out;
}

std::vector<glm::vec3> filter_all(const WaveletInput& in, const WaveletSettings& s) {
  std::vector<glm::vec3> out(size_t(in.width) * in.height);
  filter_wavelet(in, s, Rect{in.x0, in.y0, in.width, in.height}, out);
  return out;
}

TEST(WaveletFilter, APixelIsTheSameBitForBitInEveryRegionThatHoldsItsFootprint) {
  const WaveletInput whole = two_walls(64, 48);
  for (int levels : {1, 2, 3}) {
    WaveletSettings s;
    s.levels = levels;
    const std::vector<glm::vec3> reference = filter_all(whole, s);
    const int f = wavelet_footprint(levels);
    // Tiles of 8 x 8 at odd places, each in a region of the tile plus its footprint, clipped.
    for (const auto& [tx, ty] : {std::pair{0, 0}, {20, 9}, {56, 40}, {30, 17}}) {
      const int x0 = std::max(tx - f, 0), y0 = std::max(ty - f, 0);
      const int x1 = std::min(tx + 8 + f, 64), y1 = std::min(ty + 8 + f, 48);
      const WaveletInput region = crop(whole, x0, y0, x1 - x0, y1 - y0);
      std::vector<glm::vec3> out(64);
      filter_wavelet(region, s, Rect{tx, ty, 8, 8}, out);
      for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 8; ++x)
          ASSERT_EQ(std::memcmp(&out[size_t(y) * 8 + x], &reference[size_t(ty + y) * 64 + tx + x], sizeof(glm::vec3)),
                    0)
              << "levels " << levels << ", pixel (" << tx + x << ", " << ty + y << ")";
    }
  }
}

TEST(WaveletFilter, SmoothsNoiseOnASurfaceWithoutMixingTheNextOne) {
  const WaveletInput in = two_walls(64, 48);
  WaveletSettings s;
  s.levels = 3;
  const std::vector<glm::vec3> out = filter_all(in, s);
  // Spread of the left wall's pixels (away from the edge and the hole), before and after.
  auto spread = [&](const std::vector<glm::vec3>& v, int xa, int xb, double* mean) {
    double sum = 0, sum2 = 0;
    int n = 0;
    for (int y = 8; y < 40; ++y)
      for (int x = xa; x < xb; ++x) {
        sum += v[size_t(y) * 64 + x].x;
        sum2 += double(v[size_t(y) * 64 + x].x) * v[size_t(y) * 64 + x].x;
        ++n;
      }
    *mean = sum / n;
    return std::sqrt(std::max(0.0, sum2 / n - *mean * *mean));
  };
  double mean_in, mean_out;
  const double before = spread(in.value, 8, 20, &mean_in), after = spread(out, 8, 20, &mean_out);
  EXPECT_LT(after, 0.5 * before) << "the filter smooths a surface's noise";
  EXPECT_NEAR(mean_out, mean_in, 0.05 * mean_in) << "and keeps its light";
  // The columns beside the edge stay on their own wall's level (1 and 4).
  double left_edge, right_edge;
  spread(out, 22, 24, &left_edge);
  spread(out, 24, 26, &right_edge);
  EXPECT_NEAR(left_edge, 1.0, 0.15);
  EXPECT_NEAR(right_edge, 4.0, 0.6);
  // The pixel with no surface is copied through.
  EXPECT_EQ(out[5 * 64 + 5], in.value[5 * 64 + 5]);
}

TEST(WaveletFilter, RefusesMalformedInputAndSettings) {
  WaveletInput in = two_walls(16, 16);
  std::vector<glm::vec3> out(256);
  WaveletSettings s;
  s.levels = 0;
  EXPECT_THROW(filter_wavelet(in, s, Rect{0, 0, 16, 16}, out), std::invalid_argument);
  s.levels = kMaxWaveletLevels + 1;
  EXPECT_THROW(filter_wavelet(in, s, Rect{0, 0, 16, 16}, out), std::invalid_argument);
  s = WaveletSettings{};
  s.sigma_luminance = 0.0f;
  EXPECT_THROW(filter_wavelet(in, s, Rect{0, 0, 16, 16}, out), std::invalid_argument);
  s = WaveletSettings{};
  EXPECT_THROW(filter_wavelet(in, s, Rect{4, 4, 16, 16}, out), std::invalid_argument);  // outside the region
  std::vector<glm::vec3> short_out(10);
  EXPECT_THROW(filter_wavelet(in, s, Rect{0, 0, 16, 16}, short_out), std::invalid_argument);
  in.material.pop_back();
  EXPECT_THROW(filter_wavelet(in, s, Rect{0, 0, 16, 16}, out), std::invalid_argument);
}

TEST(WaveletFilter, StepsAsideOneLevelEachTimeThePassesGrowFourfold) {
  EXPECT_EQ(wavelet_levels_at_pass(3, 0), 3);
  EXPECT_EQ(wavelet_levels_at_pass(3, 2), 3);
  EXPECT_EQ(wavelet_levels_at_pass(3, 3), 2);
  EXPECT_EQ(wavelet_levels_at_pass(3, 14), 2);
  EXPECT_EQ(wavelet_levels_at_pass(3, 15), 1);
  EXPECT_EQ(wavelet_levels_at_pass(3, 63), 0);
  EXPECT_EQ(wavelet_levels_at_pass(0, 0), 0);
}

// igi and ir with the filter: the same pixels in tiles of 16 and of 256 and
// on any thread count, and a visible change (the filter runs) that keeps the
// image's light.
TEST(WaveletFilter, IgiAndIrWithTheFilterAreTheSameWholeAndTiled) {
  test::Prepared p(load_scene("cornell"));
  for (MethodKind kind : {MethodKind::Igi, MethodKind::InstantRadiosity}) {
    RenderSettings s = test::vpl_settings(kind, 8, 0.3f, true, 2, 4);
    s.wavelet_levels = 2;
    const Image tiled = p.render(s, 96, 72, 1, 1, 2, 16);
    const Image whole = p.render(s, 96, 72, 1, 1, 1, 256);
    EXPECT_TRUE(test::images_identical(std::string("wavelet-tiles-") + method_name(kind), tiled, whole));
    RenderSettings off = s;
    off.wavelet_levels = 0;
    const Image plain = p.render(off, 96, 72, 1, 1, 2, 16);
    double sum_on = 0, sum_off = 0, changed = 0;
    for (size_t i = 0; i < plain.pixels.size(); ++i) {
      sum_on += test::luminance(tiled.pixels[i]);
      sum_off += test::luminance(plain.pixels[i]);
      changed += tiled.pixels[i] != plain.pixels[i];
    }
    EXPECT_GT(changed, 0.5 * double(plain.pixels.size())) << method_name(kind);
    EXPECT_NEAR(sum_on / sum_off, 1.0, 0.02) << method_name(kind) << ": the filter must not take light away";
  }
}

// Progressive passes render with fewer levels, each pass still the same whole and tiled.
TEST(WaveletFilter, ProgressivePassesAreTheSameWholeAndTiled) {
  test::Prepared p(load_scene("cornell"));
  RenderSettings s = test::vpl_settings(MethodKind::Igi, 8, 0.3f, true, 0, 4);
  s.wavelet_levels = 2;  // passes 0-2 at 2 levels, 3-4 at 1
  EXPECT_TRUE(test::images_identical("wavelet-passes", p.render(s, 64, 48, 5, 3, 2, 16), p.render(s, 64, 48, 5, 3, 1, 128)));
}

}  // namespace
}  // namespace igi
