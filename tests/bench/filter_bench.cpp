// Cost per pixel of the discontinuity buffer against the window width.
//
// A 640 x 480 region of a smooth curved surface, once as is ("smooth": every
// pixel takes the fast path) and once with a few edges ("edges": a depth
// step, a crease, a horizontal step and a disc of background). Each window
// width (3, 5, 6, 7, 9) is timed as the median of several runs
// (thread CPU time, so that other processes' time slices do not count); the
// fast path's cost should stay flat (within ~20 %) from width 3 to 9, while
// the brute force grows with the window area.
//
// usage: filter_bench [runs]   (default 9)
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <limits>
#include <vector>

#include <glm/geometric.hpp>

#include "filter/discontinuity_buffer.h"
#include "sampling/hash.h"

namespace {

using namespace igi;

constexpr int kWidth = 640, kHeight = 480;

float uniform(int x, int y, uint32_t seed) { return float(hash(uint32_t(x), uint32_t(y), seed) >> 8) * 0x1p-24f; }

struct Surface {
  float depth;
  glm::vec3 normal;
};

// A gently curved surface, seen from a little way off.
Surface smooth_surface(int x, int y) {
  const float u = 0.01f * float(x), v = 0.008f * float(y);
  return {5.0f + 0.5f * std::sin(u) * std::cos(v),
          glm::normalize(glm::vec3(0.2f * std::sin(u), 0.2f * std::cos(v), 1.0f))};
}

// The same surface cut by a few edges: a depth step at x = 213, a crease
// at x = 427, a horizontal depth step on the left half and a disc of
// background.
Surface surface_with_edges(int x, int y) {
  Surface s = smooth_surface(x, y);
  if (x >= 213) s.depth += 2.0f;
  if (x >= 427) s.normal = glm::normalize(s.normal + glm::vec3(0.8f, 0.0f, 0.0f));
  if (y >= 240 && x < 213) s.depth *= 0.7f;
  const float dx = float(x) - 320.0f, dy = float(y) - 120.0f;
  if (dx * dx + dy * dy < 40.0f * 40.0f) s.depth = std::numeric_limits<float>::infinity();
  return s;
}

FilterInput make_scene(Surface (*surface)(int, int)) {
  FilterInput in;
  in.width = kWidth, in.height = kHeight;
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x) {
      const Surface s = surface(x, y);
      // Smooth irradiance times the interleaved-sampling noise of 3 x 3 VPL sets.
      const float noise = 0.3f * (uniform(x % 3, y % 3, 1) - 0.5f);
      const float shade = 1.0f + 0.5f * std::sin(0.01f * float(x) + 0.008f * float(y));
      in.depth.push_back(s.depth);
      in.normal.push_back(s.normal);
      in.value.push_back(glm::vec3(shade, 0.8f, 0.6f) * (1.0f + noise));
    }
  return in;
}

// CPU time of this thread, not wall time: the benchmark runs on machines
// shared with compilers, and time slices given to others must not count.
double thread_cpu_ns() {
  timespec t;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return double(t.tv_sec) * 1e9 + double(t.tv_nsec);
}

template <class F>
double median_ns_per_pixel(int runs, F&& filter) {
  std::vector<double> ns;
  for (int i = 0; i < runs; ++i) {
    const double start = thread_cpu_ns();
    filter();
    ns.push_back((thread_cpu_ns() - start) / (double(kWidth) * kHeight));
  }
  std::nth_element(ns.begin(), ns.begin() + runs / 2, ns.end());
  return ns[runs / 2];
}

struct Row {
  int width;
  double smooth_ns, edges_ns, edges_fast_share, brute_ns;
};

Row measure(int window, int runs, const FilterInput& smooth, const FilterInput& edges) {
  FilterSettings s;
  s.window = window;
  const Rect all{0, 0, kWidth, kHeight};
  std::vector<glm::vec3> out(size_t(kWidth) * kHeight);
  FilterStats stats;
  Row row{window, 0, 0, 0, 0};
  row.smooth_ns = median_ns_per_pixel(runs, [&] { filter_discontinuity(smooth, s, all, out); });
  row.edges_ns = median_ns_per_pixel(runs, [&] { filter_discontinuity(edges, s, all, out, &stats); });
  row.edges_fast_share = double(stats.fast_pixels) / (double(kWidth) * kHeight);
  row.brute_ns = median_ns_per_pixel(std::max(1, runs / 3), [&] { filter_brute_force(edges, s, all, out); });
  return row;
}

void print_table(const std::vector<Row>& rows) {
  std::printf("discontinuity buffer, %d x %d region, median thread CPU ns per pixel\n", kWidth, kHeight);
  std::printf("%6s | %12s %6s | %12s %6s %7s | %12s\n", "width", "smooth ns/px", "ratio", "edges ns/px", "ratio",
              "fast %", "brute ns/px");
  for (const Row& r : rows)
    std::printf("%6d | %12.2f %6.2f | %12.2f %6.2f %7.1f | %12.2f\n", r.width, r.smooth_ns,
                r.smooth_ns / rows[0].smooth_ns, r.edges_ns, r.edges_ns / rows[0].edges_ns,
                100.0 * r.edges_fast_share, r.brute_ns);
  const double spread = rows.back().smooth_ns / rows.front().smooth_ns;
  std::printf("fast path, width %d vs %d: %.2f (target within 1.20)\n", rows.back().width, rows.front().width,
              spread);
}

}  // namespace

int main(int argc, char** argv) {
  const int runs = argc > 1 ? std::max(1, std::atoi(argv[1])) : 9;
  const FilterInput smooth = make_scene(smooth_surface), edges = make_scene(surface_with_edges);
  std::vector<Row> rows;
  for (int window : {3, 5, 6, 7, 9}) rows.push_back(measure(window, runs, smooth, edges));
  print_table(rows);
  return 0;
}
