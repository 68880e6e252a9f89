// A-Trous wavelet filter: the definition in wavelet_filter.h, level by level
// over shrinking rects. Coordinates are region coordinates unless named
// image coordinates. Level i computes its output on the inner rect grown by
// what the later levels read (2 x 2^j for every j > i), so the last level
// writes exactly the inner rect; the variance is estimated on the rect the
// first level reads.
#include "wavelet/wavelet_filter.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace igi {
namespace {

constexpr float kKernel[5] = {1.0f / 16.0f, 4.0f / 16.0f, 6.0f / 16.0f, 4.0f / 16.0f, 1.0f / 16.0f};

bool is_valid(float depth) { return depth < INFINITY; }

float luminance(const glm::vec3& c) { return 0.2126f * c.x + 0.7152f * c.y + 0.0722f * c.z; }

// Half-open rect in region coordinates.
struct Box {
  int x0, y0, x1, y1;
  Box grown(int by, int width, int height) const {
    return {std::max(x0 - by, 0), std::max(y0 - by, 0), std::min(x1 + by, width), std::min(y1 + by, height)};
  }
  int width() const { return x1 - x0; }
  int height() const { return y1 - y0; }
  size_t index(int x, int y) const { return size_t(y - y0) * size_t(width()) + size_t(x - x0); }
};

// The geometric part of w(p, q): normal^128 (seven squarings) times the depth
// term's exponent, returned apart so the caller takes one exp per tap.
struct Geometry {
  float normal_weight;  // 0: q is not on p's surface
  float depth_exponent;
};

Geometry geometry(const WaveletInput& in, const WaveletSettings& s, size_t p, size_t q, int distance) {
  if (!is_valid(in.depth[q]) || in.material[q] != in.material[p]) return {0.0f, 0.0f};
  const glm::vec3 &a = in.normal[p], &b = in.normal[q];
  float n = std::max(0.0f, a.x * b.x + a.y * b.y + a.z * b.z);
  for (int i = 0; i < 7; ++i) n *= n;
  const float d_p = in.depth[p];
  return {n, std::abs(d_p - in.depth[q]) / (s.depth_sigma * d_p * float(distance))};
}

// Luminance variance over p's 5 x 5 window, its same-surface neighbours
// weighted by the geometric terms (p itself with weight 1).
float local_variance(const WaveletInput& in, const WaveletSettings& s, int px, int py) {
  const size_t p = size_t(py) * in.width + px;
  double sum_w = 0.0, sum_l = 0.0, sum_l2 = 0.0;
  for (int dy = -2; dy <= 2; ++dy)
    for (int dx = -2; dx <= 2; ++dx) {
      const int x = px + dx, y = py + dy;
      if (x < 0 || y < 0 || x >= in.width || y >= in.height) continue;
      const size_t q = size_t(y) * in.width + x;
      float w = 1.0f;
      if (q != p) {
        const Geometry g = geometry(in, s, p, q, std::max(std::abs(dx), std::abs(dy)));
        if (g.normal_weight == 0.0f) continue;
        w = g.normal_weight * std::exp(-g.depth_exponent);
      }
      const double l = luminance(in.value[q]);
      sum_w += w;
      sum_l += w * l;
      sum_l2 += w * l * l;
    }
  const double mean = sum_l / sum_w;
  return float(std::max(0.0, sum_l2 / sum_w - mean * mean));
}

void check_arguments(const WaveletInput& in, const WaveletSettings& s, Rect inner, size_t out_size) {
  const size_t n = size_t(std::max(in.width, 0)) * size_t(std::max(in.height, 0));
  if (in.width < 0 || in.height < 0 || in.depth.size() != n || in.normal.size() != n || in.material.size() != n ||
      in.value.size() != n)
    throw std::invalid_argument("WaveletInput: depth, normal, material and value must each hold width * height = " +
                                std::to_string(n) + " entries");
  if (s.levels < 1 || s.levels > kMaxWaveletLevels)
    throw std::invalid_argument("WaveletSettings.levels: expected 1.." + std::to_string(kMaxWaveletLevels) +
                                ", got " + std::to_string(s.levels));
  if (!(s.sigma_luminance > 0.0f) || !std::isfinite(s.sigma_luminance) || !(s.depth_sigma > 0.0f) ||
      !std::isfinite(s.depth_sigma))
    throw std::invalid_argument("WaveletSettings: sigma_luminance and depth_sigma must be finite and > 0");
  if (inner.w < 0 || inner.h < 0 || inner.x < in.x0 || inner.y < in.y0 || inner.x + inner.w > in.x0 + in.width ||
      inner.y + inner.h > in.y0 + in.height)
    throw std::invalid_argument("wavelet filter: the inner rect must lie inside the region");
  if (out_size < size_t(inner.w) * size_t(inner.h))
    throw std::invalid_argument("wavelet filter output: expected " +
                                std::to_string(size_t(inner.w) * size_t(inner.h)) + " entries (inner w * h)");
}

// One level, step 2^level: reads value and variance on `from`, writes them on `to`.
void filter_level(const WaveletInput& in, const WaveletSettings& s, int level, const Box& from,
                  const std::vector<glm::vec3>& value, const std::vector<float>& variance, const Box& to,
                  std::vector<glm::vec3>& value_out, std::vector<float>& variance_out) {
  const int step = 1 << level;
  value_out.resize(size_t(to.width()) * to.height());
  variance_out.resize(value_out.size());
  for (int py = to.y0; py < to.y1; ++py)
    for (int px = to.x0; px < to.x1; ++px) {
      const size_t p = size_t(py) * in.width + px, pf = from.index(px, py), pt = to.index(px, py);
      if (!is_valid(in.depth[p])) {
        value_out[pt] = value[pf];
        variance_out[pt] = variance[pf];
        continue;
      }
      const float l_p = luminance(value[pf]);
      const float luminance_scale = s.sigma_luminance * std::sqrt(variance[pf]) + 1e-3f * l_p + 1e-30f;
      glm::vec3 sum(0.0f);
      float sum_w = 0.0f, sum_var = 0.0f;
      for (int dy = -2; dy <= 2; ++dy)
        for (int dx = -2; dx <= 2; ++dx) {
          const int x = px + dx * step, y = py + dy * step;
          if (x < from.x0 || y < from.y0 || x >= from.x1 || y >= from.y1) continue;
          const size_t q = size_t(y) * in.width + x, qf = from.index(x, y);
          float w = kKernel[dx + 2] * kKernel[dy + 2];
          if (q != p) {
            const Geometry g = geometry(in, s, p, q, step * std::max(std::abs(dx), std::abs(dy)));
            if (g.normal_weight == 0.0f) continue;
            const float luminance_exponent = std::abs(l_p - luminance(value[qf])) / luminance_scale;
            w *= g.normal_weight * std::exp(-(g.depth_exponent + luminance_exponent));
          }
          sum += w * value[qf];
          sum_w += w;
          sum_var += w * w * variance[qf];
        }
      value_out[pt] = sum / sum_w;
      variance_out[pt] = sum_var / (sum_w * sum_w);
    }
}

}  // namespace

void filter_wavelet(const WaveletInput& in, const WaveletSettings& s, Rect inner, std::span<glm::vec3> out) {
  check_arguments(in, s, inner, out.size());
  const Box inner_box{inner.x - in.x0, inner.y - in.y0, inner.x - in.x0 + inner.w, inner.y - in.y0 + inner.h};
  // rects[i]: where level i writes; rects[levels]: the inner rect... built from the last level back.
  std::vector<Box> writes(size_t(s.levels));
  writes[size_t(s.levels) - 1] = inner_box;
  for (int i = s.levels - 2; i >= 0; --i) writes[size_t(i)] = writes[size_t(i) + 1].grown(2 << (i + 1), in.width, in.height);
  Box from = writes[0].grown(2, in.width, in.height);
  std::vector<glm::vec3> value(size_t(from.width()) * from.height());
  std::vector<float> variance(value.size());
  for (int y = from.y0; y < from.y1; ++y)
    for (int x = from.x0; x < from.x1; ++x) {
      const size_t p = size_t(y) * in.width + x;
      value[from.index(x, y)] = in.value[p];
      variance[from.index(x, y)] = is_valid(in.depth[p]) ? local_variance(in, s, x, y) : 0.0f;
    }
  std::vector<glm::vec3> value_next;
  std::vector<float> variance_next;
  for (int i = 0; i < s.levels; ++i) {
    filter_level(in, s, i, from, value, variance, writes[size_t(i)], value_next, variance_next);
    from = writes[size_t(i)];
    value.swap(value_next);
    variance.swap(variance_next);
  }
  std::copy(value.begin(), value.end(), out.begin());
}

int wavelet_levels_at_pass(int levels, uint32_t pass) {
  int drop = 0;
  for (uint64_t passes = uint64_t(pass) + 1; passes >= 4; passes /= 4) ++drop;
  return std::max(0, levels - drop);
}

}  // namespace igi
