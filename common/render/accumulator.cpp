#include "render/accumulator.h"

#include <algorithm>
#include <stdexcept>

namespace igi {

void Accumulator::add(const Image& pass, double weight) {
  if (pass.width != width_ || pass.height != height_) throw std::invalid_argument("accumulator: pass size differs");
  for (size_t i = 0; i < sum_.size(); ++i) sum_[i] += glm::dvec3(pass.pixels[i]) * weight;
  weight_ += weight;
}

Image Accumulator::resolve() const {
  Image image(width_, height_);
  if (weight_ <= 0.0) return image;
  for (size_t i = 0; i < sum_.size(); ++i) image.pixels[i] = glm::vec3(sum_[i] / weight_);
  return image;
}

void Accumulator::reset() {
  std::fill(sum_.begin(), sum_.end(), glm::dvec3(0.0));
  weight_ = 0.0;
}

}  // namespace igi
