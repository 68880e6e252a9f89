// igi-compare: error figures of rendered images against a reference, as the
// accuracy benchmark computes them (image/metrics.h, image/flip.h).
//
//   igi-compare [--flip-maps] [--second-reference REF2] REFERENCE IMAGE [IMAGE ...]
//
// Prints, per image: relMSE (epsilon 0.01), RMSE, mean LDR-FLIP at 67 pixels
// per degree, and the ratio of its mean luminance to the reference's. With
// --flip-maps, writes each image's per-pixel FLIP beside it as IMAGE.flip.png
// (white = 1). With --second-reference, an independent render of the same
// reference, a last column relMSE2: relMSE with both references' noise
// cancelled (image/metrics.h, rel_mse_two_references).
#include <cstdio>
#include <string>

#include "image/flip.h"
#include "image/metrics.h"
#include "sampling/warp.h"

int main(int argc, char** argv) {
  bool maps = false;
  const char* second = nullptr;
  for (;;) {
    if (argc > 1 && std::string(argv[1]) == "--flip-maps") {
      maps = true;
      ++argv, --argc;
    } else if (argc > 2 && std::string(argv[1]) == "--second-reference") {
      second = argv[2];
      argv += 2, argc -= 2;
    } else {
      break;
    }
  }
  if (argc < 3) {
    std::fprintf(stderr, "usage: igi-compare [--flip-maps] [--second-reference REF2] REFERENCE IMAGE [IMAGE ...]\n");
    return 2;
  }
  try {
    const igi::Image reference = igi::read_image(argv[1]);
    const igi::Image reference2 = second ? igi::read_image(second) : igi::Image();
    const double reference_mean = igi::luminance(reference.mean());
    std::printf("%-40s %10s %10s %8s %8s%s\n", "image", "relMSE", "RMSE", "FLIP", "mean", second ? "    relMSE2" : "");
    for (int i = 2; i < argc; ++i) {
      const igi::Image image = igi::read_image(argv[i]);
      const igi::FlipMap flip = igi::flip_ldr(igi::tonemap_for_flip(image), igi::tonemap_for_flip(reference));
      std::printf("%-40s %10.5f %10.5f %8.4f %8.4f", argv[i], igi::rel_mse(image, reference),
                  igi::rmse(image, reference), flip.mean(), igi::luminance(image.mean()) / reference_mean);
      if (second) std::printf(" %10.5f", igi::rel_mse_two_references(image, reference, reference2));
      std::printf("\n");
      if (!maps) continue;
      igi::Image map(flip.width, flip.height);
      for (size_t p = 0; p < map.pixels.size(); ++p) map.pixels[p] = glm::vec3(igi::srgb_to_linear(flip.error[p]));
      igi::write_image(map, std::string(argv[i]) + ".flip.png");
    }
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "igi-compare: %s\n", e.what());
    return 1;
  }
}
