#include "importance/resample.h"

namespace igi::importance {

void systematic_counts(std::span<const double> weights, int n, double u, std::vector<int>& counts) {
  counts.assign(weights.size(), 0);
  double total = 0.0;
  for (double w : weights) total += w;
  if (n <= 0 || !(total > 0.0)) return;
  const double step = total / double(n);
  double position = u * step, cumulative = 0.0;
  size_t c = 0;
  for (int m = 0; m < n; ++m, position += step) {
    // The entry whose interval [cumulative, cumulative + w_c) holds the position;
    // rounding at the very end falls to the last entry with weight.
    while (c + 1 < weights.size() && cumulative + weights[c] <= position) cumulative += weights[c++];
    size_t pick = c;
    while (weights[pick] <= 0.0 && pick > 0) --pick;
    ++counts[pick];
  }
}

}  // namespace igi::importance
