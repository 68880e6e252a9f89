#include "image/image.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <functional>
#include <stdexcept>
#include <thread>

#include <unistd.h>

#include <OpenImageIO/imageio.h>

namespace igi {

namespace fs = std::filesystem;

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

std::vector<unsigned char> to_srgb8(const Image& image, const ToneMapping& tone) {
  std::vector<unsigned char> bytes(image.pixels.size() * 3);
  for (size_t i = 0; i < image.pixels.size(); ++i) {
    const std::array<uint8_t, 3> pixel = tone_map_srgb8(image.pixels[i], tone);
    std::copy(pixel.begin(), pixel.end(), bytes.begin() + ptrdiff_t(3 * i));
  }
  return bytes;
}

bool is_float_format(const std::string& path) {
  std::string ext = path.substr(path.find_last_of('.') + 1);
  std::transform(ext.begin(), ext.end(), ext.begin(), ::tolower);
  return ext == "exr" || ext == "hdr" || ext == "pfm" || ext == "tif" || ext == "tiff";
}

// OpenImageIO picks the format from `path` and writes `file`. EXR headers get
// no DateTime (OpenImageIO adds the clock's otherwise): equal images give
// equal files.
static void write_image_file(const Image& image, const std::string& path, const std::string& file,
                             const ToneMapping& tone) {
  auto out = OIIO::ImageOutput::create(path);
  if (!out) throw std::runtime_error(path + ": cannot write image (" + OIIO::geterror() + ")");
  const bool linear = is_float_format(path);
  OIIO::ImageSpec spec(image.width, image.height, 3, linear ? OIIO::TypeDesc::FLOAT : OIIO::TypeDesc::UINT8);
  spec.attribute("DateTime", "");
  if (!out->open(file, spec)) throw std::runtime_error(path + ": " + out->geterror());
  bool ok;
  if (linear) {
    ok = out->write_image(OIIO::TypeDesc::FLOAT, image.pixels.data());
  } else {
    ok = out->write_image(OIIO::TypeDesc::UINT8, to_srgb8(image, tone).data());
  }
  if (!ok || !out->close()) throw std::runtime_error(path + ": " + out->geterror());
}

// A hidden name beside `path`, unique to this process and thread (the only
// writers that could race for it).
static std::string temporary_name(const std::string& path) {
  const fs::path target(path);
  char suffix[64];
  std::snprintf(suffix, sizeof suffix, ".%ld-%zx.tmp", long(::getpid()),
                std::hash<std::thread::id>{}(std::this_thread::get_id()));
  return (target.parent_path() / ("." + target.filename().string() + suffix)).string();
}

// The file a write to `path` replaces: `path`, or the file its link names.
static std::string replaced_file(const std::string& path) {
  std::error_code absent;  // a path that does not exist yet is the common case
  if (!fs::is_symlink(fs::symlink_status(path, absent))) return path;
  std::error_code error;
  const fs::path target = fs::canonical(path, error);
  if (error) throw std::runtime_error(path + ": cannot follow the link (" + error.message() + ")");
  return target.string();
}

std::optional<std::string> image_path_error(const std::string& path) {
  std::error_code absent;
  const fs::file_status status = fs::status(path, absent);
  if (fs::exists(status) && !fs::is_regular_file(status)) return std::nullopt;  // a device: written in place
  if (!OIIO::ImageOutput::create(path))
    return path + ": no image format for its extension (.exr, .hdr, .pfm and .tif are written as float, "
                  ".png and .jpg as 8-bit sRGB)";
  const fs::path folder = fs::path(path).parent_path();
  if (!folder.empty() && !fs::is_directory(folder, absent)) return path + ": the folder " + folder.string() + " does not exist";
  return std::nullopt;
}

// The image goes to a temporary file in the same folder, renamed over `path`
// once whole: a process killed mid-write leaves the old file or none under
// `path`, never a truncated one (rename is atomic within a file system). A
// link is followed (its target is replaced); a device or pipe (-o /dev/null)
// is written in place, as renaming over it would replace the device.
void write_image(const Image& image, const std::string& path, const ToneMapping& tone) {
  std::error_code absent;
  const fs::file_status status = fs::status(path, absent);
  if (fs::exists(status) && !fs::is_regular_file(status)) return write_image_file(image, path, path, tone);
  const std::string target = replaced_file(path);
  const std::string temporary = temporary_name(target);
  try {
    write_image_file(image, path, temporary, tone);
  } catch (...) {
    std::remove(temporary.c_str());
    throw;
  }
  if (std::rename(temporary.c_str(), target.c_str()) != 0) {
    const std::string reason = std::strerror(errno);
    std::remove(temporary.c_str());
    throw std::runtime_error(path + ": cannot replace the file (" + reason + ")");
  }
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
