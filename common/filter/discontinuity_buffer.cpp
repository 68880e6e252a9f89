// Discontinuity buffer: the definition (brute force) and the constant-time
// version. Coordinates below are region coordinates (0..width, 0..height)
// unless named image coordinates.
//
// Constant-time version, per inner pixel p, independent of the window size:
//   1. the extrema of depth and of each normal component over p's window,
//      separably (rows, then columns) by van Herk / Gil-Werman;
//   2. if the extrema prove every window pixel on p's surface, S_p is the
//      whole clipped window and out_p = box sum / pixel count, the box sums
//      from running sums (rows, then columns);
//   3. otherwise p is evaluated by the definition (exact_pixel).
// The running sums are int64 fixed point, not float: a float running sum's
// rounding depends on where its row began, so a pixel would come out
// differently in differently cut tiles. Integer adds are exact, so a box sum
// depends only on the values in the box. The inner rect is processed in bands
// of rows (cache), which for the same reason changes no bit.
//
// Float expressions here are written for -ffp-contract=off (set for the whole
// project): the step 2 test is conservative only if dot3 is not fused.
#include "filter/discontinuity_buffer.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace igi {
namespace {

constexpr float kInfinity = std::numeric_limits<float>::infinity();

// Per-pixel SIMD values (GCC and Clang vector extensions), so that one
// operation covers all channels of a pixel: its geometry (depth, normal x,
// y, z) for min and max, its value in fixed point (r, g, b, 0) for the sums,
// and the doubles that value is converted from.
using Float4 = float __attribute__((vector_size(16)));
using Fixed4 = int64_t __attribute__((vector_size(32)));
using Double4 = double __attribute__((vector_size(32)));

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
  if (s.window < 1 || s.window > 2049)
    throw std::invalid_argument("FilterSettings.window: expected 1..2049, got " + std::to_string(s.window));
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

// The window's reach before and after p, each way.
int reach_before(int window) { return window / 2; }
int reach_after(int window) { return window - 1 - window / 2; }

// out_p by the definition. The window is summed row-major in double, so the
// result depends only on the window's data; p always counts, even where
// rounding puts dot(n_p, n_p) a hair below normal_cos.
glm::vec3 exact_pixel(const FilterInput& in, const FilterSettings& s, int px, int py) {
  const int a = reach_before(s.window), b = reach_after(s.window), w = in.width;
  const size_t p = size_t(py) * w + px;
  const float d_p = in.depth[p];
  if (!is_valid(d_p)) return in.value[p];
  const glm::vec3 n_p = in.normal[p];
  glm::dvec3 sum(0.0);
  int count = 0;
  for (int y = std::max(py - a, 0); y <= std::min(py + b, in.height - 1); ++y)
    for (int x = std::max(px - a, 0); x <= std::min(px + b, w - 1); ++x) {
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
  Float4 operator()(Float4 a, Float4 b) const { return b < a ? b : a; }
  static constexpr float identity = kInfinity;
};
struct Max {
  Float4 operator()(Float4 a, Float4 b) const { return a < b ? b : a; }
  static constexpr float identity = -kInfinity;
};

// A 1-D sequence of n entries, entry k being `lanes` values at
// data + k * stride. Lanes are contiguous: a row pass has one lane (the
// pixel), a column pass a lane per column.
template <class T>
struct Sequence {
  const T* data;
  size_t stride;
  int n, lanes;
  const T* entry(int k) const { return data + size_t(k) * stride; }
};

// Per-lane working values: on the stack when the lane count is a
// compile-time constant (kLanes > 0: the row passes), else on the heap.
template <class T, int kLanes>
struct Lanes {
  explicit Lanes(int) {}
  T* data() { return values.data(); }
  std::array<T, kLanes> values{};
};
template <class T>
struct Lanes<T, 0> {
  explicit Lanes(int lanes) : values(size_t(lanes)) {}
  T* data() { return values.data(); }
  std::vector<T> values;
};

// out entry i, for i in [o0, o1), = op over entries [i - a, i + b] (clipped).
// Pad the sequence with a identity entries before and b after and cut it into
// blocks of w = a + b + 1; padded window [i, i + w - 1] then spans at most two
// blocks, and its extremum is op(suffix of i's block from i, prefix of the
// next block up to i + w - 1): three op per entry whatever w. kLanes > 0
// fixes in.lanes at compile time.
template <int kLanes, class Op>
void sliding_extremum(Op op, int a, int b, Sequence<Float4> in, int o0, int o1, Float4* out, size_t out_stride,
                      std::vector<Float4>& suffixes) {
  if (o0 >= o1) return;
  const int w = a + b + 1, lanes = kLanes > 0 ? kLanes : in.lanes;
  Lanes<Float4, kLanes> identity(lanes), prefix(lanes);
  std::fill_n(identity.data(), lanes, Float4{} + Op::identity);
  auto entry = [&](int k) {  // padded index k
    const int j = k - a;
    return j >= 0 && j < in.n ? in.entry(j) : identity.data();
  };
  auto combine = [&](Float4* dst, const Float4* a, const Float4* b) {  // dst may be a or b
    for (int l = 0; l < lanes; ++l) dst[l] = op(a[l], b[l]);
  };
  // Backward from a block end: suffix[k] = op(entries k .. end of k's block).
  const int top = (o1 - 1) / w * w + w - 1;
  suffixes.resize(size_t(top - o0 + 1) * lanes);
  for (int k = top, to_end = 0; k >= o0; --k, to_end = to_end == w - 1 ? 0 : to_end + 1) {
    Float4* suffix = suffixes.data() + size_t(k - o0) * lanes;
    const Float4* e = entry(k);
    combine(suffix, e, to_end == 0 ? e : suffix + lanes);
  }
  // Forward from a block start: prefix = op(entries from the start of k's
  // block .. k); window i ends at k.
  for (int k = (o0 + w - 1) / w * w, from_start = 0; k < o1 + w - 1;
       ++k, from_start = from_start == w - 1 ? 0 : from_start + 1) {
    const Float4* e = entry(k);
    combine(prefix.data(), from_start == 0 ? e : prefix.data(), e);
    const int i = k - (w - 1);
    if (i < o0) continue;
    combine(out + size_t(i - o0) * out_stride, suffixes.data() + size_t(i - o0) * lanes, prefix.data());
  }
}

// Inner rows are filtered in bands so that the intermediate planes stay in
// cache; a band reads the rows its windows reach above and below it again.
constexpr int kBandRows = 32;

// Working memory of one call, reused from band to band.
struct BandScratch {
  std::vector<Float4> geometry;  // per pixel of the rows read
  std::vector<Float4> along_rows, lo, hi, suffixes;
  std::vector<Fixed4> fixed, row_sums, sums;
};

// Rows of the region that windows of a band's rows reach.
int rows_begin(const Box& band, int a) { return std::max(band.y0 - a, 0); }
int rows_end(const Box& band, int b, int height) { return std::min(band.y1 + b, height); }

// Per band pixel, row-major: lo (Min) or hi (Max) of the geometry over its
// window. Rows first, then columns.
template <class Op>
void window_extremum(Op op, int a, int b, const Box& band, int region_width, int rows, BandScratch& scratch,
                     std::vector<Float4>& result) {
  const int bw = band.width(), ry0 = rows_begin(band, a);
  scratch.along_rows.resize(size_t(rows) * bw);
  for (int y = 0; y < rows; ++y) {
    const Sequence<Float4> row{scratch.geometry.data() + size_t(y) * region_width, 1, region_width, 1};
    Float4* along_row = scratch.along_rows.data() + size_t(y) * bw;
    sliding_extremum<1>(op, a, b, row, band.x0, band.x1, along_row, 1, scratch.suffixes);
  }
  result.resize(size_t(band.height()) * bw);
  const Sequence<Float4> columns{scratch.along_rows.data(), size_t(bw), rows, bw};
  sliding_extremum<0>(op, a, b, columns, band.y0 - ry0, band.y1 - ry0, result.data(), bw, scratch.suffixes);
}

// Fills scratch.lo and scratch.hi for the band.
void window_extrema(const FilterInput& in, int a, int b, const Box& band, BandScratch& scratch) {
  const int ry0 = rows_begin(band, a), rows = rows_end(band, b, in.height) - ry0;
  scratch.geometry.resize(size_t(rows) * in.width);
  const size_t first = size_t(ry0) * in.width;
  for (size_t i = 0; i < scratch.geometry.size(); ++i) {
    const glm::vec3& n = in.normal[first + i];
    scratch.geometry[i] = Float4{in.depth[first + i], n.x, n.y, n.z};
  }
  window_extremum(Min{}, a, b, band, in.width, rows, scratch, scratch.lo);
  window_extremum(Max{}, a, b, band, in.width, rows, scratch, scratch.hi);
}

// True when every pixel of p's window (band pixel i) passes same_surface,
// judged from the extrema alone. Conservative in floats too, because
// rounding is monotone: d_p - d_min >= d_p - d_q, and each
// min(n_p.c * lo.c, n_p.c * hi.c) <= n_p.c * n_q.c, so the sum in dot3's
// order bounds dot3(n_p, n_q) from below.
bool window_on_one_surface(const FilterSettings& s, float d_p, const glm::vec3& n_p, const BandScratch& scratch,
                           size_t i) {
  const Float4 lo = scratch.lo[i], hi = scratch.hi[i];
  if (!is_valid(hi[0])) return false;
  const float tolerance = s.depth_ratio * d_p;
  if (d_p - lo[0] > tolerance || hi[0] - d_p > tolerance) return false;
  auto lower = [&](int c) { return std::min(n_p[c] * lo[c + 1], n_p[c] * hi[c + 1]); };
  return lower(0) + lower(1) + lower(2) >= s.normal_cos;
}

// ---------------------------------------------------------------------------
// Box sums in int64 fixed point.

// Each value is clamped to +-cap before rounding, cap = 2^55 / window area,
// so no window sum (nor a running sum mid-update) can overflow.
double fixed_cap(int window) { return 0x1p55 / (double(window) * double(window)); }

// llround(clamp(v * scale, -cap, cap)) for the three channels at once, bit
// for bit: truncate, then round the remainder half away from zero. The
// remainder x - trunc(x) is exact (Sterbenz: trunc(x) is 0 or within a
// factor 2 of x). Vector comparisons give -1 for true.
Fixed4 to_fixed(const glm::vec3& v, double scale, double cap) {
  const Double4 lo = Double4{} - cap, hi = Double4{} + cap;
  Double4 x = Double4{v.x, v.y, v.z, 0.0} * scale;
  x = x < lo ? lo : x > hi ? hi : x;
  const Fixed4 truncated = __builtin_convertvector(x, Fixed4);
  const Double4 rest = x - __builtin_convertvector(truncated, Double4);
  return truncated - (rest >= 0.5) + (rest <= -0.5);
}

// out entry i, for i in [o0, o1), = sum of entries [i - a, i + b] (clipped).
// Starting from the window of o0 - 1, each step adds the entering entry
// i + b and subtracts the leaving one i - a - 1. kLanes as in sliding_extremum.
template <int kLanes>
void running_box_sum(int a, int b, Sequence<Fixed4> in, int o0, int o1, Fixed4* out, size_t out_stride) {
  const int lanes = kLanes > 0 ? kLanes : in.lanes;
  Lanes<Fixed4, kLanes> sum(lanes);
  Fixed4* s = sum.data();
  auto add = [&](int k) { for (int l = 0; l < lanes; ++l) s[l] += in.entry(k)[l]; };
  auto subtract = [&](int k) { for (int l = 0; l < lanes; ++l) s[l] -= in.entry(k)[l]; };
  for (int k = std::max(o0 - 1 - a, 0); k <= std::min(o0 - 1 + b, in.n - 1); ++k) add(k);
  for (int i = o0; i < o1; ++i) {
    if (i + b < in.n) add(i + b);
    if (i - a - 1 >= 0) subtract(i - a - 1);
    std::copy_n(s, lanes, out + size_t(i - o0) * out_stride);
  }
}

// Fills scratch.sums: per band pixel, row-major, the channel sums of fixed
// values over its whole clipped window. Rows first, then columns.
void window_sums(const FilterInput& in, const FilterSettings& s, const Box& band, BandScratch& scratch) {
  const int a = reach_before(s.window), b = reach_after(s.window);
  const int ry0 = rows_begin(band, a), rows = rows_end(band, b, in.height) - ry0;
  const int bw = band.width();
  const double cap = fixed_cap(s.window);
  scratch.fixed.resize(size_t(in.width));
  scratch.row_sums.resize(size_t(rows) * bw);
  for (int y = 0; y < rows; ++y) {
    const glm::vec3* value = in.value.data() + size_t(ry0 + y) * in.width;
    for (int x = 0; x < in.width; ++x) scratch.fixed[x] = to_fixed(value[x], s.fixed_scale, cap);
    const Sequence<Fixed4> row{scratch.fixed.data(), 1, in.width, 1};
    running_box_sum<1>(a, b, row, band.x0, band.x1, scratch.row_sums.data() + size_t(y) * bw, 1);
  }
  scratch.sums.resize(size_t(band.height()) * bw);
  const Sequence<Fixed4> columns{scratch.row_sums.data(), size_t(bw), rows, bw};
  running_box_sum<0>(a, b, columns, band.y0 - ry0, band.y1 - ry0, scratch.sums.data(), bw);
}

// Pixels of the window of region pixel (x, y), clipped to the region.
int window_count(const FilterInput& in, int a, int b, int x, int y) {
  const int w = std::min(x + b, in.width - 1) - std::max(x - a, 0) + 1;
  const int h = std::min(y + b, in.height - 1) - std::max(y - a, 0) + 1;
  return w * h;
}

// The window average in real units, sum / (fixed_scale * count), as a
// multiply by a reciprocal (as deterministic, and cheaper).
glm::vec3 from_fixed(const Fixed4& sum, double per_quantum) {
  return glm::vec3(double(sum[0]) * per_quantum, double(sum[1]) * per_quantum, double(sum[2]) * per_quantum);
}

// Filters the band's pixels into `out` (band pixels, row-major).
void filter_band(const FilterInput& in, const FilterSettings& s, const Box& band, BandScratch& scratch,
                 glm::vec3* out, FilterStats& stats) {
  const int a = reach_before(s.window), b = reach_after(s.window);
  window_extrema(in, a, b, band, scratch);
  window_sums(in, s, band, scratch);
  // Most windows are whole: their reciprocal is computed once (the same
  // expression, so the same bits as computing it per pixel).
  const int whole = s.window * s.window;
  const double whole_per_quantum = 1.0 / (s.fixed_scale * whole);
  size_t i = 0;
  for (int y = band.y0; y < band.y1; ++y)
    for (int x = band.x0; x < band.x1; ++x, ++i) {
      const size_t p = size_t(y) * in.width + x;
      const float d_p = in.depth[p];
      if (is_valid(d_p) && window_on_one_surface(s, d_p, in.normal[p], scratch, i)) {
        const int count = window_count(in, a, b, x, y);
        out[i] = from_fixed(scratch.sums[i], count == whole ? whole_per_quantum : 1.0 / (s.fixed_scale * count));
        ++stats.fast_pixels;
      } else {
        out[i] = exact_pixel(in, s, x, y);
        ++stats.exact_pixels;
      }
    }
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
  thread_local BandScratch scratch;  // reused across calls: no allocation per tile
  FilterStats counted;
  for (int y0 = box.y0; y0 < box.y1; y0 += kBandRows) {
    const Box band{box.x0, y0, box.x1, std::min(y0 + kBandRows, box.y1)};
    filter_band(in, s, band, scratch, out.data() + size_t(y0 - box.y0) * box.width(), counted);
  }
  if (stats) *stats = counted;
}

double filter_fixed_scale(double typical_value) {
  if (!(typical_value > 0.0) || !std::isfinite(typical_value)) return 0x1p32;
  const double exponent = std::clamp(24.0 - std::round(std::log2(typical_value)), -32.0, 64.0);
  return std::ldexp(1.0, int(exponent));
}

float filter_weight_at_pass(uint32_t pass) {
  return std::min(1.0f, std::sqrt(float(kFilterFullPasses) / (float(pass) + 1.0f)));
}

void filter_tent(const FilterInput& in, const FilterSettings& s, Rect inner, std::span<glm::vec3> out) {
  check_arguments(in, s, inner, out.size());
  // The first pass over the inner rect grown by a window's reach (clipped to
  // the region), then the second over that: the region holds both reaches.
  const int a = reach_before(s.window), b = reach_after(s.window);
  const int x0 = std::max(inner.x - a, in.x0), y0 = std::max(inner.y - a, in.y0);
  const int x1 = std::min(inner.x + inner.w + b, in.x0 + in.width), y1 = std::min(inner.y + inner.h + b, in.y0 + in.height);
  thread_local FilterInput first;
  first.x0 = x0, first.y0 = y0, first.width = x1 - x0, first.height = y1 - y0;
  const size_t n = size_t(first.width) * size_t(first.height);
  first.value.resize(n);
  filter_discontinuity(in, s, Rect{x0, y0, first.width, first.height}, first.value);
  first.depth.resize(n);
  first.normal.resize(n);
  for (int y = 0; y < first.height; ++y)
    for (int x = 0; x < first.width; ++x) {
      const size_t from = size_t(y + y0 - in.y0) * size_t(in.width) + size_t(x + x0 - in.x0);
      first.depth[size_t(y) * first.width + x] = in.depth[from];
      first.normal[size_t(y) * first.width + x] = in.normal[from];
    }
  filter_discontinuity(first, s, inner, out);
}

void filter_handed_over(const FilterInput& in, const FilterSettings& s, Rect inner, float weight, float spike_level,
                        std::span<glm::vec3> out) {
  if (weight >= 1.0f) return filter_tent(in, s, inner, out);
  bool any_spike = false;
  for (const glm::vec3& v : in.value) any_spike |= v.x > spike_level || v.y > spike_level || v.z > spike_level;
  // With spikes: one copy of the input, its values the lower part u - h
  // first, then (after the blend has read them) the spikes h.
  thread_local FilterInput split;
  thread_local std::vector<glm::vec3> spikes, spikes_out;
  if (any_spike) {
    split = in;
    spikes.resize(in.value.size());
    for (size_t p = 0; p < in.value.size(); ++p)
      for (int c = 0; c < 3; ++c) {
        spikes[p][c] = std::max(in.value[p][c] - spike_level, 0.0f);
        split.value[p][c] = in.value[p][c] - spikes[p][c];
      }
  }
  const FilterInput& lower = any_spike ? split : in;
  filter_tent(lower, s, inner, out);
  const int region_x = inner.x - in.x0, region_y = inner.y - in.y0;
  for (int y = 0; y < inner.h; ++y)
    for (int x = 0; x < inner.w; ++x) {
      glm::vec3& o = out[size_t(y) * inner.w + x];
      o = weight * o + (1.0f - weight) * lower.value[size_t(region_y + y) * in.width + size_t(region_x + x)];
    }
  if (!any_spike) return;
  split.value.swap(spikes);
  spikes_out.resize(size_t(inner.w) * inner.h);
  filter_tent(split, s, inner, spikes_out);
  for (size_t i = 0; i < spikes_out.size(); ++i) out[i] += spikes_out[i];
}

float filter_spike_level(float typical_value, uint32_t pass) {
  return typical_value * std::sqrt(std::sqrt((float(pass) + 1.0f) / float(kFilterFullPasses)));
}

}  // namespace igi
