#include "image/exposure_check.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

namespace igi {

namespace {

constexpr float kBlack = 1e-6f;          // luminance that counts as no light
constexpr float kMostlyClipped = 0.5f;   // of the lit pixels
constexpr float kFewLit = 0.75f;         // black pixels past this share: a dark scene with a lamp in view, not white
constexpr float kTooDark = 0.02f;        // the 99th percentile, after exposure: under 1/50 of white
constexpr float kTarget = 0.9f;          // where the suggested exposure puts the 99th percentile

float luminance(glm::vec3 c) { return 0.2126f * c.x + 0.7152f * c.y + 0.0722f * c.z; }

std::string number(double x) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3g", x);
  return text;
}

}  // namespace

ExposureFigures exposure_figures(const Image& image, float exposure) {
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
    clipped += std::max({shown.x, shown.y, shown.z}) >= 1.0f;
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
  const ExposureFigures f = exposure_figures(image, c.exposure);
  const bool photometric = c.photometric;
  if (f.black >= 1.0f && c.framing_camera)
    return std::string("the image is black: the file has no camera, and the one framing it from outside sees "
                       "only the unlit outside of a closed room; place one inside with --camera FILE (the "
                       "window's F5 saves one)");
  if (f.black >= 1.0f)
    return std::string("the image is black: no light reaches the camera. A file exported without its lamps "
                       "(Blender: Include > Punctual Lights) or its world can be lit with --environment 1,1,1") +
           (c.file_lamps && photometric ? "; lamps written in W/sr and W/m^2 need --light-units radiometric" : "");
  if (!c.clips) return std::nullopt;
  const std::string exposure = "--exposure " + number(f.suggested_exposure);
  if (f.clipped > kMostlyClipped && f.black < kFewLit)
    return "the image is mostly white: " + number(100.0 * f.clipped) + " % of its lit pixels clip at exposure " +
           number(c.exposure) + "; " + exposure + " would show them" +
           (c.file_lamps && !photometric ? ", or --light-units photometric if the lamps are in candela and lux (glTF's, Blender's)" : "");
  if (f.bright < kTooDark)
    return "the image is nearly black: its brightest 1 % is under " + number(100.0 * kTooDark) +
           " % of white at exposure " + number(c.exposure) + "; " + exposure + " would show it" +
           (c.file_lamps && photometric ? ", or --light-units radiometric if the lamps are in W/sr and W/m^2" : "");
  return std::nullopt;
}

}  // namespace igi
