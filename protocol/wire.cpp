#include "wire.h"

#include <bit>
#include <cstring>

#include "image/half.h"
#include "image/rgb9e5.h"

namespace igi::protocol {

void Writer::u16(uint16_t v) {
  u8(uint8_t(v));
  u8(uint8_t(v >> 8));
}

void Writer::u32(uint32_t v) {
  for (int shift = 0; shift < 32; shift += 8) u8(uint8_t(v >> shift));
}

void Writer::u64(uint64_t v) {
  for (int shift = 0; shift < 64; shift += 8) u8(uint8_t(v >> shift));
}

void Writer::f32(float v) { u32(std::bit_cast<uint32_t>(v)); }
void Writer::f64(double v) { u64(std::bit_cast<uint64_t>(v)); }

void Writer::vec3(glm::vec3 v) {
  f32(v.x);
  f32(v.y);
  f32(v.z);
}

// The wire is little-endian like every machine we build for: a block copy.
static_assert(std::endian::native == std::endian::little, "the wire format assumes a little-endian host");

void Writer::floats(const float* values, size_t n) {
  const auto* p = reinterpret_cast<const uint8_t*>(values);
  bytes_.insert(bytes_.end(), p, p + n * sizeof(float));
}

void Writer::halves(const float* values, size_t n) {
  const size_t at = bytes_.size();
  bytes_.resize(at + 2 * n);
  std::vector<uint16_t> h(n);
  to_half(values, h.data(), n);
  std::memcpy(bytes_.data() + at, h.data(), 2 * n);
}

void Writer::rgb9e5s(const float* rgb, size_t pixels) {
  const size_t at = bytes_.size();
  bytes_.resize(at + 4 * pixels);
  std::vector<uint32_t> words(pixels);
  to_rgb9e5(rgb, words.data(), pixels);
  std::memcpy(bytes_.data() + at, words.data(), 4 * pixels);
}

void Writer::string(std::string_view s) {
  u32(static_cast<uint32_t>(s.size()));
  bytes_.insert(bytes_.end(), s.begin(), s.end());
}

void Writer::bytes(std::span<const uint8_t> bytes) {
  u32(static_cast<uint32_t>(bytes.size()));
  bytes_.insert(bytes_.end(), bytes.begin(), bytes.end());
}

void Reader::fail(const char* field, const std::string& what) {
  if (error_.empty()) error_ = std::string(message_) + "." + field + ": " + what;
}

void Reader::fail(const std::string& what) {
  if (error_.empty()) error_ = what;
}

const uint8_t* Reader::take(const char* field, size_t n) {
  if (!ok()) return nullptr;
  if (n > remaining()) {
    fail(field, "truncated: needs " + std::to_string(n) + " bytes, " + std::to_string(remaining()) + " left");
    return nullptr;
  }
  const uint8_t* p = bytes_.data() + pos_;
  pos_ += n;
  return p;
}

uint8_t Reader::u8(const char* field) {
  const uint8_t* p = take(field, 1);
  return p ? p[0] : 0;
}

uint16_t Reader::u16(const char* field) {
  const uint8_t* p = take(field, 2);
  return p ? uint16_t(p[0] | p[1] << 8) : 0;
}

uint32_t Reader::u32(const char* field) {
  const uint8_t* p = take(field, 4);
  if (!p) return 0;
  uint32_t v = 0;
  for (int i = 3; i >= 0; --i) v = v << 8 | p[i];
  return v;
}

uint64_t Reader::u64(const char* field) {
  const uint8_t* p = take(field, 8);
  if (!p) return 0;
  uint64_t v = 0;
  for (int i = 7; i >= 0; --i) v = v << 8 | p[i];
  return v;
}

float Reader::f32(const char* field) { return std::bit_cast<float>(u32(field)); }
double Reader::f64(const char* field) { return std::bit_cast<double>(u64(field)); }

bool Reader::boolean(const char* field) {
  uint8_t v = u8(field);
  if (v > 1) fail(field, "boolean byte " + std::to_string(v) + ", expected 0 or 1");
  return v == 1;
}

bool Reader::floats(const char* field, float* out, size_t n) {
  const uint8_t* p = take(field, n * sizeof(float));
  if (!p) return false;
  std::memcpy(out, p, n * sizeof(float));
  return true;
}

bool Reader::halves(const char* field, float* out, size_t n) {
  const uint8_t* p = take(field, n * sizeof(uint16_t));
  if (!p) return false;
  std::vector<uint16_t> h(n);
  std::memcpy(h.data(), p, n * sizeof(uint16_t));
  from_half(h.data(), out, n);
  return true;
}

bool Reader::rgb9e5s(const char* field, float* rgb, size_t pixels) {
  const uint8_t* p = take(field, pixels * sizeof(uint32_t));
  if (!p) return false;
  std::vector<uint32_t> words(pixels);
  std::memcpy(words.data(), p, pixels * sizeof(uint32_t));
  from_rgb9e5(words.data(), rgb, pixels);
  return true;
}

std::span<const uint8_t> Reader::span(const char* field, size_t n) {
  const uint8_t* p = take(field, n);
  return p ? std::span<const uint8_t>(p, n) : std::span<const uint8_t>();
}

glm::vec3 Reader::vec3(const char* field) {
  float x = f32(field);
  float y = f32(field);
  float z = f32(field);
  return {x, y, z};
}

uint32_t Reader::length(const char* field, size_t max_bytes) {
  uint32_t n = u32(field);
  if (n > max_bytes) {
    fail(field, "length " + std::to_string(n) + " over the limit of " + std::to_string(max_bytes));
  } else if (n > remaining()) {
    fail(field, "truncated: length " + std::to_string(n) + ", " + std::to_string(remaining()) + " bytes left");
  }
  return ok() ? n : 0;
}

std::string Reader::string(const char* field, size_t max_bytes) {
  uint32_t n = length(field, max_bytes);
  const uint8_t* p = take(field, n);
  return p ? std::string(reinterpret_cast<const char*>(p), n) : std::string();
}

std::vector<uint8_t> Reader::bytes(const char* field, size_t max_bytes) {
  uint32_t n = length(field, max_bytes);
  const uint8_t* p = take(field, n);
  return p ? std::vector<uint8_t>(p, p + n) : std::vector<uint8_t>();
}

uint32_t Reader::count(const char* field, size_t element_bytes, size_t max_count) {
  uint32_t n = u32(field);
  if (n > max_count) {
    fail(field, "count " + std::to_string(n) + " over the limit of " + std::to_string(max_count));
  } else if (uint64_t(n) * element_bytes > remaining()) {
    fail(field, "truncated: " + std::to_string(n) + " elements of " + std::to_string(element_bytes) +
                    " bytes, " + std::to_string(remaining()) + " bytes left");
  }
  return ok() ? n : 0;
}

}  // namespace igi::protocol
