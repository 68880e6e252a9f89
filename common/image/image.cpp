#include "image/image.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <OpenImageIO/imageio.h>

namespace igi {

glm::vec3 Image::mean() const {
  glm::dvec3 sum(0.0);
  for (const glm::vec3& p : pixels) sum += glm::dvec3(p);
  return pixels.empty() ? glm::vec3(0.0f) : glm::vec3(sum / double(pixels.size()));
}

float linear_to_srgb(float v) {
  v = std::clamp(v, 0.0f, 1.0f);
  return v <= 0.0031308f ? 12.92f * v : 1.055f * std::pow(v, 1.0f / 2.4f) - 0.055f;
}

float srgb_to_linear(float v) {
  return v <= 0.04045f ? v / 12.92f : std::pow((v + 0.055f) / 1.055f, 2.4f);
}

std::vector<unsigned char> to_srgb8(const Image& image, float exposure) {
  std::vector<unsigned char> bytes(image.pixels.size() * 3);
  for (size_t i = 0; i < image.pixels.size(); ++i)
    for (int c = 0; c < 3; ++c)
      bytes[3 * i + c] = (unsigned char)std::lround(255.0f * linear_to_srgb(exposure * image.pixels[i][c]));
  return bytes;
}

static bool is_float_format(const std::string& path) {
  std::string ext = path.substr(path.find_last_of('.') + 1);
  std::transform(ext.begin(), ext.end(), ext.begin(), ::tolower);
  return ext == "exr" || ext == "hdr" || ext == "pfm" || ext == "tif" || ext == "tiff";
}

void write_image(const Image& image, const std::string& path, float exposure) {
  auto out = OIIO::ImageOutput::create(path);
  if (!out) throw std::runtime_error(path + ": cannot write image (" + OIIO::geterror() + ")");
  const bool linear = is_float_format(path);
  OIIO::ImageSpec spec(image.width, image.height, 3, linear ? OIIO::TypeDesc::FLOAT : OIIO::TypeDesc::UINT8);
  if (!out->open(path, spec)) throw std::runtime_error(path + ": " + out->geterror());
  bool ok;
  if (linear) {
    ok = out->write_image(OIIO::TypeDesc::FLOAT, image.pixels.data());
  } else {
    ok = out->write_image(OIIO::TypeDesc::UINT8, to_srgb8(image, exposure).data());
  }
  if (!ok || !out->close()) throw std::runtime_error(path + ": " + out->geterror());
}

Image read_image(const std::string& path) {
  auto in = OIIO::ImageInput::open(path);
  if (!in) throw std::runtime_error(path + ": cannot read image (" + OIIO::geterror() + ")");
  const OIIO::ImageSpec& spec = in->spec();
  std::vector<float> data(size_t(spec.width) * spec.height * spec.nchannels);
  if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, data.data()))
    throw std::runtime_error(path + ": " + in->geterror());
  Image image(spec.width, spec.height);
  const bool encoded = spec.format == OIIO::TypeDesc::UINT8;
  for (size_t i = 0; i < image.pixels.size(); ++i)
    for (int c = 0; c < 3; ++c) {
      float v = data[i * spec.nchannels + std::min(c, spec.nchannels - 1)];
      image.pixels[i][c] = encoded ? srgb_to_linear(v) : v;
    }
  return image;
}

}  // namespace igi
