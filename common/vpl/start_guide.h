#pragma once
// Where on a light its paths start, learned for the view.
//
// A light path's start draws, once its light is chosen, two pairs of numbers
// (vpl/light_path.h): `point` (where on the light: a point of an area light,
// the disc a directional light or the sky shines from) and `direction`
// (which way: an area light's cosine lobe, a point light's sphere, the
// sky's direction). The plain rule takes them uniform on [0, 1)^4. A guide
// replaces, for the lights it holds, that uniform density by a piecewise-
// constant one over a grid of cells,
//   q(u) = n p_cell(u),   p_cell = floor / n + (1 - floor) value_cell / sum of values,
// n cells, and warps the path's own numbers to it (dimension by dimension,
// each conditioned on the cells before it, as pbrt's 2-D piecewise-constant
// distributions do). The path's power is divided by q(u), so every set stays
// an unbiased estimate of the light; the floor keeps every start possible
// (q >= floor), so a region the learning missed costs variance, never bias.
//
// The warp follows the numbers and the cell values continuously, but where a
// boundary between the first dimension's columns crosses a path's number:
// there its other coordinates follow another column's conditional and jump.
// Values changed within 1 % (a camera that moved a little) moved starts 0.12
// of a cell on average, and 5 % of them over a quarter cell
// (StartGuide.AStartMovesALittleWhenTheValuesChangeALittle). A guide is
// plain data, built the same way by every peer (importance/view_guide.h),
// and hashed with the VPL sets.
#include <array>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "sampling/distribution.h"

namespace igi {

// The numbers a path's start draws after its light is chosen.
struct StartNumbers {
  glm::vec2 point{0.5f};
  glm::vec2 direction{0.5f};
};

class StartGuide {
 public:
  // The grid's dimensions, in the order of its conditionals: the direction
  // first, so that a light whose start draws both (the sky) keeps its
  // directions one stratified net, then the point given the direction.
  static constexpr int kDims = 4;  // direction.x, direction.y, point.x, point.y
  using Resolution = std::array<int, kDims>;
  static std::array<float, kDims> dims(StartNumbers u) { return {u.direction.x, u.direction.y, u.point.x, u.point.y}; }
  static StartNumbers numbers(const std::array<float, kDims>& v) { return StartNumbers{{v[2], v[3]}, {v[0], v[1]}}; }

  // Light `light` (a LightSet entry, once) starts by the density above over a
  // grid of `resolution` cells (1 along a dimension it leaves uniform);
  // `values` holds one non-negative value a cell, row-major with the last
  // dimension fastest. Ignored when every value is 0.
  void guide(uint32_t light, Resolution resolution, const std::vector<float>& values, float floor);

  bool guides(uint32_t light) const { return find(light) != nullptr; }
  bool empty() const { return grids_.empty(); }
  // `u` warped to the light's density; `density` its value q there (1 for a
  // light the guide does not hold, where u is returned unchanged).
  StartNumbers warp(uint32_t light, StartNumbers u, float& density) const;
  // q at `u`, as warp() reports it for the numbers it returns.
  float density(uint32_t light, StartNumbers u) const;
  uint64_t hash() const { return hash_; }

 private:
  struct Grid {
    uint32_t light = 0;
    Resolution resolution{1, 1, 1, 1};
    // Level k holds one distribution over dimension k's cells for every cell
    // of dimensions 0 .. k-1 (row-major): the marginals, then the conditionals.
    std::array<std::vector<Distribution1D>, kDims> levels;
  };
  const Grid* find(uint32_t light) const;

  std::vector<Grid> grids_;
  uint64_t hash_ = 0;
};

}  // namespace igi
