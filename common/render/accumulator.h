#pragma once
// Progressive refinement: passes are added as weighted sums and normalised
// only on read-out, so passes merge in any order.
#include "image/image.h"

namespace igi {

class Accumulator {
 public:
  Accumulator(int width, int height) : sum_(size_t(width) * height, glm::dvec3(0.0)), width_(width), height_(height) {}
  // `pass` holds per-pixel means over `weight` samples.
  void add(const Image& pass, double weight);
  Image resolve() const;
  void reset();
  double weight() const { return weight_; }

 private:
  std::vector<glm::dvec3> sum_;
  int width_, height_;
  double weight_ = 0.0;
};

}  // namespace igi
