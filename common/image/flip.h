#pragma once
// FLIP (LDR), the perceptual difference of Andersson, Nilsson, Akenine-Moeller,
// Oskarsson, Astroem and Fairchild, "FLIP: A Difference Evaluator for
// Alternating Images", HPG 2020, following NVIDIA's reference flip.py.
//
// Per pixel, in [0, 1] (0: no visible difference):
//   colour   the images in YyCxCz are blurred by the contrast sensitivity
//            functions of the viewer (achromatic, red-green, blue-yellow),
//            clamped to the sRGB gamut, taken to L*a*b* with the Hunt
//            adjustment, compared by HyAB and remapped through (pc, pt).
//   feature  edges (first Gaussian derivative) and points (second) of the
//            achromatic channel; their largest difference.
//   flip     colour^(1 - feature).
// Viewing conditions enter as pixels per degree of visual angle: 67 is a
// 0.7 m wide 4K monitor seen from 0.7 m (the paper's default).
//
// Inputs are sRGB-encoded values in [0, 1] (what a display shows); HDR
// renders go through tonemap_for_flip first. Edges are clamped (the image
// is extended by its border pixels) for every filter.
#include <vector>

#include "image/image.h"

namespace igi {

inline constexpr float kFlipPixelsPerDegree = 67.0f;

struct FlipMap {
  int width = 0;
  int height = 0;
  std::vector<float> error;  // row-major, row 0 at the top
  double mean() const;
};

// Both images sRGB-encoded in [0, 1] and of the same size (else throws
// std::invalid_argument). FLIP is not symmetric: `reference` is the ground truth.
FlipMap flip_ldr(const Image& test, const Image& reference, float pixels_per_degree = kFlipPixelsPerDegree);

// The LDR display of a linear render, as the PNG output makes it: scale by
// exposure, clamp to [0, 1], encode sRGB.
Image tonemap_for_flip(const Image& linear, float exposure = 1.0f);

// Mean FLIP of two linear renders after tonemap_for_flip.
double mean_flip(const Image& test, const Image& reference, float exposure = 1.0f,
                 float pixels_per_degree = kFlipPixelsPerDegree);

}  // namespace igi
