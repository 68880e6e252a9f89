#include "vpl/start_guide.h"

#include <algorithm>

#include "sampling/content_hash.h"

namespace igi {
void StartGuide::guide(uint32_t light, Resolution resolution, const std::vector<float>& values, float floor) {
  size_t cells = 1;
  for (int r : resolution) cells *= size_t(std::max(1, r));
  double total = 0.0;
  for (size_t c = 0; c < cells && c < values.size(); ++c) total += std::max(0.0f, values[c]);
  if (!(total > 0.0) || values.size() != cells || find(light)) return;
  Grid grid;
  grid.light = light;
  for (int k = 0; k < kDims; ++k) grid.resolution[k] = std::max(1, resolution[k]);
  // The cells' probabilities, then each level's sums over the dimensions after it.
  std::vector<float> mass(cells);
  for (size_t c = 0; c < cells; ++c)
    mass[c] = float(double(floor) / double(cells) + (1.0 - double(floor)) * double(std::max(0.0f, values[c])) / total);
  ContentHasher h;
  h.add(light);
  h.add(grid.resolution);
  h.add_bytes(mass.data(), mass.size() * sizeof(float));
  for (int k = kDims - 1; k >= 0; --k) {
    const size_t r = size_t(grid.resolution[k]), prefixes = mass.size() / r;
    std::vector<float> sums(prefixes);
    grid.levels[k].reserve(prefixes);
    for (size_t p = 0; p < prefixes; ++p) {
      const std::vector<float> row(mass.begin() + long(p * r), mass.begin() + long((p + 1) * r));
      grid.levels[k].emplace_back(row);
      float sum = 0.0f;
      for (float m : row) sum += m;
      sums[p] = sum;
    }
    mass = std::move(sums);
  }
  grids_.push_back(std::move(grid));
  hash_ = combine_content_hashes(hash_, h.value());
}

const StartGuide::Grid* StartGuide::find(uint32_t light) const {
  for (const Grid& g : grids_)
    if (g.light == light) return &g;
  return nullptr;
}

StartNumbers StartGuide::warp(uint32_t light, StartNumbers u, float& density) const {
  density = 1.0f;
  const Grid* grid = find(light);
  if (!grid) return u;
  std::array<float, kDims> v = dims(u);
  size_t prefix = 0;
  for (int k = 0; k < kDims; ++k) {
    const int r = grid->resolution[k];
    const Distribution1D& d = grid->levels[k][prefix];
    float remapped = 0.0f;
    const uint32_t i = d.sample(v[k], remapped);
    density *= d.probability(i) * float(r);
    v[k] = std::min((float(i) + remapped) / float(r), 0x1.fffffep-1f);
    prefix = prefix * size_t(r) + i;
  }
  return numbers(v);
}

float StartGuide::density(uint32_t light, StartNumbers u) const {
  const Grid* grid = find(light);
  if (!grid) return 1.0f;
  const std::array<float, kDims> v = dims(u);
  float density = 1.0f;
  size_t prefix = 0;
  for (int k = 0; k < kDims; ++k) {
    const int r = grid->resolution[k];
    const uint32_t i = uint32_t(std::clamp(int(v[k] * float(r)), 0, r - 1));
    density *= grid->levels[k][prefix].probability(i) * float(r);
    prefix = prefix * size_t(r) + i;
  }
  return density;
}

}  // namespace igi
