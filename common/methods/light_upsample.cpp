#include "methods/light_upsample.h"

#include <algorithm>
#include <cmath>

namespace igi {
namespace {

// floor(a / b) for b > 0, a of either sign.
int floor_div(int a, int b) { return a >= 0 ? a / b : -((-a + b - 1) / b); }

// Where image pixel x lies on the lattice: the lattice pixel at or before it, and how far towards the next.
struct Position {
  int cell;
  float fraction;
};
Position lattice_position(int x, int step) {
  const int from = x - step / 2;  // lattice pixel c stands for image pixel c step + step / 2
  const int cell = floor_div(from, step);
  return {cell, float(from - cell * step) / float(step)};
}

bool same_surface(const GSample& pixel, const GSample& sample) {
  if (!sample.valid()) return false;
  const glm::vec3 n = sample.surface.geometric_normal;
  if (glm::dot(pixel.surface.geometric_normal, n) < upsample::kNormalCos) return false;
  const float plane = std::abs(glm::dot(n, pixel.surface.position - sample.surface.position));
  return plane <= upsample::kPlaneTolerance * pixel.depth;
}

}  // namespace

TileJob lattice_cells(const TileJob& job, int step, int width, int height, int border) {
  const Position x0 = lattice_position(job.x, step), x1 = lattice_position(job.x + job.w - 1, step);
  const Position y0 = lattice_position(job.y, step), y1 = lattice_position(job.y + job.h - 1, step);
  // The 4 x 4 around each pixel: one cell before its own, two after.
  const int cx0 = std::max(0, x0.cell - 1), cy0 = std::max(0, y0.cell - 1);
  const int cx1 = std::min(lattice_extent(width, step), x1.cell + 3);
  const int cy1 = std::min(lattice_extent(height, step), y1.cell + 3);
  return TileJob{cx0, cy0, cx1 - cx0, cy1 - cy0, border};
}

glm::vec3 upsample_light(const LatticeLight& l, int layer, const GSample& g, int x, int y) {
  if (layer >= l.lattice.layer_count() || !g.valid()) return glm::vec3(0.0f);
  const int step = l.lattice.region.step;
  const Position px = lattice_position(x, step), py = lattice_position(y, step);
  const int last_x = l.cells.x + l.cells.w - 1, last_y = l.cells.y + l.cells.h - 1;
  auto sample = [&](int cx, int cy) -> const GSample* {
    if (cx < l.cells.x || cy < l.cells.y || cx > last_x || cy > last_y) return nullptr;
    return &l.lattice.at(layer, l.lattice.region.index(cx, cy));
  };
  auto light = [&](int cx, int cy) {
    return l.light[size_t(layer) * l.lattice.region.pixels() + l.lattice.region.index(cx, cy)];
  };
  // The 2 x 2 around the pixel on its surface, bilinearly (those of weight 0,
  // on the far side of a pixel on the lattice's row or column, only when the one on it fails: by distance below).
  glm::vec3 sum(0.0f);
  float weight = 0.0f;
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 2; ++i) {
      const int cx = px.cell + i, cy = py.cell + j;
      const GSample* s = sample(cx, cy);
      if (!s || !same_surface(g, *s)) continue;
      const float w = (i ? px.fraction : 1.0f - px.fraction) * (j ? py.fraction : 1.0f - py.fraction);
      sum += w * light(cx, cy);
      weight += w;
    }
  if (weight > 0.0f) return sum / weight;
  sum = glm::vec3(0.0f);
  // The 4 x 4, by distance.
  for (int cy = py.cell - 1; cy <= py.cell + 2; ++cy)
    for (int cx = px.cell - 1; cx <= px.cell + 2; ++cx) {
      const GSample* s = sample(cx, cy);
      if (!s || !same_surface(g, *s)) continue;
      const float dx = float(cx - px.cell) - px.fraction, dy = float(cy - py.cell) - py.fraction;
      const float w = 1.0f / (1.0f + dx * dx + dy * dy);
      sum += w * light(cx, cy);
      weight += w;
    }
  if (weight > 0.0f) return sum / weight;
  // Nothing of its surface near: the nearest sample that has a surface.
  float nearest = INFINITY;
  glm::vec3 value(0.0f);
  for (int cy = py.cell - 1; cy <= py.cell + 2; ++cy)
    for (int cx = px.cell - 1; cx <= px.cell + 2; ++cx) {
      const GSample* s = sample(cx, cy);
      if (!s || !s->valid()) continue;
      const float dx = float(cx - px.cell) - px.fraction, dy = float(cy - py.cell) - py.fraction;
      if (dx * dx + dy * dy < nearest) {
        nearest = dx * dx + dy * dy;
        value = light(cx, cy);
      }
    }
  return value;
}

}  // namespace igi
