#pragma once
// A render's exposure: the meter that picks one from the image (--exposure
// auto, the window's default), and what a finished render says about its
// light: an image all black, too dark to see, or mostly clipped at a fixed
// exposure is named at the end of the render, with the option that fixes it
// (a file's lamps read in the wrong units come out 683 times too bright or
// too dark).
#include <optional>
#include <string>

#include "image/image.h"

namespace igi {

// Exposures span 2^-kExposureStops to 2^kExposureStops (--ev, the panel, the meter).
inline constexpr float kExposureStops = 24.0f;

// As a camera's averaging meter sets it: the factor that brings the
// log-average luminance of the image's lit pixels to middle grey (0.18), so
// a few bright windows or lamps in view barely move it. It reads the whole
// image in raster order, so an image gets the same exposure whoever rendered
// it (whole, tiled or distributed: the same pixels); never meter a tile. 1
// for an image with no light.
float metered_exposure(const Image& image);

// --exposure K, --ev S or auto: a fixed factor, or one metered from each image shown or written.
struct ExposureChoice {
  bool metered = false;
  float factor = 1.0f;
};
float exposure_for(const Image& image, const ExposureChoice& choice);

struct ExposureFigures {
  float black = 0.0f;    // fraction of pixels with no light (luminance <= 1e-6)
  float clipped = 0.0f;  // fraction of the others shown white: a channel at 254 of 255 or over
  float bright = 0.0f;   // the 99th percentile of luminance after the exposure
  float suggested_exposure = 1.0f;  // puts that percentile at 0.9 (a factor)
};
ExposureFigures exposure_figures(const Image& image, float exposure,
                                 ViewTransform view = ViewTransform::Standard);

struct ExposureContext {
  float exposure = 1.0f;
  bool metered = false;     // --exposure auto chose it: only black is said
  ViewTransform view = ViewTransform::Standard;
  bool clips = true;        // written as 8-bit sRGB (a .png): clipping and darkness show
  bool file_lamps = false;   // a glTF file's lamps lit it (--light-units applies)
  bool photometric = true;   // and were read in candela and lux (--light-units photometric)
  bool framing_camera = false;  // the file had no camera: the loader framed its bounds from outside
};

// One line for the user, or nothing when the image looks exposed: black
// (always said), or, when `clips` at a fixed exposure, over half the lit
// pixels clipped (a quarter of the image lit at least: a lamp in view of a
// dark room is not a white image) or the brightest 1 % under 0.02; the fix
// named is --ev in stops, or --exposure auto.
std::optional<std::string> exposure_advice(const Image& image, const ExposureContext& context);

}  // namespace igi
