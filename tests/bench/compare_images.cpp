// igi-compare: error figures of rendered images against a reference, as the
// accuracy benchmark computes them (image/metrics.h, image/flip.h).
//
//   igi-compare REFERENCE IMAGE [IMAGE ...]
//
// Prints, per image: relMSE (epsilon 0.01), RMSE, mean LDR-FLIP at 67 pixels
// per degree, and the ratio of its mean luminance to the reference's.
#include <cstdio>

#include "image/flip.h"
#include "image/metrics.h"
#include "sampling/warp.h"

int main(int argc, char** argv) {
  if (argc < 3) {
    std::fprintf(stderr, "usage: %s REFERENCE IMAGE [IMAGE ...]\n", argv[0]);
    return 2;
  }
  try {
    const igi::Image reference = igi::read_image(argv[1]);
    const double reference_mean = igi::luminance(reference.mean());
    std::printf("%-40s %10s %10s %8s %8s\n", "image", "relMSE", "RMSE", "FLIP", "mean");
    for (int i = 2; i < argc; ++i) {
      const igi::Image image = igi::read_image(argv[i]);
      std::printf("%-40s %10.5f %10.5f %8.4f %8.4f\n", argv[i], igi::rel_mse(image, reference),
                  igi::rmse(image, reference), igi::mean_flip(image, reference),
                  igi::luminance(image.mean()) / reference_mean);
    }
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "igi-compare: %s\n", e.what());
    return 1;
  }
}
