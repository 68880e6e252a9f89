#pragma once
// A window that shows one rendered image (igi-render --show).
#include <string>

#include "image/image.h"

namespace igi {

struct WindowOptions {
  std::string title = "igi-cluster";
  ToneMapping tone;  // as the image file shows it
  double seconds = 0.0;     // close after this long; 0: when the user closes it (or Esc)
  std::string screenshot;   // when set: save what the window shows as PNG, then close
};

// Blocks until the window closes. Throws std::runtime_error when none opens.
void show_image(const Image& image, const WindowOptions& options);

}  // namespace igi
