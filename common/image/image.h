#pragma once
// Linear RGB float images and their files. EXR (and any float format
// OpenImageIO knows) stores linear values; PNG/JPEG store clamped sRGB.
#include <algorithm>
#include <span>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "image/view_transform.h"

namespace igi {

struct Image {
  int width = 0;
  int height = 0;
  std::vector<glm::vec3> pixels;  // row-major, row 0 at the top

  Image() = default;
  Image(int w, int h) : width(w), height(h), pixels(size_t(w) * h, glm::vec3(0.0f)) {}
  glm::vec3& at(int x, int y) { return pixels[size_t(y) * width + x]; }
  const glm::vec3& at(int x, int y) const { return pixels[size_t(y) * width + x]; }
  glm::vec3 mean() const;
  // Copies a w x h row-major block (a tile's pixels) to (x, y); the block must lie inside.
  void paste(std::span<const glm::vec3> block, int x, int y, int w, int h) {
    for (int row = 0; row < h; ++row)
      std::copy_n(block.begin() + ptrdiff_t(row) * w, w, pixels.begin() + ptrdiff_t(y + row) * width + x);
  }
};

// Replaces `path` whole or not at all (written beside it, then renamed), and
// equal images give byte-identical files (no time stamp in the header).
// Throws std::runtime_error naming the path on failure; the old file stays.
// 8-bit formats show the image through `tone` (image/view_transform.h).
void write_image(const Image& image, const std::string& path, const ToneMapping& tone = {});
// Why write_image() could not write `path`, asked before any work: a format
// no writer has for its extension, or a folder that does not exist. Nothing
// for a device such as /dev/null. Writes nothing.
std::optional<std::string> image_path_error(const std::string& path);
Image read_image(const std::string& path);
// Whether write_image() writes `path` as linear floats (.exr, .hdr, .pfm,
// .tif) rather than 8-bit sRGB through a tone mapping.
bool is_float_format(const std::string& path);

// 8-bit sRGB, three bytes a pixel, row 0 at the top, through `tone` (tone_map_srgb8).
std::vector<unsigned char> to_srgb8(const Image& image, const ToneMapping& tone = {});

float linear_to_srgb(float linear);
float srgb_to_linear(float encoded);

}  // namespace igi
