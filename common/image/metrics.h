#pragma once
// Image error against a reference, per pixel and channel.
#include "image/image.h"

namespace igi {

// relMSE = mean over pixels and channels of (x - r)^2 / (r^2 + epsilon).
inline constexpr float kRelMseEpsilon = 1e-2f;
double rel_mse(const Image& image, const Image& reference, float epsilon = kRelMseEpsilon);
// relMSE against a reference known through two independent, unbiased renders
// a and b of it: the mean of (x - a)(x - b) / (r^2 + epsilon). The product's
// expectation is (x - L)^2 for the true image L, so the references' own
// noise, which rel_mse adds to the figure (a 4096-spp pt reference of the
// glass scene adds ~0.0009 at 128x128, about igi's own error at 256 passes),
// cancels; it can come out slightly negative when x is that close. r is the
// references' mean over the pixel's 8 neighbours, not the pixel itself:
// noise the numerator shares with the denominator biased the figure by ~20 %
// where the references' noise outweighs the image's error.
double rel_mse_two_references(const Image& image, const Image& a, const Image& b, float epsilon = kRelMseEpsilon);
double rmse(const Image& image, const Image& reference);
double max_abs_error(const Image& image, const Image& reference);
// Per-pixel absolute difference, for diff images.
Image abs_difference(const Image& a, const Image& b);

}  // namespace igi
