#include "scene/texture_decode.h"

#include <algorithm>
#include <climits>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <optional>

#include <tiny_gltf.h>

#include "image/image.h"

namespace igi {
namespace {

std::string trimmed(std::string text) {
  while (!text.empty() && (text.back() == '\n' || text.back() == ' ')) text.pop_back();
  return text;
}

// stb decodes to 4 channels of 8 or 16 bits, row 0 at the top (as Texture).
// 8-bit images stay bytes (Texture::texel decodes them); 16-bit ones become floats.
Texture to_texture(tinygltf::Image& image, bool srgb) {
  Texture texture;
  texture.width = image.width;
  texture.height = image.height;
  texture.srgb = srgb;
  if (image.bits == 8) {
    texture.bytes = std::move(image.image);
    return texture;
  }
  const size_t count = size_t(image.width) * size_t(image.height);
  texture.texels.resize(count);
  for (size_t i = 0; i < count; ++i) {
    glm::vec4 encoded;
    for (int c = 0; c < 4; ++c) {
      const size_t at = i * 4 + size_t(c);
      encoded[c] = float(image.image[2 * at] | (image.image[2 * at + 1] << 8)) * (1.0f / 65535.0f);
    }
    texture.texels[i] = srgb ? glm::vec4(srgb_to_linear(encoded.r), srgb_to_linear(encoded.g),
                                         srgb_to_linear(encoded.b), encoded.a)
                             : encoded;
  }
  return texture;
}

uint32_t big_endian(const unsigned char* at, int bytes) {
  uint32_t value = 0;
  for (int i = 0; i < bytes; ++i) value = value << 8 | at[i];
  return value;
}

// Width and height from a PNG or JPEG header, read before decoding so that a
// small file cannot make the decoder allocate gigabytes. nullopt: neither
// format (glTF allows only these two), or a header cut short.
std::optional<glm::ivec2> encoded_image_size(const unsigned char* bytes, size_t size) {
  static const unsigned char png[] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  if (size >= 24 && std::equal(png, png + 8, bytes) && std::memcmp(bytes + 12, "IHDR", 4) == 0)
    return glm::ivec2(int(std::min(big_endian(bytes + 16, 4), uint32_t(INT_MAX))),
                      int(std::min(big_endian(bytes + 20, 4), uint32_t(INT_MAX))));
  if (size < 4 || bytes[0] != 0xFF || bytes[1] != 0xD8) return std::nullopt;
  // JPEG: segments FF <marker> <u16 length> ... up to a start-of-frame.
  for (size_t at = 2; at + 4 <= size;) {
    if (bytes[at] != 0xFF) return std::nullopt;
    const unsigned char marker = bytes[at + 1];
    if (marker == 0xFF) { ++at; continue; }  // fill byte
    const bool start_of_frame =
        marker >= 0xC0 && marker <= 0xCF && marker != 0xC4 && marker != 0xC8 && marker != 0xCC;
    if (start_of_frame) {  // FF Cn, length, precision, height, width
      if (at + 9 > size) return std::nullopt;
      return glm::ivec2(big_endian(bytes + at + 7, 2), big_endian(bytes + at + 5, 2));
    }
    at += 2 + big_endian(bytes + at + 2, 2);
  }
  return std::nullopt;
}

// Texels are stored as float4: 2^26 of them are 1 GiB. A header may also
// claim more pixels than its file can hold: stb decodes a JPEG whose scans
// are cut short or missing as if the rest were there, so a 600-byte file
// that says 8000 x 8000 took 12 s and 1.4 GB before this check. The most
// pixels a byte can hold:
// - PNG: 8 (1-bit pixels) times deflate's largest ratio, 1032:1.
// - JPEG: a scan spends at least one bit on each 8 x 8 block (a 1-bit DC
//   code, progressive); 1024 is twice that, for slack. Real files stay far
//   below: a flat 4:2:0 JPEG with the standard tables holds about 64.
void check_image_size(const unsigned char* bytes, size_t size, const std::string& name, const GltfDiagnostics& diag) {
  constexpr int64_t kMaxTexels = int64_t(1) << 26;
  const std::optional<glm::ivec2> extent = encoded_image_size(bytes, size);
  if (!extent) diag.fail(name, "neither a PNG nor a JPEG image (or its header is cut short)");
  const int64_t texels = int64_t(extent->x) * extent->y;
  if (extent->x <= 0 || extent->y <= 0 || texels > kMaxTexels)
    diag.fail(name, std::to_string(extent->x) + " x " + std::to_string(extent->y) +
                         " pixels, expected at least 1 x 1 and at most 2^26 pixels");
  const bool png = bytes[0] == 0x89;
  const int64_t per_byte = png ? 8 * 1032 : 1024;
  if (texels > per_byte * int64_t(size))
    diag.fail(name, std::to_string(extent->x) + " x " + std::to_string(extent->y) + " pixels in " +
                         std::to_string(size) + " bytes: more than a " + (png ? "PNG" : "JPEG") +
                         " file of that size can hold (" + std::to_string(per_byte) +
                         " pixels a byte); the file is cut short or broken");
}

uint32_t little_endian(const unsigned char* at) {
  uint32_t value;
  std::memcpy(&value, at, 4);  // DDS is little-endian, as is every machine this runs on
  return value;
}

// One BC4 block: two endpoints and sixteen 3-bit indices into their palette.
void decode_bc4_block(const unsigned char* block, uint8_t out[16]) {
  const int r0 = block[0], r1 = block[1];
  int palette[8] = {r0, r1};
  if (r0 > r1) {
    for (int k = 2; k < 8; ++k) palette[k] = ((8 - k) * r0 + (k - 1) * r1 + 3) / 7;
  } else {
    for (int k = 2; k < 6; ++k) palette[k] = ((6 - k) * r0 + (k - 1) * r1 + 2) / 5;
    palette[6] = 0;
    palette[7] = 255;
  }
  uint64_t bits = 0;
  for (int i = 0; i < 6; ++i) bits |= uint64_t(block[2 + i]) << (8 * i);
  for (int i = 0; i < 16; ++i) out[i] = uint8_t(palette[(bits >> (3 * i)) & 7]);
}

}  // namespace

Texture decode_texture(const unsigned char* bytes, size_t size, const std::string& shown, const GltfDiagnostics& diag,
                       bool srgb) {
  check_image_size(bytes, size, shown, diag);
  std::string error, warning;
  tinygltf::Image decoded;
  const bool ok = tinygltf::LoadImageData(&decoded, 0, &error, &warning, 0, 0, bytes, int(size), nullptr);
  const size_t expected_bytes = size_t(decoded.width) * size_t(decoded.height) * 4 * size_t(decoded.bits / 8);
  if (!ok || decoded.component != 4 || (decoded.bits != 8 && decoded.bits != 16) ||
      decoded.image.size() != expected_bytes)
    diag.fail(shown, "cannot be decoded" + (error.empty() ? std::string() : " (" + trimmed(error) + ")") +
                         ": expected a PNG or JPEG image");
  return to_texture(decoded, srgb);
}

bool is_dds(const unsigned char* bytes, size_t size) { return size >= 4 && std::memcmp(bytes, "DDS ", 4) == 0; }

Texture decode_dds_bc4(const unsigned char* bytes, size_t size, const std::string& shown, const GltfDiagnostics& diag) {
  constexpr size_t kHeader = 128, kDx10Header = 20;
  if (!is_dds(bytes, size) || size < kHeader || little_endian(bytes + 4) != 124)
    diag.fail(shown, "not a DDS file (or its header is cut short)");
  const uint32_t height = little_endian(bytes + 12), width = little_endian(bytes + 16);
  const bool dx10 = std::memcmp(bytes + 84, "DX10", 4) == 0;
  const bool bc4 = dx10 ? size >= kHeader + kDx10Header && little_endian(bytes + kHeader) == 80  // BC4_UNORM
                        : std::memcmp(bytes + 84, "ATI1", 4) == 0 || std::memcmp(bytes + 84, "BC4U", 4) == 0;
  if (!bc4)
    diag.fail(shown, "a DDS file of a format other than BC4 (one channel): only BC4 is read; "
                     "--ignore-extension MSFT_texture_dds loads the file without its DDS images");
  const uint64_t texels = uint64_t(width) * height;
  if (width == 0 || height == 0 || texels > (uint64_t(1) << 26))
    diag.fail(shown, std::to_string(width) + " x " + std::to_string(height) +
                         " pixels, expected at least 1 x 1 and at most 2^26 pixels");
  const size_t blocks_x = (width + 3) / 4, blocks_y = (height + 3) / 4;
  const size_t data = kHeader + (dx10 ? kDx10Header : 0);
  if (size - data < blocks_x * blocks_y * 8)
    diag.fail(shown, "its BC4 blocks are cut short (" + std::to_string(size) + " bytes for " + std::to_string(width) +
                         " x " + std::to_string(height) + ")");
  Texture texture;
  texture.width = int(width);
  texture.height = int(height);
  texture.srgb = false;
  texture.bytes.assign(size_t(texels) * 4, 255);
  uint8_t block[16];
  for (size_t by = 0; by < blocks_y; ++by)
    for (size_t bx = 0; bx < blocks_x; ++bx) {
      decode_bc4_block(bytes + data + (by * blocks_x + bx) * 8, block);
      for (size_t i = 0; i < 16; ++i) {
        const size_t x = bx * 4 + i % 4, y = by * 4 + i / 4;
        if (x >= width || y >= height) continue;
        uint8_t* texel = texture.bytes.data() + 4 * (y * width + x);
        texel[0] = texel[1] = texel[2] = block[i];
      }
    }
  return texture;
}

}  // namespace igi
