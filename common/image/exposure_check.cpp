#include "image/exposure_check.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "sampling/warp.h"

namespace igi {

namespace {

constexpr float kBlack = 1e-6f;          // luminance that counts as no light
constexpr float kMostlyClipped = 0.5f;   // of the lit pixels
constexpr float kShownWhite = 0.98777f;  // display-linear at 253.5 of 255 in sRGB: shown as 254 or 255
constexpr float kFewLit = 0.75f;         // black pixels past this share: a dark scene with a lamp in view, not white
constexpr float kTooDark = 0.02f;        // the 99th percentile, after exposure: under 1/50 of white
constexpr float kTarget = 0.9f;          // where the suggested exposure puts the 99th percentile
constexpr double kMiddleGrey = 0.18;     // where the meter puts the log-average

std::string number(double x) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3g", x);
  return text;
}

// "--ev 7.6": a factor as the option that gives it, in stops.
std::string ev(float factor) {
  char text[32];
  std::snprintf(text, sizeof text, "--ev %.1f", std::log2(double(factor)) + 0.0);  // + 0.0: never "-0.0"
  return text;
}

}  // namespace

float metered_exposure(const Image& image) {
  double log_sum = 0.0;
  size_t lit = 0;
  for (const glm::vec3& p : image.pixels) {
    const float l = luminance(p);
    if (!(l > kBlack) || !std::isfinite(l)) continue;
    log_sum += std::log(double(l));
    ++lit;
  }
  if (lit == 0) return 1.0f;
  const double stops = std::log2(kMiddleGrey) - log_sum / double(lit) / std::log(2.0);
  return float(std::exp2(std::clamp(stops, -double(kExposureStops), double(kExposureStops))));
}

float exposure_for(const Image& image, const ExposureChoice& choice) {
  return choice.metered ? metered_exposure(image) : choice.factor;
}

ExposureFigures exposure_figures(const Image& image, float exposure, ViewTransform view) {
  ExposureFigures f;
  if (image.pixels.empty()) return f;
  std::vector<float> lum;
  lum.reserve(image.pixels.size());
  size_t black = 0, clipped = 0;
  for (const glm::vec3& p : image.pixels) {
    const glm::vec3 shown = exposure * p;
    const float l = std::isfinite(luminance(shown)) ? luminance(shown) : 0.0f;
    lum.push_back(l);
    black += !(luminance(p) > kBlack);
    const glm::vec3 white = view_transform(shown, view);
    clipped += std::max({white.x, white.y, white.z}) >= kShownWhite;
  }
  const size_t at = std::min(lum.size() - 1, size_t(0.99 * double(lum.size())));
  std::nth_element(lum.begin(), lum.begin() + ptrdiff_t(at), lum.end());
  f.black = float(black) / float(lum.size());
  f.clipped = black < lum.size() ? float(clipped) / float(lum.size() - black) : 0.0f;
  f.bright = lum[at];
  f.suggested_exposure = f.bright > 0.0f ? exposure * kTarget / f.bright : exposure;
  return f;
}

std::optional<std::string> exposure_advice(const Image& image, const ExposureContext& c) {
  const ExposureFigures f = exposure_figures(image, c.exposure, c.view);
  const bool photometric = c.photometric;
  if (f.black >= 1.0f && c.framing_camera)
    return std::string("the image is black: the file has no camera, and the one framing it from outside sees "
                       "only the unlit outside of a closed room; place one inside with --camera FILE (the "
                       "window's F5 saves one)");
  if (f.black >= 1.0f)
    return std::string("the image is black: no light reaches the camera. A file exported without its lamps "
                       "(Blender: Include > Punctual Lights) or its world can be lit with --environment 1,1,1") +
           (c.file_lamps && photometric ? "; lamps written in W/sr and W/m^2 need --light-units radiometric" : "");
  if (!c.clips || c.metered) return std::nullopt;
  const std::string exposure = ev(f.suggested_exposure) + " (or --exposure auto)";
  if (f.clipped > kMostlyClipped && f.black < kFewLit)
    return "the image is mostly white: " + number(100.0 * f.clipped) + " % of its lit pixels clip at " +
           ev(c.exposure) + "; " + exposure + " would show them" +
           (c.file_lamps && !photometric ? ", or --light-units photometric if the lamps are in candela and lux (glTF's, Blender's)" : "");
  if (f.bright < kTooDark)
    return "the image is nearly black: its brightest 1 % is under " + number(100.0 * kTooDark) +
           " % of white at " + ev(c.exposure) + "; " + exposure + " would show it" +
           (c.file_lamps && photometric ? ", or --light-units radiometric if the lamps are in W/sr and W/m^2" : "");
  return std::nullopt;
}

}  // namespace igi
