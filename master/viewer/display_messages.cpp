#include "viewer/display_messages.h"

#include <cmath>
#include <cstdio>
#include <numbers>

#include <zstd.h>

#include "protocol/codec.h"
#include "protocol/wire.h"

namespace igi::display {
namespace {

using protocol::Reader;
using protocol::Writer;

constexpr uint64_t kMaxStamp = uint64_t(1) << 62;  // microseconds: any clock, never an overflow when subtracted
constexpr float kMaxExposure = 1e6f;

std::string show(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.9g", v);
  return text;
}

// ---- The fields shared by several messages, each with its check.

void write(Writer& w, const Camera& c) {
  w.vec3(c.position);
  w.vec3(c.forward);
  w.vec3(c.up);
  w.f32(c.vfov);
}

bool finite(glm::vec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

void read(Reader& r, Camera& c) {
  c.position = r.vec3("camera.position");
  c.forward = r.vec3("camera.forward");
  c.up = r.vec3("camera.up");
  c.vfov = r.f32("camera.vfov");
  if (!r.ok()) return;
  if (!finite(c.position)) r.fail("camera.position", "not finite");
  for (auto [field, v] : {std::pair{"camera.forward", c.forward}, std::pair{"camera.up", c.up}})
    if (!finite(v) || !std::isnormal(glm::length(v))) r.fail(field, "zero, degenerate or not finite, expected a direction");
  if (r.ok() && glm::length(glm::cross(glm::normalize(c.forward), glm::normalize(c.up))) < 1e-4f)
    r.fail("camera.up", "parallel to forward, expected a direction across it");
  if (!(c.vfov > 0.0f && c.vfov < std::numbers::pi_v<float>))
    r.fail("camera.vfov", show(c.vfov) + " radians, expected (0, pi)");
}

// RenderSettings as the workers' wire writes and checks them (protocol/codec.h).
void write(Writer& w, const RenderSettings& s) { protocol::write_settings(w, s); }
void read(Reader& r, RenderSettings& s) { protocol::read_settings(r, s); }

void write(Writer& w, const ToneMapping& t) {
  w.f32(t.exposure);
  w.u8(uint8_t(t.view));
}

void read(Reader& r, ToneMapping& t) {
  t.exposure = r.f32("tone.exposure");
  const uint8_t view = r.u8("tone.view");
  if (!(t.exposure > 0.0f && t.exposure <= kMaxExposure))
    r.fail("tone.exposure", show(t.exposure) + ", expected (0, 1e6]");
  if (view >= kViewTransforms.size()) r.fail("tone.view", std::to_string(view) + ", expected 0..2");
  t.view = ViewTransform(view);
}

void read_side(Reader& r, const char* field, int32_t& v) {
  v = r.i32(field);
  if (v < 1 || v > kMaxSide) r.fail(field, std::to_string(v) + ", expected 1.." + std::to_string(kMaxSide));
}

uint64_t read_stamp(Reader& r, const char* field) {
  const uint64_t v = r.u64(field);
  if (v > kMaxStamp) r.fail(field, std::to_string(v) + ", expected under 2^62 microseconds");
  return v;
}

// ---- The messages.

void write(Writer& w, const Hello& m) { w.string(m.program); }
void read(Reader& r, Hello& m) { m.program = r.string("program", kMaxText); }

void write(Writer& w, const Welcome& m) {
  w.string(m.scene);
  w.i32(m.width);
  w.i32(m.height);
  write(w, m.settings);
  write(w, m.camera);
  w.f32(m.speed);
  write(w, m.tone);
  w.boolean(m.metering);
  w.u32(uint32_t(m.preview_levels.size()));
  for (const std::string& level : m.preview_levels) w.string(level);
}

void read(Reader& r, Welcome& m) {
  m.scene = r.string("scene", kMaxText);
  read_side(r, "width", m.width);
  read_side(r, "height", m.height);
  read(r, m.settings);
  read(r, m.camera);
  m.speed = r.f32("speed");
  if (!(m.speed > 0.0f && std::isfinite(m.speed))) r.fail("speed", show(m.speed) + ", expected a finite speed > 0");
  read(r, m.tone);
  m.metering = r.boolean("metering");
  m.preview_levels.resize(r.count("preview_levels", 4, kMaxLevels));
  for (std::string& level : m.preview_levels) level = r.string("preview_levels", 64);
}

void write(Writer& w, const Refuse& m) { w.string(m.reason); }
void read(Reader& r, Refuse& m) { m.reason = r.string("reason", kMaxText); }

void write(Writer& w, const View& m) {
  write(w, m.camera);
  write(w, m.settings);
  w.u64(m.camera_generation);
  w.u64(m.settings_generation);
  w.vec3(m.light_offset);
  w.i32(m.preview);
  write(w, m.tone);
  w.boolean(m.metering);
  w.u64(m.stamp_us);
}

void read(Reader& r, View& m) {
  read(r, m.camera);
  read(r, m.settings);
  m.camera_generation = r.u64("camera_generation");
  m.settings_generation = r.u64("settings_generation");
  m.light_offset = r.vec3("light_offset");
  if (r.ok() && !finite(m.light_offset)) r.fail("light_offset", "not finite");
  m.preview = r.i32("preview");
  if (m.preview < -1 || m.preview >= int32_t(kMaxLevels))
    r.fail("preview", std::to_string(m.preview) + ", expected -1.." + std::to_string(kMaxLevels - 1));
  read(r, m.tone);
  m.metering = r.boolean("metering");
  m.stamp_us = read_stamp(r, "stamp_us");
}

void write(Writer& w, const Ack& m) { w.u64(m.frame); }
void read(Reader& r, Ack& m) { m.frame = r.u64("frame"); }

void write(Writer& w, const Request& m) { w.u8(uint8_t(m.kind)); }
void read(Reader& r, Request& m) {
  const uint8_t kind = r.u8("kind");
  if (kind < 1 || kind > 2) r.fail("kind", std::to_string(kind) + ", expected 1 (meter) or 2 (save the image)");
  m.kind = RequestKind(kind);
}

void write(Writer& w, const Reply& m) {
  w.string(m.text);
  w.f32(m.exposure);
  w.bytes(m.exr);
}
void read(Reader& r, Reply& m) {
  m.text = r.string("text", kMaxText);
  m.exposure = r.f32("exposure");
  if (!(m.exposure >= 0.0f && m.exposure <= kMaxExposure))
    r.fail("exposure", show(m.exposure) + ", expected 0 (none) or (0, 1e6]");
  m.exr = r.bytes("exr", kMaxMessageBytes);
}

void write(Writer& w, const Frame& m) {
  w.u64(m.sequence);
  w.u64(m.stamp_us);
  w.u64(m.settings_generation);
  w.i32(m.width);
  w.i32(m.height);
  w.u8(uint8_t(m.codec));
  w.boolean(m.full);
  w.f32(m.metered);
  w.f32(m.accumulated);
  w.f32(m.seconds);
  w.string(m.level);
  w.string(m.status);
  w.bytes(m.pixels);
}

void read(Reader& r, Frame& m) {
  m.sequence = r.u64("sequence");
  m.stamp_us = read_stamp(r, "stamp_us");
  m.settings_generation = r.u64("settings_generation");
  read_side(r, "width", m.width);
  read_side(r, "height", m.height);
  const uint8_t codec = r.u8("codec");
  if (codec != uint8_t(FrameCodec::Zstd) && codec != uint8_t(FrameCodec::H264))
    r.fail("codec", std::to_string(codec) + ", expected 1 (zstd) or 2 (h264)");
  m.codec = FrameCodec(codec);
  m.full = r.boolean("full");
  m.metered = r.f32("metered");
  if (!(m.metered >= 0.0f && m.metered <= kMaxExposure))
    r.fail("metered", show(m.metered) + ", expected 0 (none) or (0, 1e6]");
  m.accumulated = r.f32("accumulated");
  if (!(m.accumulated >= 0.0f && std::isfinite(m.accumulated)))
    r.fail("accumulated", show(m.accumulated) + ", expected a finite count >= 0");
  m.seconds = r.f32("seconds");
  if (!(m.seconds >= 0.0f && std::isfinite(m.seconds))) r.fail("seconds", show(m.seconds) + ", expected a finite time >= 0");
  m.level = r.string("level", 64);
  m.status = r.string("status", kMaxText);
  m.pixels = r.bytes("pixels", size_t(m.width) * size_t(m.height) * 3 + 1024);  // zstd's worst case, at most
}

void write(Writer&, const Ping&) {}
void read(Reader&, Ping&) {}

void write(Writer& w, const Bye& m) { w.string(m.reason); }
void read(Reader& r, Bye& m) { m.reason = r.string("reason", kMaxText); }

template <typename M>
Message read_as(Reader& r) {
  M m;
  read(r, m);
  return m;
}

Message read_payload(Reader& r, Type type) {
  switch (type) {
    case Type::Hello: return read_as<Hello>(r);
    case Type::Welcome: return read_as<Welcome>(r);
    case Type::Refuse: return read_as<Refuse>(r);
    case Type::View: return read_as<View>(r);
    case Type::Ack: return read_as<Ack>(r);
    case Type::Request: return read_as<Request>(r);
    case Type::Reply: return read_as<Reply>(r);
    case Type::Frame: return read_as<Frame>(r);
    case Type::Ping: return read_as<Ping>(r);
    case Type::Bye: return read_as<Bye>(r);
  }
  return Ping{};  // not reached: the header's type was checked
}

std::optional<Type> read_header(Reader& r) {
  const uint32_t magic = r.u32("magic");
  const uint16_t version = r.u16("version");
  const uint8_t type = r.u8("type");
  const uint8_t flags = r.u8("flags");
  if (!r.ok()) return std::nullopt;
  if (magic != kMagic) {
    r.fail("not a display link message (bad magic; a worker or another program on the viewer port?)");
  } else if (version != kVersion) {
    r.fail("display link version " + std::to_string(version) + ", this build speaks " + std::to_string(kVersion) +
           ": run igi-view and igi-master of the same release");
  } else if (type < 1 || type > kTypes) {
    r.fail("unknown display message type " + std::to_string(type));
  } else if (flags != 0) {
    r.fail(std::string(type_name(Type(type))) + ": flags " + std::to_string(flags) + ", expected 0");
  }
  if (!r.ok()) return std::nullopt;
  return Type(type);
}

}  // namespace

const char* type_name(Type type) {
  static constexpr const char* kNames[] = {"Hello", "Welcome", "Refuse", "View", "Ack",
                                           "Request", "Reply", "Frame", "Ping", "Bye"};
  const int t = int(type);
  return t >= 1 && t <= kTypes ? kNames[t - 1] : "unknown";
}

Type type_of(const Message& message) { return Type(message.index() + 1); }

std::vector<uint8_t> encode(const Message& message) {
  Writer w;
  w.u32(kMagic);
  w.u16(kVersion);
  w.u8(uint8_t(type_of(message)));
  w.u8(0);
  std::visit([&](const auto& m) { write(w, m); }, message);
  return w.take();
}

Decoded decode(std::span<const uint8_t> bytes) {
  if (bytes.size() > kMaxMessageBytes)
    return {std::nullopt, "display message of " + std::to_string(bytes.size()) + " bytes, over the limit of " +
                              std::to_string(kMaxMessageBytes)};
  Reader r(bytes);
  const std::optional<Type> type = read_header(r);
  if (!type) return {std::nullopt, r.error()};
  r.begin(type_name(*type));
  Message message = read_payload(r, *type);
  if (r.ok() && r.remaining() != 0)
    r.fail(std::string(type_name(*type)) + ": " + std::to_string(r.remaining()) + " trailing bytes after the payload");
  if (!r.ok()) return {std::nullopt, r.error()};
  return {std::move(message), {}};
}

std::vector<uint8_t> pack_pixels(std::span<const uint8_t> rgb) {
  std::vector<uint8_t> packed(ZSTD_compressBound(rgb.size()));
  // Level 1: a 640x480 frame in a few ms on one core; higher levels gain little on rendered noise.
  const size_t size = ZSTD_compress(packed.data(), packed.size(), rgb.data(), rgb.size(), 1);
  packed.resize(ZSTD_isError(size) ? 0 : size);
  return packed;
}

std::optional<std::vector<uint8_t>> unpack_pixels(const Frame& frame, std::string& error) {
  if (frame.codec != FrameCodec::Zstd) {
    error = "Frame.pixels: H.264, not zstd (video_codec.h decodes it)";
    return std::nullopt;
  }
  const size_t expected = size_t(frame.width) * size_t(frame.height) * 3;
  const unsigned long long content = ZSTD_getFrameContentSize(frame.pixels.data(), frame.pixels.size());
  if (content != expected) {
    error = "Frame.pixels: a zstd frame of " +
            (content == ZSTD_CONTENTSIZE_ERROR ? std::string("no valid header") : std::to_string(content) + " bytes") +
            ", expected " + std::to_string(expected) + " (" + std::to_string(frame.width) + " x " +
            std::to_string(frame.height) + " x 3)";
    return std::nullopt;
  }
  std::vector<uint8_t> rgb(expected);
  const size_t size = ZSTD_decompress(rgb.data(), rgb.size(), frame.pixels.data(), frame.pixels.size());
  if (ZSTD_isError(size) || size != expected) {
    error = std::string("Frame.pixels: ") + (ZSTD_isError(size) ? ZSTD_getErrorName(size) : "short") +
            " (zstd), expected " + std::to_string(expected) + " bytes";
    return std::nullopt;
  }
  return rgb;
}

}  // namespace igi::display
