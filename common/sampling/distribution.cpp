#include "sampling/distribution.h"

#include <algorithm>

namespace igi {

Distribution1D::Distribution1D(const std::vector<float>& weights) : weights_(weights) {
  double sum = 0.0;
  cdf_.reserve(weights.size());
  for (float w : weights) { sum += std::max(0.0f, w); cdf_.push_back(sum); }
  total_ = float(sum);
  if (sum > 0.0)
    for (double& c : cdf_) c /= sum;
}

uint32_t Distribution1D::sample(float u) const {
  auto it = std::upper_bound(cdf_.begin(), cdf_.end(), double(u));
  uint32_t i = uint32_t(std::min<size_t>(it - cdf_.begin(), cdf_.size() - 1));
  while (i > 0 && weights_[i] <= 0.0f) --i;  // never return a zero-weight entry
  while (i + 1 < weights_.size() && weights_[i] <= 0.0f) ++i;
  return i;
}

uint32_t Distribution1D::sample(float u, float& remapped) const {
  const uint32_t i = sample(u);
  const double lo = i == 0 ? 0.0 : cdf_[i - 1], hi = cdf_[i];
  remapped = hi > lo ? float(std::clamp((double(u) - lo) / (hi - lo), 0.0, 0x1.fffffep-1)) : 0.5f;
  return i;
}

}  // namespace igi
