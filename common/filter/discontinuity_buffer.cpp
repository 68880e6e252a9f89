// Discontinuity buffer: the definition (brute force) and the constant-time
// version. Coordinates below are region coordinates (0..width, 0..height)
// unless named image coordinates.
//
// Constant-time version, per inner pixel p, independent of r:
//   1. the extrema of depth and of each normal component over p's window,
//      separably (rows, then columns) by van Herk / Gil-Werman;
//   2. if the extrema prove every window pixel on p's surface, S_p is the
//      whole clipped window and out_p = box sum / pixel count, the box sums
//      from running sums (rows, then columns);
//   3. otherwise p is evaluated by the definition (exact_pixel).
// The running sums are int64 fixed point, not float: a float running sum's
// rounding depends on where its row began, so a pixel would come out
// differently in differently cut tiles. Integer adds are exact, so a box sum
// depends only on the values in the box.
#include "filter/discontinuity_buffer.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace igi {
namespace {

static_assert(sizeof(glm::vec3) == 3 * sizeof(float), "normal components are read with a stride of 3 floats");

constexpr float kInfinity = std::numeric_limits<float>::infinity();

bool is_valid(float depth) { return depth < kInfinity; }

// Written out so the summation order is fixed, (x + y) + z: the window test
// in window_on_one_surface bounds exactly this expression.
float dot3(const glm::vec3& a, const glm::vec3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }

bool same_surface(const FilterSettings& s, float d_p, const glm::vec3& n_p, float d_q, const glm::vec3& n_q) {
  return is_valid(d_q) && dot3(n_p, n_q) >= s.normal_cos && std::abs(d_q - d_p) <= s.depth_ratio * d_p;
}

// The inner rect in region coordinates, half-open.
struct Box {
  int x0, y0, x1, y1;
  int width() const { return x1 - x0; }
  int height() const { return y1 - y0; }
};

std::string rect_text(int x, int y, int w, int h) {
  return "(x " + std::to_string(x) + ", y " + std::to_string(y) + ", w " + std::to_string(w) + ", h " +
         std::to_string(h) + ")";
}

Box check_arguments(const FilterInput& in, const FilterSettings& s, Rect inner, size_t out_size) {
  const size_t n = size_t(std::max(in.width, 0)) * size_t(std::max(in.height, 0));
  if (in.width < 0 || in.height < 0 || in.depth.size() != n || in.normal.size() != n || in.value.size() != n)
    throw std::invalid_argument("FilterInput: depth, normal and value must each hold width * height = " +
                                std::to_string(n) + " entries, got " + std::to_string(in.depth.size()) + ", " +
                                std::to_string(in.normal.size()) + ", " + std::to_string(in.value.size()));
  if (s.radius < 0 || s.radius > 1024)
    throw std::invalid_argument("FilterSettings.radius: expected 0..1024, got " + std::to_string(s.radius));
  if (!(s.fixed_scale > 0.0) || !std::isfinite(s.fixed_scale))
    throw std::invalid_argument("FilterSettings.fixed_scale: expected a finite positive scale");
  const Box box{inner.x - in.x0, inner.y - in.y0, inner.x - in.x0 + inner.w, inner.y - in.y0 + inner.h};
  if (inner.w < 0 || inner.h < 0 || box.x0 < 0 || box.y0 < 0 || box.x1 > in.width || box.y1 > in.height)
    throw std::invalid_argument("filter inner rect " + rect_text(inner.x, inner.y, inner.w, inner.h) +
                                " must lie inside the region " + rect_text(in.x0, in.y0, in.width, in.height));
  if (out_size < size_t(inner.w) * size_t(inner.h))
    throw std::invalid_argument("filter output: expected " + std::to_string(size_t(inner.w) * size_t(inner.h)) +
                                " entries (inner w * h), got " + std::to_string(out_size));
  return box;
}

// out_p by the definition. The window is summed row-major in double, so the
// result depends only on the window's data; p always counts, even where
// rounding puts dot(n_p, n_p) a hair below normal_cos.
glm::vec3 exact_pixel(const FilterInput& in, const FilterSettings& s, int px, int py) {
  const int r = s.radius, w = in.width;
  const size_t p = size_t(py) * w + px;
  const float d_p = in.depth[p];
  if (!is_valid(d_p)) return in.value[p];
  const glm::vec3 n_p = in.normal[p];
  glm::dvec3 sum(0.0);
  int count = 0;
  for (int y = std::max(py - r, 0); y <= std::min(py + r, in.height - 1); ++y)
    for (int x = std::max(px - r, 0); x <= std::min(px + r, w - 1); ++x) {
      const size_t q = size_t(y) * w + x;
      if (q != p && !same_surface(s, d_p, n_p, in.depth[q], in.normal[q])) continue;
      sum += glm::dvec3(in.value[q]);
      ++count;
    }
  return glm::vec3(sum / double(count));
}

// ---------------------------------------------------------------------------
// Sliding extrema (van Herk / Gil-Werman).

struct Min {
  float operator()(float a, float b) const { return b < a ? b : a; }
  static constexpr float identity = kInfinity;
};
struct Max {
  float operator()(float a, float b) const { return a < b ? b : a; }
  static constexpr float identity = -kInfinity;
};

// A 1-D sequence of n entries, entry k being `lanes` floats at
// data + k * stride. Lanes are contiguous, so a column pass (one lane per
// column) runs over whole rows.
struct Sequence {
  const float* data;
  size_t stride;
  int n, lanes;
};

struct SlidingScratch {
  std::vector<float> suffix, prefix, identity_entry;
};

// out entry i, for i in [o0, o1), = op over entries [i - r, i + r] (clipped).
// Pad the sequence with r identity entries at each end and cut it into
// blocks of w = 2r + 1; padded window [i, i + w - 1] then spans at most two
// blocks, and its extremum is op(suffix of i's block from i, prefix of the
// next block up to i + w - 1): three op per entry whatever r.
template <class Op>
void sliding_extremum(Op op, int r, Sequence in, int o0, int o1, float* out, size_t out_stride,
                      SlidingScratch& scratch) {
  if (o0 >= o1) return;
  const int w = 2 * r + 1, lanes = in.lanes;
  scratch.identity_entry.assign(lanes, Op::identity);
  auto entry = [&](int k) {  // padded index k
    const int j = k - r;
    return j >= 0 && j < in.n ? in.data + size_t(j) * in.stride : scratch.identity_entry.data();
  };
  // Backward: suffix[k] = op(entries k .. end of k's block).
  const int top = (o1 - 1) / w * w + w - 1;
  scratch.suffix.resize(size_t(top - o0 + 1) * lanes);
  for (int k = top; k >= o0; --k) {
    float* suffix = &scratch.suffix[size_t(k - o0) * lanes];
    const float* e = entry(k);
    if ((k + 1) % w == 0) std::copy(e, e + lanes, suffix);
    else for (int l = 0; l < lanes; ++l) suffix[l] = op(e[l], suffix[l + lanes]);
  }
  // Forward: prefix = op(entries from the start of k's block .. k); window i ends at k.
  scratch.prefix.resize(lanes);
  float* prefix = scratch.prefix.data();
  for (int k = (o0 + w - 1) / w * w; k < o1 + w - 1; ++k) {
    const float* e = entry(k);
    if (k % w == 0) std::copy(e, e + lanes, prefix);
    else for (int l = 0; l < lanes; ++l) prefix[l] = op(prefix[l], e[l]);
    const int i = k - (w - 1);
    if (i < o0) continue;
    const float* suffix = &scratch.suffix[size_t(i - o0) * lanes];
    float* o = out + size_t(i - o0) * out_stride;
    for (int l = 0; l < lanes; ++l) o[l] = op(suffix[l], prefix[l]);
  }
}

// Per inner pixel (row-major over the box), lo/hi over its window of
// channel 0: depth, channels 1..3: normal x, y, z.
struct WindowExtrema {
  std::vector<float> lo[4], hi[4];
};

// Rows of the region that windows of box rows reach.
int rows_begin(const Box& box, int r) { return std::max(box.y0 - r, 0); }
int rows_end(const Box& box, int r, int height) { return std::min(box.y1 + r, height); }

// Rows first (over the region rows the box's windows reach, box columns
// only), then columns (box rows only).
template <class Op>
std::vector<float> window_extremum(Op op, const FilterInput& in, int channel, int r, const Box& box,
                                   SlidingScratch& scratch) {
  const float* data = channel == 0 ? in.depth.data() : &in.normal[0].x + (channel - 1);
  const size_t stride = channel == 0 ? 1 : 3;
  const int ry0 = rows_begin(box, r), ry1 = rows_end(box, r, in.height), bw = box.width();
  std::vector<float> along_rows(size_t(ry1 - ry0) * bw);
  for (int y = ry0; y < ry1; ++y) {
    const Sequence row{data + size_t(y) * in.width * stride, stride, in.width, 1};
    sliding_extremum(op, r, row, box.x0, box.x1, &along_rows[size_t(y - ry0) * bw], 1, scratch);
  }
  std::vector<float> result(size_t(box.height()) * bw);
  const Sequence columns{along_rows.data(), size_t(bw), ry1 - ry0, bw};
  sliding_extremum(op, r, columns, box.y0 - ry0, box.y1 - ry0, result.data(), bw, scratch);
  return result;
}

WindowExtrema window_extrema(const FilterInput& in, int r, const Box& box) {
  if (in.normal.empty()) return {};
  WindowExtrema e;
  SlidingScratch scratch;
  for (int c = 0; c < 4; ++c) {
    e.lo[c] = window_extremum(Min{}, in, c, r, box, scratch);
    e.hi[c] = window_extremum(Max{}, in, c, r, box, scratch);
  }
  return e;
}

// True when every pixel of p's window (extremum index i) passes
// same_surface, judged from the extrema alone. Conservative in floats too,
// because rounding is monotone: d_p - d_min >= d_p - d_q, and each
// min(n_p.c * lo.c, n_p.c * hi.c) <= n_p.c * n_q.c, so the sum in dot3's
// order bounds dot3(n_p, n_q) from below.
bool window_on_one_surface(const FilterSettings& s, float d_p, const glm::vec3& n_p, const WindowExtrema& e,
                           size_t i) {
  const float d_min = e.lo[0][i], d_max = e.hi[0][i];
  if (!is_valid(d_max)) return false;
  const float tolerance = s.depth_ratio * d_p;
  if (d_p - d_min > tolerance || d_max - d_p > tolerance) return false;
  auto lower = [&](int c) { return std::min(n_p[c] * e.lo[c + 1][i], n_p[c] * e.hi[c + 1][i]); };
  return lower(0) + lower(1) + lower(2) >= s.normal_cos;
}

// ---------------------------------------------------------------------------
// Box sums in int64 fixed point.

// Each value is clamped to +-cap before rounding, cap = 2^55 / window area,
// so no window sum (nor a running sum mid-update) can overflow.
double fixed_cap(int r) { return 0x1p55 / (double(2 * r + 1) * double(2 * r + 1)); }

int64_t to_fixed(float v, double scale, double cap) { return std::llround(std::clamp(double(v) * scale, -cap, cap)); }

// out entry i, for i in [o0, o1), = sum of entries [i - r, i + r] (clipped);
// entry k is `lanes` int64 at in + k * stride. Each step adds the entering
// entry and subtracts the leaving one.
void running_box_sum(int r, const int64_t* in, size_t stride, int n, int lanes, int o0, int o1, int64_t* out,
                     size_t out_stride) {
  if (o0 >= o1) return;
  std::fill(out, out + lanes, int64_t(0));
  for (int k = std::max(o0 - r, 0); k <= std::min(o0 + r, n - 1); ++k)
    for (int l = 0; l < lanes; ++l) out[l] += in[size_t(k) * stride + l];
  const std::vector<int64_t> zero(lanes, 0);
  for (int i = o0 + 1; i < o1; ++i) {
    const int64_t* entering = i + r < n ? in + size_t(i + r) * stride : zero.data();
    const int64_t* leaving = i - r - 1 >= 0 ? in + size_t(i - r - 1) * stride : zero.data();
    int64_t* sum = out + size_t(i - o0) * out_stride;
    const int64_t* previous = sum - out_stride;
    for (int l = 0; l < lanes; ++l) sum[l] = previous[l] + entering[l] - leaving[l];
  }
}

// Per inner pixel (row-major over the box), the 3 channel sums of fixed
// values over its whole clipped window: rows first, then columns.
std::vector<int64_t> window_sums(const FilterInput& in, const FilterSettings& s, const Box& box) {
  const int r = s.radius, ry0 = rows_begin(box, r), ry1 = rows_end(box, r, in.height), bw = box.width();
  const double cap = fixed_cap(r);
  std::vector<int64_t> fixed(size_t(in.width) * 3), along_rows(size_t(ry1 - ry0) * bw * 3);
  for (int y = ry0; y < ry1; ++y) {
    const glm::vec3* row = &in.value[size_t(y) * in.width];
    for (int x = 0; x < in.width; ++x)
      for (int c = 0; c < 3; ++c) fixed[size_t(x) * 3 + c] = to_fixed(row[x][c], s.fixed_scale, cap);
    running_box_sum(r, fixed.data(), 3, in.width, 3, box.x0, box.x1, &along_rows[size_t(y - ry0) * bw * 3], 3);
  }
  std::vector<int64_t> sums(size_t(box.height()) * bw * 3);
  const size_t row_stride = size_t(bw) * 3;
  running_box_sum(r, along_rows.data(), row_stride, ry1 - ry0, bw * 3, box.y0 - ry0, box.y1 - ry0, sums.data(),
                  row_stride);
  return sums;
}

// Pixels of the window of region pixel (x, y), clipped to the region.
int window_count(const FilterInput& in, int r, int x, int y) {
  const int w = std::min(x + r, in.width - 1) - std::max(x - r, 0) + 1;
  const int h = std::min(y + r, in.height - 1) - std::max(y - r, 0) + 1;
  return w * h;
}

}  // namespace

void filter_brute_force(const FilterInput& in, const FilterSettings& s, Rect inner, std::span<glm::vec3> out) {
  const Box box = check_arguments(in, s, inner, out.size());
  size_t o = 0;
  for (int y = box.y0; y < box.y1; ++y)
    for (int x = box.x0; x < box.x1; ++x) out[o++] = exact_pixel(in, s, x, y);
}

void filter_discontinuity(const FilterInput& in, const FilterSettings& s, Rect inner, std::span<glm::vec3> out,
                          FilterStats* stats) {
  const Box box = check_arguments(in, s, inner, out.size());
  const WindowExtrema extrema = window_extrema(in, s.radius, box);
  const std::vector<int64_t> sums = window_sums(in, s, box);
  FilterStats counted;
  size_t i = 0;
  for (int y = box.y0; y < box.y1; ++y)
    for (int x = box.x0; x < box.x1; ++x, ++i) {
      const size_t p = size_t(y) * in.width + x;
      const float d_p = in.depth[p];
      if (is_valid(d_p) && window_on_one_surface(s, d_p, in.normal[p], extrema, i)) {
        const double count = window_count(in, s.radius, x, y);
        const int64_t* sum = &sums[i * 3];
        out[i] = glm::vec3(double(sum[0]) / s.fixed_scale / count, double(sum[1]) / s.fixed_scale / count,
                           double(sum[2]) / s.fixed_scale / count);
        ++counted.fast_pixels;
      } else {
        out[i] = exact_pixel(in, s, x, y);
        ++counted.exact_pixels;
      }
    }
  if (stats) *stats = counted;
}

double filter_fixed_scale(double typical_value) {
  if (!(typical_value > 0.0) || !std::isfinite(typical_value)) return 0x1p32;
  const double exponent = std::clamp(24.0 - std::round(std::log2(typical_value)), -32.0, 64.0);
  return std::ldexp(1.0, int(exponent));
}

}  // namespace igi
