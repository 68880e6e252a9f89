#pragma once
// Little-endian byte writer and bounds-checked reader for the wire format.
//
// Writer appends; it never fails. Reader never throws and never reads past its
// span: the first failure (truncation, a length over its limit, a bad value)
// is kept as the error, and every later read returns a zero value without
// touching the bytes, so decode code reads straight through and checks ok()
// once. Lengths and counts are checked against the bytes that are left before
// anything is allocated, so a peer cannot make us allocate more than it sent.
//
// Field names in errors are relative to the message being read ("tile.w");
// the Reader prefixes the message name set by begin() ("TileResult.tile.w").
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <glm/glm.hpp>

namespace igi::protocol {

class Writer {
 public:
  void u8(uint8_t v) { bytes_.push_back(v); }
  void u16(uint16_t v);
  void u32(uint32_t v);
  void u64(uint64_t v);
  void i32(int32_t v) { u32(static_cast<uint32_t>(v)); }  // two's complement
  void f32(float v);                                       // IEEE-754 bits
  void f64(double v);                                      // IEEE-754 bits
  void boolean(bool v) { u8(v ? 1 : 0); }
  void vec3(glm::vec3 v);
  void floats(const float* values, size_t n);
  void halves(const float* values, size_t n);  // each rounded to a half (image/half.h), 2 bytes
  void rgb9e5s(const float* rgb, size_t pixels);  // each pixel as one shared-exponent word (image/rgb9e5.h)
  void string(std::string_view s);             // u32 length + bytes
  void bytes(std::span<const uint8_t> bytes);  // u32 length + bytes

  void reserve(size_t extra) { bytes_.reserve(bytes_.size() + extra); }
  std::vector<uint8_t> take() { return std::move(bytes_); }

 private:
  std::vector<uint8_t> bytes_;
};

class Reader {
 public:
  explicit Reader(std::span<const uint8_t> bytes) : bytes_(bytes) {}

  // Names the message being read, for error messages.
  void begin(std::string_view message_name) { message_ = message_name; }

  bool ok() const { return error_.empty(); }
  const std::string& error() const { return error_; }
  size_t remaining() const { return bytes_.size() - pos_; }

  uint8_t u8(const char* field);
  uint16_t u16(const char* field);
  uint32_t u32(const char* field);
  uint64_t u64(const char* field);
  int32_t i32(const char* field) { return static_cast<int32_t>(u32(field)); }
  float f32(const char* field);
  double f64(const char* field);
  bool boolean(const char* field);  // 0 or 1; any other byte is an error
  glm::vec3 vec3(const char* field);
  // n floats in one bounds check (pixel blocks); false when too few bytes are left.
  bool floats(const char* field, float* out, size_t n);
  // n halves, widened to floats (exactly); false when too few bytes are left.
  bool halves(const char* field, float* out, size_t n);
  // n pixels of one shared-exponent word each, as 3n floats (exactly); false when too few bytes are left.
  bool rgb9e5s(const char* field, float* rgb, size_t pixels);
  // The next n bytes as they are (no copy); empty, with an error, when fewer are left.
  std::span<const uint8_t> span(const char* field, size_t n);
  // u32 length (at most max_bytes) + bytes.
  std::string string(const char* field, size_t max_bytes);
  std::vector<uint8_t> bytes(const char* field, size_t max_bytes);
  // u32 count of elements of element_bytes each; fails when the count is over
  // max_count or the rest of the message cannot hold that many elements.
  uint32_t count(const char* field, size_t element_bytes, size_t max_count);

  // Records "<Message>.<field>: <what>" unless an error is already recorded.
  void fail(const char* field, const std::string& what);
  // Records `what` as it is (header errors, which belong to no message).
  void fail(const std::string& what);

 private:
  // Position of n readable bytes, or nullptr (and an error) when fewer are left.
  const uint8_t* take(const char* field, size_t n);
  uint32_t length(const char* field, size_t max_bytes);

  std::span<const uint8_t> bytes_;
  size_t pos_ = 0;
  std::string_view message_ = "message";
  std::string error_;
};

}  // namespace igi::protocol
