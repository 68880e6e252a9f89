#include "image/metrics.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace igi {

static void check_sizes(const Image& a, const Image& b) {
  if (a.width != b.width || a.height != b.height)
    throw std::invalid_argument("image sizes differ: " + std::to_string(a.width) + "x" + std::to_string(a.height) +
                                " vs " + std::to_string(b.width) + "x" + std::to_string(b.height));
}

double rel_mse(const Image& image, const Image& reference, float epsilon) {
  check_sizes(image, reference);
  double sum = 0.0;
  for (size_t i = 0; i < image.pixels.size(); ++i)
    for (int c = 0; c < 3; ++c) {
      double d = image.pixels[i][c] - reference.pixels[i][c];
      double r = reference.pixels[i][c];
      sum += d * d / (r * r + epsilon);
    }
  return sum / (3.0 * double(image.pixels.size()));
}

double rel_mse_two_references(const Image& image, const Image& a, const Image& b, float epsilon) {
  check_sizes(image, a);
  check_sizes(image, b);
  const int w = image.width, h = image.height;
  double sum = 0.0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      // r: both references' mean over the pixel's neighbours (8 inside the image).
      glm::dvec3 r(0.0);
      int n = 0;
      for (int j = std::max(0, y - 1); j <= std::min(h - 1, y + 1); ++j)
        for (int i = std::max(0, x - 1); i <= std::min(w - 1, x + 1); ++i) {
          if (i == x && j == y) continue;
          r += glm::dvec3(a.at(i, j)) + glm::dvec3(b.at(i, j));
          n += 2;
        }
      if (n > 0) r /= double(n);
      const glm::vec3 v = image.at(x, y), ra = a.at(x, y), rb = b.at(x, y);
      for (int c = 0; c < 3; ++c) sum += (double(v[c]) - ra[c]) * (double(v[c]) - rb[c]) / (r[c] * r[c] + epsilon);
    }
  return sum / (3.0 * double(image.pixels.size()));
}

double rmse(const Image& image, const Image& reference) {
  check_sizes(image, reference);
  double sum = 0.0;
  for (size_t i = 0; i < image.pixels.size(); ++i)
    for (int c = 0; c < 3; ++c) {
      double d = image.pixels[i][c] - reference.pixels[i][c];
      sum += d * d;
    }
  return std::sqrt(sum / (3.0 * double(image.pixels.size())));
}

double max_abs_error(const Image& image, const Image& reference) {
  check_sizes(image, reference);
  double m = 0.0;
  for (size_t i = 0; i < image.pixels.size(); ++i)
    for (int c = 0; c < 3; ++c) m = std::max(m, double(std::abs(image.pixels[i][c] - reference.pixels[i][c])));
  return m;
}

Image abs_difference(const Image& a, const Image& b) {
  check_sizes(a, b);
  Image d(a.width, a.height);
  for (size_t i = 0; i < a.pixels.size(); ++i) d.pixels[i] = glm::abs(a.pixels[i] - b.pixels[i]);
  return d;
}

}  // namespace igi
