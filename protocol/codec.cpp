// Encode and decode, one write/read pair per message, side by side. Each read
// validates its fields right after reading them; the limits are listed first.
#include "protocol/codec.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <cstdio>
#include <numbers>
#include <type_traits>
#include <variant>

#include <lz4.h>
#include <zstd.h>

#include "core/settings_table.h"
#include "protocol/wire.h"

namespace igi::protocol {

// Every field of RenderSettings once, in the wire's order: its row in
// core/settings_table.h. write() and read() both walk the table, so the two
// cannot drift apart, and a setting needs no line here.
void write_settings(Writer& w, const RenderSettings& s) {
  for (const Setting& row : settings_table())
    std::visit(
        [&](auto member) {
          using T = std::remove_cvref_t<decltype(s.*member)>;
          if constexpr (std::is_same_v<T, MethodKind>) w.u8(static_cast<uint8_t>(s.*member));
          else if constexpr (std::is_same_v<T, bool>) w.boolean(s.*member);
          else if constexpr (std::is_same_v<T, float>) w.f32(s.*member);
          else w.i32(s.*member);
        },
        row.member);
}

// RenderSettings in write()'s order, then the one check of them all
// (core/settings.h): the wire knows the fields, not each method's rules.
void read_settings(Reader& r, RenderSettings& s) {
  for (const Setting& row : settings_table())
    std::visit(
        [&](auto member) {
          using T = std::remove_cvref_t<decltype(s.*member)>;
          if constexpr (std::is_same_v<T, MethodKind>) s.*member = static_cast<MethodKind>(r.u8(row.wire));
          else if constexpr (std::is_same_v<T, bool>) s.*member = r.boolean(row.wire);
          else if constexpr (std::is_same_v<T, float>) s.*member = r.f32(row.wire);
          else s.*member = r.i32(row.wire);
        },
        row.member);
  if (!r.ok()) return;
  if (auto error = check_settings(s)) r.fail(("settings." + error->field).c_str(), error->message);
}

namespace {

// zstd level 1: the fastest of its levels but the negative ones; a 1080p
// frame of rendered half floats packs 2.1x there (2.5x at level 3, for about
// twice the time), and a display frame must not wait on its packing.
constexpr int kZstdLevel = 1;

// One context a thread, kept (a fresh one a tile would allocate each time).
struct ZstdContexts {
  ZSTD_CCtx* compress = ZSTD_createCCtx();
  ZSTD_DCtx* decompress = ZSTD_createDCtx();
  ~ZstdContexts() {
    ZSTD_freeCCtx(compress);
    ZSTD_freeDCtx(decompress);
  }
};
ZstdContexts& zstd_contexts() {
  thread_local ZstdContexts contexts;
  return contexts;
}

std::vector<uint8_t> zstd_compress(std::vector<uint8_t> raw) {
  std::vector<uint8_t> packed(ZSTD_compressBound(raw.size()));
  const size_t n = ZSTD_compressCCtx(zstd_contexts().compress, packed.data(), packed.size(), raw.data(), raw.size(),
                                     kZstdLevel);
  if (ZSTD_isError(n)) return raw;  // cannot happen with a bound-sized buffer; the decoder would then refuse
  packed.resize(n);
  return packed;
}

std::vector<uint8_t> lz4_compress(std::vector<uint8_t> raw) {
  std::vector<uint8_t> packed(size_t(LZ4_compressBound(int(raw.size()))));
  const int n = LZ4_compress_default(reinterpret_cast<const char*>(raw.data()), reinterpret_cast<char*>(packed.data()),
                                     int(raw.size()), int(packed.size()));
  if (n <= 0) return raw;  // cannot happen with a bound-sized buffer; the decoder would then refuse
  packed.resize(size_t(n));
  return packed;
}

// A block's bytes packed by `codec` (not Raw).
std::vector<uint8_t> pack(PixelCodec codec, std::vector<uint8_t> raw) {
  return codec == PixelCodec::Lz4 ? lz4_compress(std::move(raw)) : zstd_compress(std::move(raw));
}

// The field a packed block is read as: "pixels.zstd", "surfaces.lz4", ...
std::string packed_field(const char* block, PixelCodec codec) {
  return std::string(block) + "." + pixel_codec_name(codec);
}

// Unpacks `packed` (by `codec`, not Raw) into `out`, which must come out
// exactly `size` bytes (`what`: "pixels" or "surfaces", for the error);
// returns "" or what was wrong. Never writes more than `size` bytes.
std::string unpack(PixelCodec codec, std::span<const uint8_t> packed, size_t size, std::vector<uint8_t>& out,
                   const char* what) {
  out.resize(size);
  if (codec == PixelCodec::Lz4) {
    const int n = LZ4_decompress_safe(reinterpret_cast<const char*>(packed.data()), reinterpret_cast<char*>(out.data()),
                                      int(packed.size()), int(out.size()));
    if (n < 0) return std::string("not an lz4 block of the tile's ") + what;
    if (size_t(n) != size)
      return "the lz4 block holds " + std::to_string(n) + " bytes, the tile's " + what + " are " + std::to_string(size);
    return "";
  }
  const size_t n = ZSTD_decompressDCtx(zstd_contexts().decompress, out.data(), out.size(), packed.data(), packed.size());
  if (ZSTD_isError(n)) return std::string("not a zstd frame of the tile's ") + what + ": " + ZSTD_getErrorName(n);
  if (n != size)
    return "the zstd frame holds " + std::to_string(n) + " bytes, the tile's " + what + " are " + std::to_string(size);
  return "";
}

constexpr size_t kHeaderBytes = 8;
constexpr size_t kSurfaceBytes = 8;  // PixelSurface on the wire: f32 depth, 3 x i8 normal, u8 flags
constexpr int64_t kMaxThreads = 4096;
// Settings are checked by core/settings.h's check_settings(); liveness and
// credits are messages.h's, which the master's command line checks too.
constexpr int64_t kMaxBorder = 64;
// sin of the smallest angle allowed between camera forward and up.
constexpr float kMinSinForwardUp = 1e-4f;

// ---- Checks: each records "<field>: <what was wrong, what was expected>".

std::string show(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.9g", v);
  return text;
}

void check_range(Reader& r, const char* field, int64_t v, int64_t lo, int64_t hi) {
  if (v < lo || v > hi)
    r.fail(field, std::to_string(v) + ", expected [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
}

// lo <= v <= hi, which NaN fails.
void check_closed(Reader& r, const char* field, float v, float lo, float hi) {
  if (!(v >= lo && v <= hi)) r.fail(field, show(v) + ", expected [" + show(lo) + ", " + show(hi) + "]");
}

void check_finite(Reader& r, const char* field, float v) {
  if (!std::isfinite(v)) r.fail(field, show(v) + ", expected a finite number");
}

void check_finite_non_negative(Reader& r, const char* field, float v) {
  if (!(std::isfinite(v) && v >= 0.0f)) r.fail(field, show(v) + ", expected a finite number >= 0");
}

void check_finite(Reader& r, const char* field, glm::vec3 v) {
  for (int i = 0; i < 3; ++i) check_finite(r, field, v[i]);
}

// At most 64 bytes of a peer's text, non-printable bytes as '?', for an error message.
std::string quote(const std::string& text) {
  std::string shown = "\"";
  for (size_t i = 0; i < text.size() && i < 64; ++i) shown += std::isprint(uint8_t(text[i])) ? text[i] : '?';
  return shown + (text.size() > 64 ? "\"..." : "\"");
}

// The name becomes a file name in the worker's cache: no directories, no way up.
void check_file_name(Reader& r, const char* field, const std::string& name) {
  bool ok = !name.empty() && name.find_first_of(std::string("/\\\0", 3)) == std::string::npos &&
            name.find("..") == std::string::npos;
  if (!ok) r.fail(field, quote(name) + ", expected a non-empty file name without '/', '\\', NUL or \"..\"");
}

// Renderers normalise camera vectors in float: the length must be a normal float.
void check_direction(Reader& r, const char* field, glm::vec3 v) {
  check_finite(r, field, v);
  if (r.ok() && !std::isnormal(glm::length(v))) r.fail(field, "zero or degenerate length, expected a direction");
}

void check_camera(Reader& r, const Camera& camera) {
  check_finite(r, "frame.camera.position", camera.position);
  check_direction(r, "frame.camera.forward", camera.forward);
  check_direction(r, "frame.camera.up", camera.up);
  if (r.ok() && glm::length(glm::cross(glm::normalize(camera.forward), glm::normalize(camera.up))) < kMinSinForwardUp)
    r.fail("frame.camera.up", "parallel to forward, expected a direction across it");
  float vfov = camera.vfov;
  if (!(vfov > 0.0f && vfov < std::numbers::pi_v<float>))
    r.fail("frame.camera.vfov", show(vfov) + " radians, expected (0, pi)");
}

// ---- Shared parts.

void write(Writer& w, const RenderSettings& s) { write_settings(w, s); }
void read(Reader& r, RenderSettings& s) { read_settings(r, s); }

void write(Writer& w, const TileJob& t) {
  w.i32(t.x);
  w.i32(t.y);
  w.i32(t.w);
  w.i32(t.h);
  w.i32(t.border);
}

// x and y stay below kMaxImageSide so that x + w cannot overflow.
void read(Reader& r, TileJob& t) {
  t.x = r.i32("tile.x");
  check_range(r, "tile.x", t.x, 0, kMaxImageSide - 1);
  t.y = r.i32("tile.y");
  check_range(r, "tile.y", t.y, 0, kMaxImageSide - 1);
  t.w = r.i32("tile.w");
  check_range(r, "tile.w", t.w, 1, kMaxTileSide);
  t.h = r.i32("tile.h");
  check_range(r, "tile.h", t.h, 1, kMaxTileSide);
  t.border = r.i32("tile.border");
  check_range(r, "tile.border", t.border, 0, kMaxBorder);
}

// ---- Messages, in MessageType order.

void write(Writer& w, const Hello& m) {
  w.string(m.build_id);
  w.string(m.simd);
  w.u32(m.threads);
  w.string(m.libraries);
}

void read(Reader& r, Hello& m) {
  m.build_id = r.string("build_id", kMaxString);
  m.simd = r.string("simd", kMaxString);
  m.threads = r.u32("threads");
  check_range(r, "threads", m.threads, 1, kMaxThreads);
  m.libraries = r.string("libraries", kMaxString);
}

void write(Writer& w, const Welcome& m) {
  w.u64(m.session);
  w.string(m.scene_name);
  w.u64(m.scene_hash);
  w.u64(m.scene_size);
  w.vec3(m.environment);
  write(w, m.settings);
  w.u32(m.credits);
  w.u32(m.heartbeat_ms);
  w.u32(m.timeout_ms);
  w.u8(static_cast<uint8_t>(m.pixel_format));
  w.string(m.environment_map);
  w.u64(m.environment_map_hash);
  w.u64(m.environment_map_size);
  w.f32(m.environment_rotation);
  w.u8(static_cast<uint8_t>(m.light_units));
  w.u8(static_cast<uint8_t>(m.pixel_codec));
}

PixelCodec read_pixel_codec(Reader& r, const char* field) {
  const uint8_t codec = r.u8(field);
  check_range(r, field, codec, 0, static_cast<uint8_t>(PixelCodec::Lz4));
  return r.ok() ? PixelCodec(codec) : PixelCodec::Raw;
}

PixelFormat read_pixel_format(Reader& r, const char* field) {
  const uint8_t format = r.u8(field);
  check_range(r, field, format, 0, static_cast<uint8_t>(PixelFormat::Rgb9e5));
  return r.ok() ? PixelFormat(format) : PixelFormat::Float32;
}

void read(Reader& r, Welcome& m) {
  m.session = r.u64("session");
  m.scene_name = r.string("scene_name", kMaxString);
  check_file_name(r, "scene_name", m.scene_name);
  m.scene_hash = r.u64("scene_hash");
  m.scene_size = r.u64("scene_size");
  if (m.scene_size > kMaxSceneBytes)
    r.fail("scene_size", std::to_string(m.scene_size) + " bytes, over the limit of " + std::to_string(kMaxSceneBytes));
  m.environment = r.vec3("environment");
  for (int c = 0; c < 3; ++c)
    if (!(m.environment[c] >= 0.0f && m.environment[c] <= kMaxEnvironment))
      r.fail("environment", show(m.environment[c]) + ", expected a radiance from 0 to " + show(float(kMaxEnvironment)));
  read(r, m.settings);
  m.credits = r.u32("credits");
  check_range(r, "credits", m.credits, 1, kMaxCredits);
  m.heartbeat_ms = r.u32("heartbeat_ms");
  check_range(r, "heartbeat_ms", m.heartbeat_ms, kMinHeartbeatMs, kMaxHeartbeatMs);
  m.timeout_ms = r.u32("timeout_ms");
  check_range(r, "timeout_ms", m.timeout_ms, kMinTimeoutMs, kMaxTimeoutMs);
  m.pixel_format = read_pixel_format(r, "pixel_format");
  m.environment_map = r.string("environment_map", kMaxString);
  if (!m.environment_map.empty()) check_file_name(r, "environment_map", m.environment_map);
  m.environment_map_hash = r.u64("environment_map_hash");
  m.environment_map_size = r.u64("environment_map_size");
  if (m.environment_map_size > kMaxSceneBytes)
    r.fail("environment_map_size", std::to_string(m.environment_map_size) + " bytes, over the limit of " +
                                       std::to_string(kMaxSceneBytes));
  m.environment_rotation = r.f32("environment_rotation");
  if (!(std::abs(m.environment_rotation) <= 360.0f))
    r.fail("environment_rotation", show(m.environment_rotation) + ", expected degrees within +-360");
  const uint8_t units = r.u8("light_units");
  if (units > static_cast<uint8_t>(LightUnits::Radiometric))
    r.fail("light_units", std::to_string(units) + ", expected 0 (photometric) or 1 (radiometric)");
  m.light_units = r.ok() ? LightUnits(units) : LightUnits::Photometric;
  m.pixel_codec = read_pixel_codec(r, "pixel_codec");
}

void write(Writer& w, const Refuse& m) { w.string(m.reason); }

void read(Reader& r, Refuse& m) { m.reason = r.string("reason", kMaxString); }

void write(Writer& w, const SceneRequest& m) { w.u64(m.scene_hash); }

void read(Reader& r, SceneRequest& m) { m.scene_hash = r.u64("scene_hash"); }

void write(Writer& w, const SceneData& m) {
  w.u64(m.scene_hash);
  w.string(m.file_name);
  w.bytes(m.bytes);
}

void read(Reader& r, SceneData& m) {
  m.scene_hash = r.u64("scene_hash");
  m.file_name = r.string("file_name", kMaxString);
  check_file_name(r, "file_name", m.file_name);
  m.bytes = r.bytes("bytes", kMaxSceneBytes);
}

void write(Writer& w, const FrameSetupMsg& m) {
  const FrameSetup& f = m.frame;
  w.u64(f.frame_id);
  w.vec3(f.camera.position);
  w.vec3(f.camera.forward);
  w.vec3(f.camera.up);
  w.f32(f.camera.vfov);
  w.i32(f.width);
  w.i32(f.height);
  w.u32(f.seed);
  w.u32(f.sample_begin);
  w.u32(f.sample_count);
  w.f32(f.jitter_x);
  w.f32(f.jitter_y);
  w.f64(f.pose.time);
  w.vec3(f.pose.light_offset);
  w.boolean(f.want_surfaces);
  write(w, m.settings);
}

void read(Reader& r, FrameSetupMsg& m) {
  FrameSetup& f = m.frame;
  f.frame_id = r.u64("frame.frame_id");
  f.camera.position = r.vec3("frame.camera.position");
  f.camera.forward = r.vec3("frame.camera.forward");
  f.camera.up = r.vec3("frame.camera.up");
  f.camera.vfov = r.f32("frame.camera.vfov");
  check_camera(r, f.camera);
  f.width = r.i32("frame.width");
  check_range(r, "frame.width", f.width, 1, kMaxImageSide);
  f.height = r.i32("frame.height");
  check_range(r, "frame.height", f.height, 1, kMaxImageSide);
  f.seed = r.u32("frame.seed");
  f.sample_begin = r.u32("frame.sample_begin");
  f.sample_count = r.u32("frame.sample_count");
  // Sample indices sample_begin + i must not wrap around.
  check_range(r, "frame.sample_count", f.sample_count, 1, int64_t(UINT32_MAX) - f.sample_begin);
  f.jitter_x = r.f32("frame.jitter_x");
  check_closed(r, "frame.jitter_x", f.jitter_x, 0.0f, 1.0f);
  f.jitter_y = r.f32("frame.jitter_y");
  check_closed(r, "frame.jitter_y", f.jitter_y, 0.0f, 1.0f);
  f.pose.time = r.f64("frame.pose.time");
  if (!(std::abs(f.pose.time) <= kMaxSceneTime))  // NaN fails too
    r.fail("frame.pose.time", std::to_string(f.pose.time) + ", expected a finite time within +-1e9 s");
  f.pose.light_offset = r.vec3("frame.pose.light_offset");
  check_finite(r, "frame.pose.light_offset", f.pose.light_offset);
  f.want_surfaces = r.boolean("frame.want_surfaces");
  read(r, m.settings);
}

void write(Writer& w, const TileJobMsg& m) {
  w.u64(m.frame_id);
  w.u64(m.job_id);
  write(w, m.tile);
}

void read(Reader& r, TileJobMsg& m) {
  m.frame_id = r.u64("frame_id");
  m.job_id = r.u64("job_id");
  read(r, m.tile);
}

void write(Writer& w, const TileResult& m) {
  w.u64(m.frame_id);
  w.u64(m.job_id);
  write(w, m.tile);
  w.f32(m.render_seconds);
  w.u64(m.frame_state_hash);
  w.u64(m.rays.primary);
  w.u64(m.rays.shadow);
  w.u64(m.rays.secondary);
  w.u32(m.nonfinite_pixels);
  w.u8(static_cast<uint8_t>(m.pixel_format));
  w.u8(static_cast<uint8_t>(m.pixel_codec));
  w.u32(static_cast<uint32_t>(m.pixels.size()));
  static_assert(sizeof(glm::vec3) == 3 * sizeof(float));
  auto write_pixels = [&](Writer& to) {
    const float* values = &m.pixels.data()->x;
    switch (m.pixel_format) {
      case PixelFormat::Float32: to.floats(values, 3 * m.pixels.size()); break;
      case PixelFormat::Float16: to.halves(values, 3 * m.pixels.size()); break;
      case PixelFormat::Rgb9e5: to.rgb9e5s(values, m.pixels.size()); break;
    }
  };
  if (m.pixel_codec != PixelCodec::Raw) {
    Writer raw;
    raw.reserve(m.pixels.size() * bytes_per_pixel(m.pixel_format));
    write_pixels(raw);
    w.bytes(pack(m.pixel_codec, raw.take()));  // u32 length + the zstd frame or lz4 block
  } else {
    w.reserve(m.pixels.size() * bytes_per_pixel(m.pixel_format));
    write_pixels(w);
  }
  w.u32(static_cast<uint32_t>(m.surfaces.size()));
  auto write_surfaces = [&](Writer& to) {
    to.reserve(m.surfaces.size() * kSurfaceBytes);
    for (const PixelSurface& s : m.surfaces) {
      to.f32(s.depth);
      for (int8_t n : s.normal) to.u8(static_cast<uint8_t>(n));
      to.u8(s.flags);
    }
  };
  if (m.pixel_codec != PixelCodec::Raw && !m.surfaces.empty()) {
    Writer raw;
    write_surfaces(raw);
    w.bytes(pack(m.pixel_codec, raw.take()));
  } else {
    write_surfaces(w);
  }
}

PixelSurface read_surface(Reader& r) {
  PixelSurface s;
  s.depth = r.f32("surfaces.depth");
  for (int8_t& n : s.normal) n = static_cast<int8_t>(r.u8("surfaces.normal"));
  s.flags = r.u8("surfaces.flags");
  return s;
}

// The surfaces block: none, or one per pixel, each checked. Returns its
// bytes: the message's own, or when packed the block unpacked into `storage`.
std::span<const uint8_t> read_surface_block(Reader& r, const TileResult& m, std::vector<uint8_t>& storage) {
  const bool packed = m.pixel_codec != PixelCodec::Raw;
  const uint32_t n = packed ? r.u32("surfaces") : r.count("surfaces", kSurfaceBytes, size_t(kMaxTileSide) * kMaxTileSide);
  const size_t expected = size_t(m.tile.w) * size_t(m.tile.h);
  if (r.ok() && n != 0 && n != expected)
    r.fail("surfaces", std::to_string(n) + " surfaces, expected 0 or " + std::to_string(expected));
  if (!r.ok() || n == 0) return {};
  std::span<const uint8_t> block;
  if (packed) {
    const std::string field = packed_field("surfaces", m.pixel_codec);
    const std::span<const uint8_t> frame = r.span(field.c_str(), r.u32(field.c_str()));
    if (!r.ok()) return {};
    if (std::string error = unpack(m.pixel_codec, frame, size_t(n) * kSurfaceBytes, storage, "surfaces"); !error.empty()) {
      r.fail(field.c_str(), error);
      return {};
    }
    block = storage;
  } else {
    block = r.span("surfaces", size_t(n) * kSurfaceBytes);
  }
  // Checked straight from the bytes (a Reader call per field took a quarter
  // of the master's time on full-size previews): depth at 0, flags at 7.
  for (uint32_t i = 0; i < n && r.ok(); ++i) {
    PixelSurface s;
    std::memcpy(&s.depth, block.data() + size_t(i) * kSurfaceBytes, 4);  // little-endian, as copy_tile_surfaces reads it
    s.flags = block[size_t(i) * kSurfaceBytes + 7];
    if (!(std::isfinite(s.depth) && s.depth >= 0.0f))
      r.fail("surfaces", "surface " + std::to_string(i) + " has depth " + show(s.depth) +
                             ", expected a finite number >= 0");
    else if (s.flags & ~PixelSurface::kViewDependent)
      r.fail("surfaces", "surface " + std::to_string(i) + " has flags " + std::to_string(s.flags) +
                             ", expected 0 or " + std::to_string(PixelSurface::kViewDependent));
  }
  return r.ok() ? block : std::span<const uint8_t>{};
}

// Everything but the pixels themselves (the master copies those straight into its frame).
void read_fields(Reader& r, TileResult& m) {
  m.frame_id = r.u64("frame_id");
  m.job_id = r.u64("job_id");
  read(r, m.tile);
  m.render_seconds = r.f32("render_seconds");
  check_finite_non_negative(r, "render_seconds", m.render_seconds);
  m.frame_state_hash = r.u64("frame_state_hash");
  m.rays.primary = r.u64("rays.primary");
  m.rays.shadow = r.u64("rays.shadow");
  m.rays.secondary = r.u64("rays.secondary");
  m.nonfinite_pixels = r.u32("nonfinite_pixels");
  check_range(r, "nonfinite_pixels", m.nonfinite_pixels, 0, int64_t(m.tile.w) * m.tile.h);
  m.pixel_format = read_pixel_format(r, "pixel_format");
  m.pixel_codec = read_pixel_codec(r, "pixel_codec");
}

// The pixel block: its count must match the tile before anything is allocated
// or read for it. Returns its bytes, unchecked for finiteness: the message's
// own, or when packed the block unpacked into `storage` (exactly the tile's
// pixels, or an error: never more bytes than the tile holds).
std::span<const uint8_t> read_pixel_block(Reader& r, const TileResult& m, std::vector<uint8_t>& storage) {
  const size_t pixel_bytes = bytes_per_pixel(m.pixel_format);
  const bool packed = m.pixel_codec != PixelCodec::Raw;
  // Raw: the count must fit in what is left; packed: the block is checked below.
  const uint32_t n = packed ? r.u32("pixels") : r.count("pixels", pixel_bytes, size_t(kMaxTileSide) * kMaxTileSide);
  const size_t expected = size_t(m.tile.w) * size_t(m.tile.h);
  if (r.ok() && n != expected)
    r.fail("pixels", std::to_string(n) + " pixels, expected " + std::to_string(m.tile.w) + " x " +
                         std::to_string(m.tile.h) + " = " + std::to_string(expected));
  if (!r.ok()) return {};
  if (!packed) return r.span("pixels", size_t(n) * pixel_bytes);
  const std::string field = packed_field("pixels", m.pixel_codec);
  const std::span<const uint8_t> block = r.span(field.c_str(), r.u32(field.c_str()));
  if (!r.ok()) return {};
  if (std::string error = unpack(m.pixel_codec, block, size_t(n) * pixel_bytes, storage, "pixels"); !error.empty()) {
    r.fail(field.c_str(), error);
    return {};
  }
  return storage;
}

void read(Reader& r, TileResult& m) {
  read_fields(r, m);
  std::vector<uint8_t> storage, surface_storage;
  const std::span<const uint8_t> block = read_pixel_block(r, m, storage);
  const std::span<const uint8_t> surfaces = read_surface_block(r, m, surface_storage);
  // Trailing bytes before finiteness: the order decode_tile_result + copy_tile_pixels check them in.
  if (r.ok() && r.remaining() != 0)
    r.fail("TileResult: " + std::to_string(r.remaining()) + " trailing bytes after the payload");
  if (!r.ok()) return;
  const size_t n = block.size() / bytes_per_pixel(m.pixel_format);
  m.pixels.resize(n);
  Reader pixels(block);
  float* values = &m.pixels.data()->x;
  switch (m.pixel_format) {
    case PixelFormat::Float32: pixels.floats("pixels", values, 3 * n); break;
    case PixelFormat::Float16: pixels.halves("pixels", values, 3 * n); break;
    case PixelFormat::Rgb9e5: pixels.rgb9e5s("pixels", values, n); break;
  }
  for (size_t i = 0; i < n && r.ok(); ++i) {
    const glm::vec3 p = m.pixels[i];
    if (!(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z)))
      r.fail("pixels", "pixel " + std::to_string(i) + " is (" + show(p.x) + ", " + show(p.y) + ", " + show(p.z) +
                           "), expected finite values");
  }
  Reader each(surfaces);
  m.surfaces.resize(surfaces.size() / kSurfaceBytes);
  for (PixelSurface& s : m.surfaces) s = read_surface(each);
}

void write(Writer& w, const CancelFrame& m) { w.u64(m.frame_id); }

void read(Reader& r, CancelFrame& m) { m.frame_id = r.u64("frame_id"); }

void write(Writer&, const Heartbeat&) {}

void read(Reader&, Heartbeat&) {}

void write(Writer& w, const Bye& m) {
  w.string(m.reason);
  w.u8(static_cast<uint8_t>(m.kind));
}

void read(Reader& r, Bye& m) {
  m.reason = r.string("reason", kMaxString);
  const uint8_t kind = r.u8("kind");
  check_range(r, "kind", kind, 0, static_cast<uint8_t>(ByeKind::Failed));
  if (r.ok()) m.kind = ByeKind(kind);
}

// ---- Header and dispatch.

std::string hex(uint32_t v) {
  char text[16];
  std::snprintf(text, sizeof text, "0x%08x", v);
  return text;
}

// The message type, or nullopt with the error recorded. Magic and version come
// first so that a peer of another version is named as such.
std::optional<MessageType> read_header(Reader& r) {
  r.begin("header");
  if (r.remaining() < kHeaderBytes) {
    r.fail("message of " + std::to_string(r.remaining()) + " bytes, shorter than the " +
           std::to_string(kHeaderBytes) + "-byte header");
    return std::nullopt;
  }
  uint32_t magic = r.u32("magic");
  if (magic != kMagic) r.fail("not an igi message: magic " + hex(magic) + ", expected " + hex(kMagic) + " (\"IGI1\")");
  uint16_t version = r.u16("version");
  if (version != kVersion)
    r.fail("protocol version " + std::to_string(version) + ", this build speaks " + std::to_string(kVersion));
  uint8_t type = r.u8("type");
  if (type < uint8_t(MessageType::Hello) || type > uint8_t(MessageType::CancelFrame))
    r.fail("unknown message type " + std::to_string(type));
  uint8_t flags = r.u8("flags");
  if (r.ok() && flags != 0)
    r.fail(std::string(message_name(MessageType(type))) + ": flags " + hex(flags) + ", expected 0");
  if (!r.ok()) return std::nullopt;
  return MessageType(type);
}

template <class T>
Message read_message(Reader& r) {
  Message message{std::in_place_type<T>};
  read(r, std::get<T>(message));
  return message;
}

Message read_payload(Reader& r, MessageType type) {
  switch (type) {
    case MessageType::Hello: return read_message<Hello>(r);
    case MessageType::Welcome: return read_message<Welcome>(r);
    case MessageType::Refuse: return read_message<Refuse>(r);
    case MessageType::SceneRequest: return read_message<SceneRequest>(r);
    case MessageType::SceneData: return read_message<SceneData>(r);
    case MessageType::FrameSetup: return read_message<FrameSetupMsg>(r);
    case MessageType::TileJob: return read_message<TileJobMsg>(r);
    case MessageType::TileResult: return read_message<TileResult>(r);
    case MessageType::Heartbeat: return read_message<Heartbeat>(r);
    case MessageType::Bye: return read_message<Bye>(r);
    case MessageType::CancelFrame: return read_message<CancelFrame>(r);
  }
  r.fail("unknown message type " + std::to_string(int(type)));  // read_header let it through: a bug
  return Heartbeat{};
}

}  // namespace

std::vector<uint8_t> encode(const Message& message) {
  Writer w;
  w.u32(kMagic);
  w.u16(kVersion);
  w.u8(static_cast<uint8_t>(type_of(message)));
  w.u8(0);  // flags
  std::visit([&w](const auto& m) { write(w, m); }, message);
  return w.take();
}

namespace {
std::string oversized(size_t bytes) {
  return "message of " + std::to_string(bytes) + " bytes, over the limit of " + std::to_string(kMaxMessageBytes);
}
}  // namespace

bool is_tile_result(std::span<const uint8_t> bytes) {
  return bytes.size() >= kHeaderBytes && bytes[6] == static_cast<uint8_t>(MessageType::TileResult);
}

std::optional<TileResultHead> tile_result_head(std::span<const uint8_t> bytes, std::string& error) {
  Reader r(bytes);
  std::optional<MessageType> type = read_header(r);
  if (type && *type != MessageType::TileResult)
    r.fail(std::string(message_name(*type)) + " where a TileResult was expected");
  TileResultHead head;
  if (r.ok()) {
    r.begin(message_name(MessageType::TileResult));
    head.frame_id = r.u64("frame_id");
    head.job_id = r.u64("job_id");
    read(r, head.tile);
  }
  if (r.ok()) return head;
  error = r.error();
  return std::nullopt;
}

std::optional<TileResultView> decode_tile_result(std::span<const uint8_t> bytes, std::string& error) {
  if (bytes.size() > kMaxMessageBytes) {
    error = oversized(bytes.size());
    return std::nullopt;
  }
  Reader r(bytes);
  std::optional<MessageType> type = read_header(r);
  if (type && *type != MessageType::TileResult)
    r.fail(std::string(message_name(*type)) + " where a TileResult was expected");
  TileResultView view;
  if (r.ok()) {
    r.begin(message_name(MessageType::TileResult));
    read_fields(r, view.fields);
    view.pixel_bytes = read_pixel_block(r, view.fields, view.storage);
    view.surface_bytes = read_surface_block(r, view.fields, view.surface_storage);
    if (r.ok() && r.remaining() != 0)
      r.fail("TileResult: " + std::to_string(r.remaining()) + " trailing bytes after the payload");
  }
  if (!r.ok()) {
    error = r.error();
    return std::nullopt;
  }
  return view;
}

DecodeResult decode(std::span<const uint8_t> bytes) {
  if (bytes.size() > kMaxMessageBytes) return {std::nullopt, oversized(bytes.size())};
  Reader r(bytes);
  std::optional<MessageType> type = read_header(r);
  if (!type) return {std::nullopt, r.error()};
  std::string name = message_name(*type);
  r.begin(name);
  Message message = read_payload(r, *type);
  if (r.ok() && r.remaining() != 0)
    r.fail(name + ": " + std::to_string(r.remaining()) + " trailing bytes after the payload");
  if (!r.ok()) return {std::nullopt, r.error()};
  return {std::move(message), {}};
}

}  // namespace igi::protocol
