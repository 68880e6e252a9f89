#pragma once
// What a finished render says about its light: an image all black, too dark
// to see, or mostly clipped at its exposure is named at the end of the
// render, with the option that fixes it (a file's lamps read in the wrong
// units come out 683 times too bright or too dark).
#include <optional>
#include <string>

#include "image/image.h"

namespace igi {

struct ExposureFigures {
  float black = 0.0f;    // fraction of pixels with no light (luminance <= 1e-6)
  float clipped = 0.0f;  // fraction of the others with a channel at or over 1 after the exposure
  float bright = 0.0f;   // the 99th percentile of luminance after the exposure
  float suggested_exposure = 1.0f;  // puts that percentile at 0.9
};
ExposureFigures exposure_figures(const Image& image, float exposure);

struct ExposureContext {
  float exposure = 1.0f;
  bool clips = true;        // written as 8-bit sRGB (a .png): clipping and darkness show
  bool file_lamps = false;   // a glTF file's lamps lit it (--light-units applies)
  bool photometric = true;   // and were read in candela and lux (--light-units photometric)
  bool framing_camera = false;  // the file had no camera: the loader framed its bounds from outside
};

// One line for the user, or nothing when the image looks exposed: black
// (always said), or, when `clips`, over half the lit pixels clipped (a
// quarter of the image lit at least: a lamp in view of a dark room is not a
// white image) or the brightest 1 % under 0.02.
std::optional<std::string> exposure_advice(const Image& image, const ExposureContext& context);

}  // namespace igi
