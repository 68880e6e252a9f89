#pragma once
// Discrete distribution proportional to non-negative weights (light power).
#include <cstddef>
#include <cstdint>
#include <vector>

namespace igi {

class Distribution1D {
 public:
  Distribution1D() = default;
  explicit Distribution1D(const std::vector<float>& weights);
  // Index with probability weight/total; u in [0,1).
  uint32_t sample(float u) const;
  // The same, and where u fell inside the index's share, remapped to [0, 1)
  // (a second number from the same sample, as pbrt's continuous sampling does).
  uint32_t sample(float u, float& remapped) const;
  float probability(uint32_t index) const { return total_ > 0 ? weights_[index] / total_ : 0.0f; }
  float total() const { return total_; }
  size_t size() const { return weights_.size(); }

 private:
  std::vector<float> weights_;
  std::vector<double> cdf_;  // cdf_[i] = sum of weights before i+1, normalised
  float total_ = 0.0f;
};

}  // namespace igi
