#pragma once
// Image error against a reference, per pixel and channel.
#include "image/image.h"

namespace igi {

// relMSE = mean over pixels and channels of (x - r)^2 / (r^2 + epsilon).
inline constexpr float kRelMseEpsilon = 1e-2f;
double rel_mse(const Image& image, const Image& reference, float epsilon = kRelMseEpsilon);
double rmse(const Image& image, const Image& reference);
double max_abs_error(const Image& image, const Image& reference);
// Per-pixel absolute difference, for diff images.
Image abs_difference(const Image& a, const Image& b);

}  // namespace igi
