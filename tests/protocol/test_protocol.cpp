// The wire format: every message round-trips, and no bytes from a peer (cut
// short, corrupted, oversized, of another version) crash the decoder or get
// through as an invalid message. Then the socket helpers over loopback.
#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <bit>
#include <chrono>
#include <cmath>
#include <cstring>
#include <limits>
#include <numbers>

#include <gtest/gtest.h>

#include "image/frame_buffer.h"
#include "image/rgb9e5.h"
#include "protocol/codec.h"
#include "protocol/pixels.h"
#include "protocol/socket.h"

namespace igi::protocol {
namespace {

// ---- Field-by-field equality; floats compare by bits (so -0 != +0, NaN == NaN).

bool same(float a, float b) { return std::bit_cast<uint32_t>(a) == std::bit_cast<uint32_t>(b); }
bool same(glm::vec3 a, glm::vec3 b) { return same(a.x, b.x) && same(a.y, b.y) && same(a.z, b.z); }
bool same(const TileJob& a, const TileJob& b) {
  return a.x == b.x && a.y == b.y && a.w == b.w && a.h == b.h && a.border == b.border;
}
bool same(const RenderSettings& a, const RenderSettings& b) {
  return a.method == b.method && a.path_depth == b.path_depth && a.light_depth == b.light_depth &&
         a.specular_depth == b.specular_depth && a.interleave == b.interleave &&
         a.paths_per_set == b.paths_per_set && a.aa_samples == b.aa_samples &&
         same(a.glossy_threshold, b.glossy_threshold) && a.glossy_rays == b.glossy_rays && same(a.clamp, b.clamp) &&
         a.compensation_samples == b.compensation_samples && a.filter == b.filter &&
         same(a.filter_normal_cos, b.filter_normal_cos) && same(a.filter_depth_ratio, b.filter_depth_ratio) &&
         a.wavelet_levels == b.wavelet_levels &&
         same(a.lightcuts_error, b.lightcuts_error) && a.lightcuts_max_cut == b.lightcuts_max_cut &&
         a.lightcuts_spacing == b.lightcuts_spacing && a.lightcuts_samples == b.lightcuts_samples &&
         a.vpl_draws == b.vpl_draws && a.lightcuts_block == b.lightcuts_block &&
         a.glass_branches == b.glass_branches && a.caustics == b.caustics && a.caustic_photons == b.caustic_photons &&
         same(a.caustic_radius, b.caustic_radius) && a.importance_paths == b.importance_paths &&
         same(a.importance_floor, b.importance_floor) && a.bidir_vpls == b.bidir_vpls &&
         a.bidir_camera_paths == b.bidir_camera_paths;
}
bool same(const Hello& a, const Hello& b) {
  return a.build_id == b.build_id && a.simd == b.simd && a.threads == b.threads;
}
bool same(const Welcome& a, const Welcome& b) {
  return a.session == b.session && a.scene_name == b.scene_name && a.scene_hash == b.scene_hash &&
         a.scene_size == b.scene_size && a.environment == b.environment && same(a.settings, b.settings) && a.credits == b.credits &&
         a.heartbeat_ms == b.heartbeat_ms && a.timeout_ms == b.timeout_ms && a.pixel_format == b.pixel_format &&
         a.environment_map == b.environment_map && a.environment_map_hash == b.environment_map_hash &&
         a.environment_map_size == b.environment_map_size && a.environment_rotation == b.environment_rotation &&
         a.light_units == b.light_units && a.pixel_codec == b.pixel_codec;
}
bool same(const Refuse& a, const Refuse& b) { return a.reason == b.reason; }
bool same(const SceneRequest& a, const SceneRequest& b) { return a.scene_hash == b.scene_hash; }
bool same(const SceneData& a, const SceneData& b) {
  return a.scene_hash == b.scene_hash && a.file_name == b.file_name && a.bytes == b.bytes;
}
bool same(const FrameSetupMsg& a, const FrameSetupMsg& b) {
  const FrameSetup &f = a.frame, &g = b.frame;
  return f.frame_id == g.frame_id && same(f.camera.position, g.camera.position) &&
         same(f.camera.forward, g.camera.forward) && same(f.camera.up, g.camera.up) &&
         same(f.camera.vfov, g.camera.vfov) && f.width == g.width && f.height == g.height && f.seed == g.seed &&
         f.sample_begin == g.sample_begin && f.sample_count == g.sample_count && same(f.jitter_x, g.jitter_x) &&
         same(f.jitter_y, g.jitter_y) && f.want_surfaces == g.want_surfaces && same(a.settings, b.settings);
}
bool same(const TileJobMsg& a, const TileJobMsg& b) {
  return a.frame_id == b.frame_id && a.job_id == b.job_id && same(a.tile, b.tile);
}
bool same(const TileResult& a, const TileResult& b) {
  bool pixels = a.pixels.size() == b.pixels.size();
  for (size_t i = 0; pixels && i < a.pixels.size(); ++i) pixels = same(a.pixels[i], b.pixels[i]);
  return pixels && a.frame_id == b.frame_id && a.job_id == b.job_id && same(a.tile, b.tile) &&
         same(a.render_seconds, b.render_seconds) && a.frame_state_hash == b.frame_state_hash &&
         a.rays.primary == b.rays.primary && a.rays.shadow == b.rays.shadow && a.rays.secondary == b.rays.secondary &&
         a.nonfinite_pixels == b.nonfinite_pixels && a.pixel_format == b.pixel_format && a.surfaces == b.surfaces &&
         a.pixel_codec == b.pixel_codec;
}
bool same(const Heartbeat&, const Heartbeat&) { return true; }
bool same(const Bye& a, const Bye& b) { return a.reason == b.reason && a.kind == b.kind; }
bool same(const CancelFrame& a, const CancelFrame& b) { return a.frame_id == b.frame_id; }
bool same(const Message& a, const Message& b) {
  if (a.index() != b.index()) return false;
  return std::visit([&b](const auto& x) { return same(x, std::get<std::decay_t<decltype(x)>>(b)); }, a);
}

// ---- One message of every type, every field away from its default.

TileResult sample_tile_result() {
  TileResult m{9, 77, {64, 32, 8, 8, 1}, 0.125f, 0xa5a5a5a5deadbeefull, {100, 200, 300}, 3, PixelFormat::Float32, {}};
  for (int i = 0; i < 64; ++i) m.pixels.push_back({0.5f * float(i), -0.0f, 1e-3f * float(i * i)});
  for (int i = 0; i < 64; ++i)
    m.surfaces.push_back({0.25f * float(i), {int8_t(i), int8_t(-i), 127}, uint8_t(i % 3 == 0 ? 1 : 0)});
  return m;
}

// The same tile as half floats: values a half holds exactly (encode would round others).
TileResult sample_half_tile_result() {
  TileResult m = sample_tile_result();
  m.pixel_format = PixelFormat::Float16;
  for (int i = 0; i < 64; ++i) m.pixels[size_t(i)] = {0.5f * float(i), -0.0f, float(i) / 1024.0f};
  return m;
}

// Another set than Welcome's, every field away from its default: a frame's own settings.
RenderSettings frame_settings() {
  return RenderSettings{MethodKind::Igi, 9, 6, 2, 5, 25, 16, 25, 0.25f, 3, 0.2f, 4, true, 0.7f, 0.2f, 1, 0.04f, 400, 5, 9,
                        2, true, 2345, 0.03f};
}

std::vector<Message> samples() {
  RenderSettings settings{MethodKind::InstantRadiosity, 7, 5, 3, 4, 64, 8, 9, 0.3f, 2, 0.05f, 3, false, 0.8f, 0.1f, 3, 0.03f, 500, 6, 4,
                          5, true, 12345, 0.02f, 512, 0.3f, 64, 8};
  Camera camera{{1, 2, 3}, {0, -0.2f, -1}, {0.1f, 1, 0}, 0.9f};
  std::vector<uint8_t> scene(300);
  for (size_t i = 0; i < scene.size(); ++i) scene[i] = uint8_t(i * 7);
  return {
      Hello{"igi-1.0-abc123", "avx2", 12, "glibc 2.36, Embree 3.13.5"},
      Welcome{0x1122334455667788ull, "cornell.glb", 0xcbf29ce484222325ull, 123456, {0.5f, 1.0f, 2.0f}, settings, 3, 250, 1700,
              PixelFormat::Float16, "sky.exr", 0x5eed5eed5eed5eedull, 4096, -30.0f, LightUnits::Radiometric,
              PixelCodec::Zstd},
      Refuse{"build id mismatch: worker abc, master def"},
      SceneRequest{0xdeadbeefcafef00dull},
      SceneData{0x0123456789abcdefull, "scene.glb", scene},
      FrameSetupMsg{FrameSetup{42, camera, 640, 480, 7, 16, 4, 0.25f, 0.75f, {}, true}, frame_settings()},
      TileJobMsg{9, 77, {64, 32, 16, 8, 2}},
      sample_tile_result(),
      Heartbeat{},
      Bye{"shutting down", ByeKind::Quarantined},
      CancelFrame{0x0102030405060708ull},
  };
}

template <class T>
T sample() {
  for (const Message& m : samples())
    if (const T* p = std::get_if<T>(&m)) return *p;
  return T{};
}

// A sample of type T with one change.
template <class T>
Message edited(void (*change)(T&)) {
  T m = sample<T>();
  change(m);
  return m;
}

// The same, for a change inside Welcome::settings or FrameSetupMsg::frame.
Message settings_edited(void (*change)(RenderSettings&)) {
  Welcome m = sample<Welcome>();
  change(m.settings);
  return m;
}
Message frame_settings_edited(void (*change)(RenderSettings&)) {
  FrameSetupMsg m = sample<FrameSetupMsg>();
  change(m.settings);
  return m;
}
Message frame_edited(void (*change)(FrameSetup&)) {
  FrameSetupMsg m = sample<FrameSetupMsg>();
  change(m.frame);
  return m;
}

DecodeResult decode_copy(const std::vector<uint8_t>& bytes) {
  std::vector<uint8_t> exact(bytes);  // exactly sized, so ASan sees any over-read
  return decode(exact);
}

// ---- The codec.

TEST(Protocol, EveryTypeHasASampleANameAndItsOwnTag) {
  std::vector<Message> all = samples();
  ASSERT_EQ(all.size(), std::variant_size_v<Message>);
  for (size_t i = 0; i < all.size(); ++i) {
    EXPECT_EQ(all[i].index(), i);
    EXPECT_EQ(uint8_t(type_of(all[i])), i + 1);
    EXPECT_STRNE(message_name(type_of(all[i])), "Unknown");
  }
  EXPECT_STREQ(message_name(MessageType::TileResult), "TileResult");
  EXPECT_STREQ(message_name(MessageType(0)), "Unknown");
}

TEST(Protocol, RoundTripsEveryTypeFieldByField) {
  for (const Message& m : samples()) {
    std::vector<uint8_t> bytes = encode(m);
    DecodeResult d = decode_copy(bytes);
    ASSERT_TRUE(d.message) << message_name(type_of(m)) << ": " << d.error;
    EXPECT_TRUE(d.error.empty());
    EXPECT_TRUE(same(*d.message, m)) << message_name(type_of(m));
    EXPECT_EQ(encode(*d.message), bytes) << message_name(type_of(m));
  }
}

TEST(Protocol, HeaderAndFieldsAreLittleEndian) {
  std::vector<uint8_t> bytes = encode(SceneRequest{0x0102030405060708ull});
  std::vector<uint8_t> expected = {'I', 'G', 'I', '1', uint8_t(kVersion), 0, uint8_t(MessageType::SceneRequest), 0,
                                   8,   7,   6,   5,   4, 3, 2,                                   1};
  EXPECT_EQ(bytes, expected);
}

TEST(Protocol, EveryTruncationIsRejected) {
  for (const Message& m : samples()) {
    std::vector<uint8_t> bytes = encode(m);
    for (size_t n = 0; n < bytes.size(); ++n) {
      DecodeResult d = decode_copy(std::vector<uint8_t>(bytes.begin(), bytes.begin() + n));
      EXPECT_FALSE(d.message) << message_name(type_of(m)) << " cut to " << n << " bytes";
      EXPECT_FALSE(d.error.empty()) << message_name(type_of(m)) << " cut to " << n << " bytes";
    }
  }
}

// Accepted corruptions must be valid messages: decode only accepts canonical
// bytes, so encoding the result gives back exactly the corrupted bytes.
TEST(Protocol, EverySingleByteCorruptionIsRejectedOrValid) {
  for (const Message& m : samples()) {
    const std::vector<uint8_t> bytes = encode(m);
    for (size_t i = 0; i < bytes.size(); ++i) {
      for (uint8_t value : {uint8_t(bytes[i] ^ 0xFF), uint8_t(0), uint8_t(0xFF)}) {
        if (value == bytes[i]) continue;
        std::vector<uint8_t> corrupt = bytes;
        corrupt[i] = value;
        DecodeResult d = decode_copy(corrupt);
        if (d.message) {
          EXPECT_TRUE(d.error.empty());
          EXPECT_EQ(encode(*d.message), corrupt) << message_name(type_of(m)) << " byte " << i;
        } else {
          EXPECT_FALSE(d.error.empty()) << message_name(type_of(m)) << " byte " << i;
        }
        if (i < 8) {
          EXPECT_FALSE(d.message) << "header byte " << i << " corrupted yet accepted";
        }
      }
    }
  }
}

TEST(Protocol, OtherVersionIsNamedWithBothVersions) {
  std::vector<uint8_t> bytes = encode(sample<Hello>());
  bytes[4] = uint8_t(kVersion + 1);
  DecodeResult d = decode_copy(bytes);
  EXPECT_FALSE(d.message);
  EXPECT_EQ(d.error, "protocol version " + std::to_string(kVersion + 1) + ", this build speaks " + std::to_string(kVersion));
}

TEST(Protocol, HeaderErrors) {
  std::vector<uint8_t> bytes = encode(Heartbeat{});
  auto error_with = [&bytes](size_t i, uint8_t v) {
    std::vector<uint8_t> b = bytes;
    b[i] = v;
    return decode_copy(b).error;
  };
  EXPECT_NE(error_with(0, 'X').find("magic"), std::string::npos);
  EXPECT_EQ(error_with(6, 0), "unknown message type 0");
  EXPECT_EQ(error_with(6, 12), "unknown message type 12");
  EXPECT_EQ(error_with(7, 1), "Heartbeat: flags 0x00000001, expected 0");
  EXPECT_NE(decode_copy({1, 2, 3}).error.find("shorter than the 8-byte header"), std::string::npos);
}

TEST(Protocol, TrailingBytesAreRejected) {
  for (const Message& m : samples()) {
    std::vector<uint8_t> bytes = encode(m);
    bytes.push_back(0);
    DecodeResult d = decode_copy(bytes);
    EXPECT_FALSE(d.message);
    EXPECT_EQ(d.error, std::string(message_name(type_of(m))) + ": 1 trailing bytes after the payload");
  }
}

TEST(Protocol, HalfFloatTilesRoundTripAndTakeHalfTheBytes) {
  const TileResult m = sample_half_tile_result();
  const std::vector<uint8_t> bytes = encode(m);
  EXPECT_EQ(encode(sample_tile_result()).size() - bytes.size(), 64u * 6u) << "6 bytes a pixel instead of 12";
  DecodeResult d = decode_copy(bytes);
  ASSERT_TRUE(d.message) << d.error;
  EXPECT_TRUE(same(*d.message, m));
  EXPECT_EQ(encode(*d.message), bytes);
  // A value a half cannot hold is rounded to the nearest one; beyond 65504 it is infinite and refused.
  TileResult rounded = m;
  rounded.pixels[5].x = 1.0f + 1.0f / 4096.0f;
  DecodeResult r = decode_copy(encode(rounded));
  ASSERT_TRUE(r.message) << r.error;
  EXPECT_EQ(std::get<TileResult>(*r.message).pixels[5].x, 1.0f) << "ties to even";
  TileResult huge = m;
  huge.pixels[9].z = 70000.0f;
  EXPECT_EQ(decode_copy(encode(huge)).error.rfind("TileResult.pixels: pixel 9 is (4.5, -0, inf)", 0), 0u)
      << decode_copy(encode(huge)).error;
}

// The master's path: a view over the bytes, pixels copied straight into a frame.
TEST(Protocol, TileResultViewAgreesWithDecodeAndCopiesIntoAFrame) {
  TileResult packed = sample_tile_result(), packed_half = sample_half_tile_result();
  packed.pixel_codec = packed_half.pixel_codec = PixelCodec::Zstd;
  for (const TileResult& m : {sample_tile_result(), sample_half_tile_result(), packed, packed_half}) {
    const std::vector<uint8_t> bytes = encode(m);
    std::string error;
    std::optional<TileResultView> view = decode_tile_result(bytes, error);
    ASSERT_TRUE(view) << error;
    EXPECT_TRUE(view->fields.pixels.empty());
    EXPECT_EQ(view->fields.job_id, m.job_id);
    EXPECT_EQ(view->fields.nonfinite_pixels, m.nonfinite_pixels);
    EXPECT_EQ(view->pixel_bytes.size(), 64 * bytes_per_pixel(m.pixel_format));
    FrameBuffer frame(80, 48, m.pixel_format);
    ASSERT_EQ(copy_tile_pixels(*view, frame.pixel(m.tile.x, m.tile.y), frame.row_bytes()), "");
    const Image image = frame.to_image();
    for (int y = 0; y < 8; ++y)
      for (int x = 0; x < 8; ++x)
        EXPECT_TRUE(same(image.at(64 + x, 32 + y), m.pixels[size_t(y * 8 + x)])) << x << ", " << y;
    // A non-finite pixel: the copy fails with decode()'s own words.
    TileResult bad = m;
    bad.pixels[42].y = std::numeric_limits<float>::quiet_NaN();
    const std::vector<uint8_t> bad_bytes = encode(bad);
    view = decode_tile_result(bad_bytes, error);
    ASSERT_TRUE(view) << "finiteness is checked by the copy";
    EXPECT_EQ(copy_tile_pixels(*view, frame.pixel(64, 32), frame.row_bytes()), decode_copy(bad_bytes).error);
    // Anything else decode() refuses, the view refuses with the same error.
    for (size_t cut : {size_t(0), size_t(12), bytes.size() - 1}) {
      const std::vector<uint8_t> short_bytes(bytes.begin(), bytes.begin() + long(cut));
      EXPECT_FALSE(decode_tile_result(short_bytes, error));
      EXPECT_EQ(error, decode_copy(short_bytes).error);
    }
  }
  std::string error;
  EXPECT_FALSE(decode_tile_result(encode(Heartbeat{}), error));
  EXPECT_EQ(error, "Heartbeat where a TileResult was expected");
}

// Packed pixels (--pixel-codec zstd or lz4): the same pixels as the raw
// block, fewer bytes for a rendered-looking tile, and a block that is not the
// tile's pixels refused with a clear error, never more than the tile allocated.
TEST(Protocol, PackedPixelsDecodeToTheRawBlockAndBadBlocksAreRefused) {
  for (PixelCodec codec : {PixelCodec::Zstd, PixelCodec::Lz4})
    for (PixelFormat format : {PixelFormat::Float32, PixelFormat::Float16, PixelFormat::Rgb9e5}) {
      const std::string name = std::string(pixel_codec_name(codec)) + " " + pixel_format_name(format);
      const std::string field = std::string("TileResult.pixels.") + pixel_codec_name(codec);
      TileResult raw = sample_tile_result();
      raw.pixel_format = format;
      raw.tile.w = raw.tile.h = 32;
      raw.pixels.clear();
      raw.surfaces.clear();
      for (int y = 0; y < 32; ++y)  // a smooth wall (rendered tiles' ratios: tests/bench/RESULTS.md)
        for (int x = 0; x < 32; ++x)
          raw.pixels.push_back(glm::vec3(0.4f + 0.01f * float(x % 8), 0.3f, 0.2f + 0.005f * float(y % 4)));
      TileResult packed = raw;
      packed.pixel_codec = codec;
      const std::vector<uint8_t> raw_bytes = encode(raw), packed_bytes = encode(packed);
      EXPECT_LT(packed_bytes.size(), raw_bytes.size() * 3 / 4) << name;
      const DecodeResult a = decode_copy(raw_bytes), b = decode_copy(packed_bytes);
      ASSERT_TRUE(a.message && b.message) << a.error << b.error;
      const auto& pa = std::get<TileResult>(*a.message).pixels;
      const auto& pb = std::get<TileResult>(*b.message).pixels;
      ASSERT_EQ(pa.size(), pb.size());
      for (size_t i = 0; i < pa.size(); ++i) ASSERT_TRUE(same(pa[i], pb[i])) << i;
      std::string error;
      const std::optional<TileResultView> va = decode_tile_result(raw_bytes, error),
                                          vb = decode_tile_result(packed_bytes, error);
      ASSERT_TRUE(va && vb) << error;
      ASSERT_TRUE(std::equal(va->pixel_bytes.begin(), va->pixel_bytes.end(), vb->pixel_bytes.begin(), vb->pixel_bytes.end()));
      // The packed block sits after the count: u32 length, then the block.
      const size_t block_at = 8 + 16 + 20 + 4 + 8 + 24 + 4 + 1 + 1 + 4;
      uint32_t length;
      std::memcpy(&length, packed_bytes.data() + block_at, 4);
      std::vector<uint8_t> bad = packed_bytes;
      if (codec == PixelCodec::Zstd) bad[block_at + 4] ^= 0xFF;  // the frame's magic number
      else std::fill_n(bad.begin() + long(block_at) + 4, length, uint8_t(0xFF));  // literals past the block's end
      const std::string not_it = codec == PixelCodec::Zstd ? ": not a zstd frame of the tile's pixels"
                                                           : ": not an lz4 block of the tile's pixels";
      EXPECT_EQ(decode_copy(bad).error.rfind(field + not_it, 0), 0u) << decode_copy(bad).error;
      EXPECT_FALSE(decode_tile_result(bad, error));
      EXPECT_EQ(error, decode_copy(bad).error);
      bad = packed_bytes;
      bad[block_at + 3] = 0x7F;  // a length past the message
      EXPECT_EQ(decode_copy(bad).error.rfind(field + ": truncated", 0), 0u) << decode_copy(bad).error;
      // A well-formed block of the wrong size: a tile that claims 16 x 32 pixels.
      bad = packed_bytes;
      TileResult half_tile = packed;
      half_tile.tile.h = 16;
      half_tile.pixels.resize(16 * 32);
      const std::vector<uint8_t> small = encode(half_tile);
      std::copy_n(small.begin() + 24, 20, bad.begin() + 24);      // the tile's rectangle
      std::copy_n(small.begin() + 86, 4, bad.begin() + 86);       // the pixel count
      EXPECT_NE(decode_copy(bad).error.find(field), std::string::npos) << decode_copy(bad).error;
    }
}

// Shared-exponent pixels (--pixels rgb9e5): 4 bytes a pixel on the wire, each
// pixel the rounding of image/rgb9e5.h, the same through decode() and the
// master's view and copy, raw or zstd-packed; nothing to refuse as non-finite.
TEST(Protocol, Rgb9e5PixelsTravelAsTheirRoundingInFourBytes) {
  TileResult m = sample_tile_result();
  m.pixel_format = PixelFormat::Rgb9e5;
  m.pixels[5] = glm::vec3(-1.0f, 70000.0f, 1e-9f);  // outside the range: 0, the top, 0
  for (PixelCodec codec : {PixelCodec::Raw, PixelCodec::Zstd, PixelCodec::Lz4}) {
    m.pixel_codec = codec;
    const std::vector<uint8_t> bytes = encode(m);
    if (codec == PixelCodec::Raw) {
      TileResult as_float = m;
      as_float.pixel_format = PixelFormat::Float32;
      EXPECT_EQ(encode(as_float).size() - bytes.size(), 64u * 8u) << "4 bytes a pixel where floats take 12";
    }
    const DecodeResult d = decode_copy(bytes);
    ASSERT_TRUE(d.message) << d.error;
    const auto& pixels = std::get<TileResult>(*d.message).pixels;
    std::string error;
    const std::optional<TileResultView> view = decode_tile_result(bytes, error);
    ASSERT_TRUE(view) << error;
    FrameBuffer frame(80, 48, PixelFormat::Rgb9e5);
    ASSERT_EQ(copy_tile_pixels(*view, frame.pixel(64, 32), frame.row_bytes()), "");
    const Image image = frame.to_image();
    for (int i = 0; i < 64; ++i) {
      const glm::vec3 rounded = from_rgb9e5(to_rgb9e5(m.pixels[size_t(i)]));
      ASSERT_TRUE(same(pixels[size_t(i)], rounded)) << i;
      ASSERT_TRUE(same(image.at(64 + i % 8, 32 + i / 8), rounded)) << i;
    }
    EXPECT_EQ(pixels[5], glm::vec3(0.0f, kRgb9e5Max, 0.0f));
    EXPECT_EQ(encode(*d.message), bytes) << "the decoded tile re-encodes to its bytes";
  }
}

TEST(Protocol, WorkersSendFinitePixelsInTheFormatsRange) {
  std::vector<glm::vec3> pixels = {{1, 2, 3}, {NAN, 0.5f, 0.5f}, {0, INFINITY, 0}, {1e6f, -1e6f, 7}};
  std::vector<glm::vec3> as_float = pixels;
  EXPECT_EQ(wire_pixels(as_float, PixelFormat::Float32), 2u);
  EXPECT_EQ(as_float[0], glm::vec3(1, 2, 3));
  EXPECT_EQ(as_float[1], glm::vec3(0)) << "the whole pixel, not only the bad channel";
  EXPECT_EQ(as_float[2], glm::vec3(0));
  EXPECT_EQ(as_float[3], glm::vec3(1e6f, -1e6f, 7)) << "floats keep their range";
  std::vector<glm::vec3> as_half = pixels;
  EXPECT_EQ(wire_pixels(as_half, PixelFormat::Float16), 2u);
  EXPECT_EQ(as_half[3], glm::vec3(65504.0f, -65504.0f, 7)) << "clamped to the largest finite half";
  TileResult m = sample_half_tile_result();
  m.tile.w = 2;
  m.tile.h = 2;
  m.pixels = as_half;
  m.surfaces.clear();
  EXPECT_TRUE(decode_copy(encode(m)).message) << "sendable as halves";
}

TEST(Protocol, TileResultPixelsMustMatchTheTileAndBeFinite) {
  TileResult m = sample_tile_result();
  m.pixels.resize(37);
  EXPECT_EQ(decode_copy(encode(m)).error, "TileResult.pixels: 37 pixels, expected 8 x 8 = 64");
  for (float bad : {std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::infinity()}) {
    m = sample_tile_result();
    m.pixels[13].y = bad;
    DecodeResult d = decode_copy(encode(m));
    EXPECT_FALSE(d.message);
    EXPECT_NE(d.error.find("TileResult.pixels: pixel 13"), std::string::npos) << d.error;
  }
}

// The window's pixel surfaces: none or one a pixel, each with a finite depth
// >= 0 and no flag but kViewDependent; the master's in-place path agrees.
TEST(Protocol, TileResultSurfacesMatchTheTileAndHoldOnlyWhatTheyMayHold) {
  TileResult m = sample_tile_result();
  m.surfaces.clear();
  EXPECT_TRUE(decode_copy(encode(m)).message) << "a frame that did not ask for surfaces";
  const struct {
    void (*change)(TileResult&);
    const char* error;
  } cases[] = {
      {[](TileResult& r) { r.surfaces.resize(37); }, "TileResult.surfaces: 37 surfaces, expected 0 or 64"},
      {[](TileResult& r) { r.surfaces[5].depth = -1.0f; }, "TileResult.surfaces: surface 5 has depth -1, expected"},
      {[](TileResult& r) { r.surfaces[6].depth = std::numeric_limits<float>::quiet_NaN(); },
       "TileResult.surfaces: surface 6 has depth nan"},
      {[](TileResult& r) { r.surfaces[7].flags = 2; }, "TileResult.surfaces: surface 7 has flags 2, expected 0 or 1"},
  };
  // Raw, and packed with the pixels' codec: the same rules, the same words.
  for (PixelCodec codec : {PixelCodec::Raw, PixelCodec::Zstd, PixelCodec::Lz4})
    for (const auto& c : cases) {
      m = sample_tile_result();
      m.pixel_codec = codec;
      c.change(m);
      const std::vector<uint8_t> bytes = encode(m);
      const DecodeResult d = decode_copy(bytes);
      EXPECT_FALSE(d.message) << c.error;
      EXPECT_EQ(d.error.rfind(c.error, 0), 0u) << d.error;
      std::string error;
      EXPECT_FALSE(decode_tile_result(bytes, error)) << c.error;
      EXPECT_EQ(error, d.error) << "the master's in-place path says the same";
    }
  for (PixelCodec codec : {PixelCodec::Raw, PixelCodec::Zstd, PixelCodec::Lz4}) {
    m = sample_tile_result();
    m.pixel_codec = codec;
    const std::vector<uint8_t> bytes = encode(m);
    std::string error;
    const std::optional<TileResultView> view = decode_tile_result(bytes, error);
    ASSERT_TRUE(view) << error;
    std::vector<PixelSurface> frame(16 * 10);  // the tile's 8 x 8 at (2, 1) of a 16-wide frame
    copy_tile_surfaces(*view, &frame[1 * 16 + 2], 16);
    for (int y = 0; y < 8; ++y)
      for (int x = 0; x < 8; ++x) ASSERT_EQ(frame[size_t(y + 1) * 16 + size_t(x + 2)], m.surfaces[size_t(y) * 8 + x]);
    EXPECT_EQ(frame[0], PixelSurface{}) << "nothing outside the tile";
    EXPECT_EQ(std::get<TileResult>(*decode_copy(bytes).message).surfaces, m.surfaces);
  }
  // A packed surface block that is not the tile's surfaces is refused, by both paths alike.
  m = sample_tile_result();
  m.pixel_codec = PixelCodec::Zstd;
  std::vector<uint8_t> bad = encode(m);
  m.surfaces.clear();
  const size_t surfaces_at = encode(m).size() - 4;  // the same message without surfaces ends with their count, 0
  bad[surfaces_at + 8] ^= 0xFF;                       // after the count and the frame's length: its magic number
  const std::string refused = decode_copy(bad).error;
  EXPECT_EQ(refused.rfind("TileResult.surfaces.zstd: not a zstd frame of the tile's surfaces", 0), 0u) << refused;
  std::string error;
  EXPECT_FALSE(decode_tile_result(bad, error));
  EXPECT_EQ(error, refused);
  // FrameSetup's want_surfaces is a boolean: header 8, id 8, camera 40, size 8, seed and samples 12, jitter 8,
  // time 8, light offset 12 bytes before it.
  std::vector<uint8_t> setup = encode(sample<FrameSetupMsg>());
  ASSERT_EQ(setup[104], 1);
  setup[104] = 2;
  EXPECT_EQ(decode_copy(setup).error.rfind("FrameSetup.frame.want_surfaces", 0), 0u) << decode_copy(setup).error;
}

// Each change breaks one rule; the error must name the message and field.
TEST(Protocol, EveryFieldRuleIsEnforced) {
  struct Case { Message message; const char* error_starts; };
  std::vector<Case> cases = {
      {edited<Hello>([](Hello& m) { m.threads = 0; }), "Hello.threads: 0, expected [1, 4096]"},
      {edited<Hello>([](Hello& m) { m.threads = 4097; }), "Hello.threads: 4097"},
      {edited<Hello>([](Hello& m) { m.build_id.assign(kMaxString + 1, 'x'); }), "Hello.build_id: length 4097"},
      {edited<Welcome>([](Welcome& m) { m.credits = 0; }), "Welcome.credits"},
      {edited<Welcome>([](Welcome& m) { m.credits = 65; }), "Welcome.credits"},
      {edited<Welcome>([](Welcome& m) { m.heartbeat_ms = 9; }), "Welcome.heartbeat_ms"},
      {edited<Welcome>([](Welcome& m) { m.heartbeat_ms = 60001; }), "Welcome.heartbeat_ms"},
      {edited<Welcome>([](Welcome& m) { m.scene_name = "../x"; }), "Welcome.scene_name: \"../x\", expected"},
      {edited<Welcome>([](Welcome& m) { m.scene_name = ""; }), "Welcome.scene_name"},
      {edited<Welcome>([](Welcome& m) { m.scene_name = "a/b"; }), "Welcome.scene_name"},
      {edited<Welcome>([](Welcome& m) { m.scene_name = "a\\b"; }), "Welcome.scene_name"},
      {edited<Welcome>([](Welcome& m) { m.scene_name = std::string("a\0b", 3); }), "Welcome.scene_name"},
      {edited<Welcome>([](Welcome& m) { m.scene_name = ".."; }), "Welcome.scene_name"},
      {edited<Welcome>([](Welcome& m) { m.scene_size = kMaxSceneBytes + 1; }), "Welcome.scene_size"},
      {settings_edited([](auto& s) { s.path_depth = -1; }), "Welcome.settings.path_depth"},
      {settings_edited([](auto& s) { s.light_depth = 1025; }), "Welcome.settings.light_depth"},
      {settings_edited([](auto& s) { s.specular_depth = -2; }), "Welcome.settings.specular_depth"},
      {settings_edited([](auto& s) { s.aa_samples = 0; }), "Welcome.settings.aa_samples"},
      {settings_edited([](auto& s) { s.aa_samples = 8; }), "Welcome.settings.aa_samples: --aa: expected a square"},
      {settings_edited([](auto& s) { s.aa_samples = 81; }), "Welcome.settings.aa_samples"},
      {settings_edited([](auto& s) { s.aa_samples = 16; s.paths_per_set = 9; }), "Welcome.settings.aa_samples"},
      {settings_edited([](auto& s) { s.glossy_threshold = -0.1f; }), "Welcome.settings.glossy_threshold"},
      {settings_edited([](auto& s) { s.glossy_threshold = NAN; }), "Welcome.settings.glossy_threshold"},
      {settings_edited([](auto& s) { s.glossy_rays = 0; }), "Welcome.settings.glossy_rays"},
      {settings_edited([](auto& s) { s.glossy_rays = 65; }), "Welcome.settings.glossy_rays"},
      {settings_edited([](auto& s) { s.interleave = 17; }), "Welcome.settings.interleave"},
      {settings_edited([](auto& s) { s.importance_paths = -1; }), "Welcome.settings.importance_paths"},
      {settings_edited([](auto& s) { s.importance_paths = (1 << 20) + 1; }), "Welcome.settings.importance_paths"},
      {settings_edited([](auto& s) { s.importance_floor = 1.5f; }), "Welcome.settings.importance_floor"},
      {settings_edited([](auto& s) { s.importance_floor = NAN; }), "Welcome.settings.importance_floor"},
      {settings_edited([](auto& s) { s.bidir_vpls = -2; }), "Welcome.settings.bidir_vpls"},
      {settings_edited([](auto& s) { s.bidir_vpls = (1 << 16) + 1; }), "Welcome.settings.bidir_vpls"},
      {settings_edited([](auto& s) { s.bidir_camera_paths = 4097; }), "Welcome.settings.bidir_camera_paths"},
      {settings_edited([](auto& s) { s.method = MethodKind::PathTracer; s.importance_paths = 0; s.caustics = false; }),
       "Welcome.settings.bidir_vpls: --bidir: only for --method ir or igi"},
      {settings_edited([](auto& s) { s.bidir_vpls = 4; }), "Welcome.settings.bidir_vpls: --bidir 4 with --aa 9"},
      {settings_edited([](auto& s) { s.interleave = 0; }), "Welcome.settings.interleave"},
      {settings_edited([](auto& s) { s.paths_per_set = (1 << 20) + 1; }), "Welcome.settings.paths_per_set"},
      {settings_edited([](auto& s) { s.paths_per_set = -3; }), "Welcome.settings.paths_per_set"},
      {settings_edited([](auto& s) { s.clamp = -0.5f; }), "Welcome.settings.clamp"},
      {settings_edited([](auto& s) { s.clamp = INFINITY; }), "Welcome.settings.clamp"},
      {settings_edited([](auto& s) { s.compensation_samples = -1; }), "Welcome.settings.compensation_samples"},
      {settings_edited([](auto& s) { s.compensation_samples = 257; }), "Welcome.settings.compensation_samples"},
      {settings_edited([](auto& s) { s.filter_normal_cos = 1.01f; }), "Welcome.settings.filter_normal_cos"},
      {settings_edited([](auto& s) { s.filter_normal_cos = NAN; }), "Welcome.settings.filter_normal_cos"},
      {settings_edited([](auto& s) { s.filter_depth_ratio = -1e-6f; }), "Welcome.settings.filter_depth_ratio"},
      {settings_edited([](auto& s) { s.wavelet_levels = kMaxWaveletLevels + 1; }), "Welcome.settings.wavelet_levels"},
      {settings_edited([](auto& s) { s.vpl_draws = -1; }), "Welcome.settings.vpl_draws: --vpl-draws: expected 0..1024"},
      {frame_settings_edited([](auto& s) { s.vpl_draws = kMaxVplDraws + 1; }), "FrameSetup.settings.vpl_draws"},
      {settings_edited([](auto& s) { s.method = MethodKind(4); }), "Welcome.settings.method: --method: expected pt, ir, igi or lightcuts (0..3), got 4"},
      {settings_edited([](auto& s) { s.lightcuts_error = 0; }), "Welcome.settings.lightcuts_error: --lightcuts-error: expected a number in (0, 1), got 0"},
      {settings_edited([](auto& s) { s.lightcuts_error = 1; }), "Welcome.settings.lightcuts_error"},
      {settings_edited([](auto& s) { s.lightcuts_error = NAN; }), "Welcome.settings.lightcuts_error"},
      {settings_edited([](auto& s) { s.lightcuts_max_cut = 0; }), "Welcome.settings.lightcuts_max_cut: --lightcuts-max-cut: expected 1.."},
      {settings_edited([](auto& s) { s.lightcuts_max_cut = (1 << 20) + 1; }), "Welcome.settings.lightcuts_max_cut"},
      {settings_edited([](auto& s) { s.lightcuts_spacing = -1; }), "Welcome.settings.lightcuts_spacing"},
      {settings_edited([](auto& s) { s.lightcuts_spacing = 65; }), "Welcome.settings.lightcuts_spacing"},
      {settings_edited([](auto& s) { s.lightcuts_samples = 0; }), "Welcome.settings.lightcuts_samples"},
      {settings_edited([](auto& s) { s.lightcuts_samples = 65; }), "Welcome.settings.lightcuts_samples"},
      {settings_edited([](auto& s) { s.lightcuts_block = -1; }),
       "Welcome.settings.lightcuts_block: --lightcuts-block: expected 0..8 (0 or 1 = a cut per pixel), got -1"},
      {frame_settings_edited([](auto& s) { s.lightcuts_block = 9; }), "FrameSetup.settings.lightcuts_block"},
      {settings_edited([](auto& s) { s.method = MethodKind::Lightcuts; s.caustics = false; s.lightcuts_samples = 5; }),
       "Welcome.settings.lightcuts_samples: --lightcuts-samples: expected a square number"},
      {settings_edited([](auto& s) { s.glass_branches = 0; }), "Welcome.settings.glass_branches: --glass-branches: expected 1..8, got 0"},
      {settings_edited([](auto& s) { s.glass_branches = 9; }), "Welcome.settings.glass_branches"},
      {settings_edited([](auto& s) { s.caustic_photons = 0; }), "Welcome.settings.caustic_photons: --caustic-photons: expected 1.."},
      {settings_edited([](auto& s) { s.caustic_photons = (1 << 26) + 1; }), "Welcome.settings.caustic_photons"},
      {settings_edited([](auto& s) { s.caustic_radius = 0; }), "Welcome.settings.caustic_radius: --caustic-radius: expected a fraction of the scene diagonal in ["},
      {settings_edited([](auto& s) { s.caustic_radius = 0.26f; }), "Welcome.settings.caustic_radius"},
      {settings_edited([](auto& s) { s.caustic_radius = NAN; }), "Welcome.settings.caustic_radius"},
      {edited<SceneData>([](SceneData& m) { m.file_name = "dir/scene.glb"; }), "SceneData.file_name"},
      {edited<SceneData>([](SceneData& m) { m.file_name = ""; }), "SceneData.file_name"},
      {frame_edited([](auto& f) { f.width = 0; }), "FrameSetup.frame.width: 0"},
      {frame_settings_edited([](auto& s) { s.paths_per_set = 0; }), "FrameSetup.settings.paths_per_set"},
      {frame_settings_edited([](auto& s) { s.clamp = -0.5f; }), "FrameSetup.settings.clamp"},
      {frame_edited([](auto& f) { f.width = kMaxImageSide + 1; }), "FrameSetup.frame.width"},
      {frame_edited([](auto& f) { f.height = -1; }), "FrameSetup.frame.height"},
      {frame_edited([](auto& f) { f.sample_count = 0; }), "FrameSetup.frame.sample_count"},
      {frame_edited([](auto& f) { f.sample_begin = UINT32_MAX; }), "FrameSetup.frame.sample_count: 4, expected [1, 0]"},
      {frame_edited([](auto& f) { f.jitter_x = -0.01f; }), "FrameSetup.frame.jitter_x"},
      {frame_edited([](auto& f) { f.jitter_y = 1.01f; }), "FrameSetup.frame.jitter_y"},
      {frame_edited([](auto& f) { f.jitter_y = NAN; }), "FrameSetup.frame.jitter_y"},
      {frame_edited([](auto& f) { f.camera.position.y = NAN; }), "FrameSetup.frame.camera.position"},
      {frame_edited([](auto& f) { f.camera.forward = glm::vec3(0); }), "FrameSetup.frame.camera.forward"},
      {frame_edited([](auto& f) { f.camera.forward = {1e30f, 0, 0}; }), "FrameSetup.frame.camera.forward"},
      {frame_edited([](auto& f) { f.camera.forward = {1e-30f, 0, 0}; }), "FrameSetup.frame.camera.forward"},
      {frame_edited([](auto& f) { f.camera.up = glm::vec3(0); }), "FrameSetup.frame.camera.up"},
      {frame_edited([](auto& f) { f.camera.up = -3.0f * f.camera.forward; }), "FrameSetup.frame.camera.up: parallel"},
      {frame_edited([](auto& f) { f.camera.vfov = 0; }), "FrameSetup.frame.camera.vfov"},
      {frame_edited([](auto& f) { f.camera.vfov = std::numbers::pi_v<float>; }), "FrameSetup.frame.camera.vfov"},
      {edited<TileJobMsg>([](TileJobMsg& m) { m.tile.w = 0; }), "TileJob.tile.w: 0, expected [1, 1024]"},
      {edited<TileJobMsg>([](TileJobMsg& m) { m.tile.h = kMaxTileSide + 1; }), "TileJob.tile.h"},
      {edited<TileJobMsg>([](TileJobMsg& m) { m.tile.x = -1; }), "TileJob.tile.x"},
      {edited<TileJobMsg>([](TileJobMsg& m) { m.tile.y = kMaxImageSide; }), "TileJob.tile.y"},
      {edited<TileJobMsg>([](TileJobMsg& m) { m.tile.border = 65; }), "TileJob.tile.border"},
      {edited<TileJobMsg>([](TileJobMsg& m) { m.tile.border = -1; }), "TileJob.tile.border"},
      {edited<TileResult>([](TileResult& m) { m.tile.w = 1025; }), "TileResult.tile.w"},
      {edited<TileResult>([](TileResult& m) { m.render_seconds = -1; }), "TileResult.render_seconds"},
      {edited<TileResult>([](TileResult& m) { m.render_seconds = NAN; }), "TileResult.render_seconds"},
      {edited<TileResult>([](TileResult& m) { m.nonfinite_pixels = 65; }), "TileResult.nonfinite_pixels: 65, expected [0, 64]"},
      {edited<TileResult>([](TileResult& m) { m.pixel_format = PixelFormat(3); }), "TileResult.pixel_format: 3"},
      {edited<Welcome>([](Welcome& m) { m.timeout_ms = 49; }), "Welcome.timeout_ms: 49, expected [50, 3600000]"},
      {edited<Welcome>([](Welcome& m) { m.timeout_ms = 3600001; }), "Welcome.timeout_ms"},
      {edited<Welcome>([](Welcome& m) { m.pixel_format = PixelFormat(7); }), "Welcome.pixel_format: 7, expected [0, 2]"},
      {edited<Welcome>([](Welcome& m) { m.pixel_codec = PixelCodec(3); }), "Welcome.pixel_codec: 3, expected [0, 2]"},
      {edited<Bye>([](Bye& m) { m.kind = ByeKind(3); }), "Bye.kind: 3, expected [0, 2]"},
  };
  for (const Case& c : cases) {
    DecodeResult d = decode_copy(encode(c.message));
    EXPECT_FALSE(d.message) << c.error_starts;
    EXPECT_EQ(d.error.rfind(c.error_starts, 0), 0u)
        << "got \"" << d.error << "\", expected \"" << c.error_starts << "...\"";
  }
}

TEST(Protocol, LimitsThemselvesAreAccepted) {
  std::vector<Message> edges = {
      edited<Hello>([](Hello& m) { m.threads = 4096; m.build_id.assign(kMaxString, 'b'); }),
      edited<Welcome>([](Welcome& m) { m.credits = 64; m.heartbeat_ms = 10; m.scene_name = "a.b"; }),
      edited<Welcome>([](Welcome& m) { m.scene_size = kMaxSceneBytes; m.settings.path_depth = 1024; m.settings.specular_depth = 0; }),
      settings_edited([](auto& s) { s.filter_normal_cos = -1; s.clamp = 0; }),
      settings_edited([](auto& s) { s.aa_samples = 64; s.paths_per_set = 64; s.glossy_threshold = 1; s.glossy_rays = 64; }),
      settings_edited([](auto& s) {
        s.importance_paths = 1 << 20;
        s.importance_floor = 1;
        s.bidir_vpls = 1 << 16;
        s.bidir_camera_paths = 4096;
        s.paths_per_set = 4096;
      }),
      settings_edited([](auto& s) { s.importance_floor = 0; s.bidir_vpls = 9; s.bidir_camera_paths = 0; }),
      settings_edited([](auto& s) {
        s.method = MethodKind::Lightcuts;
        s.caustics = false;  // caustics are ir and igi's
        s.importance_paths = s.bidir_vpls = 0;
        s.lightcuts_max_cut = 1 << 20;
        s.lightcuts_spacing = 64;
        s.lightcuts_samples = 1;
      }),
      settings_edited([](auto& s) { s.lightcuts_samples = 64; s.lightcuts_spacing = 0; s.lightcuts_error = 0.999f; }),
      settings_edited([](auto& s) { s.glass_branches = 1; s.caustic_photons = 1; s.caustic_radius = 1e-5f; }),
      settings_edited([](auto& s) { s.glass_branches = 8; s.caustic_photons = 1 << 26; s.caustic_radius = 0.25f; s.caustics = false; }),
      frame_edited([](auto& f) { f.jitter_x = 0; f.jitter_y = 1; }),
      frame_edited([](auto& f) { f.width = kMaxImageSide; f.height = 1; }),
      edited<TileJobMsg>([](TileJobMsg& m) { m.tile = {kMaxImageSide - 1, 0, kMaxTileSide, 1, 64}; }),
      edited<TileResult>([](TileResult& m) { m.tile = {0, 0, 1, 1, 0}; m.pixels.resize(1); m.surfaces.resize(1); m.nonfinite_pixels = 1; }),
      edited<Welcome>([](Welcome& m) { m.timeout_ms = kMinTimeoutMs; }),
      edited<Welcome>([](Welcome& m) { m.timeout_ms = kMaxTimeoutMs; m.pixel_format = PixelFormat::Float32; }),
  };
  for (const Message& m : edges) {
    DecodeResult d = decode_copy(encode(m));
    ASSERT_TRUE(d.message) << d.error;
    EXPECT_TRUE(same(*d.message, m));
  }
}

// Raw byte patches the encoder cannot produce: each must fail on its length or
// value check, before anything is allocated for it.
TEST(Protocol, HugeLengthsAndBadBytesAreRejectedBeforeUse) {
  auto patched = [](const Message& m, size_t offset, std::vector<uint8_t> value) {
    std::vector<uint8_t> bytes = encode(m);
    std::copy(value.begin(), value.end(), bytes.begin() + offset);
    return decode_copy(bytes).error;
  };
  const std::vector<uint8_t> all_ones = {0xFF, 0xFF, 0xFF, 0xFF};
  EXPECT_EQ(patched(sample<Hello>(), 8, all_ones), "Hello.build_id: length 4294967295 over the limit of 4096");
  EXPECT_EQ(patched(sample<Hello>(), 8, {0, 0x10, 0, 0}), "Hello.build_id: truncated: length 4096, 55 bytes left");
  SceneData scene = sample<SceneData>();
  size_t bytes_at = 8 + 8 + 4 + scene.file_name.size();
  EXPECT_EQ(patched(scene, bytes_at, all_ones), "SceneData.bytes: length 4294967295 over the limit of 536870912");
  EXPECT_EQ(patched(scene, bytes_at, {0, 0, 0, 0x20}), "SceneData.bytes: truncated: length 536870912, 300 bytes left");
  size_t nonfinite_at = 8 + 16 + 20 + 4 + 8 + 24, pixels_at = nonfinite_at + 4 + 1 + 1;
  EXPECT_EQ(patched(sample<TileResult>(), nonfinite_at, all_ones),
            "TileResult.nonfinite_pixels: 4294967295, expected [0, 64]");
  EXPECT_EQ(patched(sample<TileResult>(), nonfinite_at + 4, {3}), "TileResult.pixel_format: 3, expected [0, 2]");
  EXPECT_EQ(patched(sample<TileResult>(), nonfinite_at + 5, {3}), "TileResult.pixel_codec: 3, expected [0, 2]");
  EXPECT_EQ(patched(sample<TileResult>(), pixels_at, all_ones),
            "TileResult.pixels: count 4294967295 over the limit of 1048576");
  EXPECT_EQ(patched(sample_half_tile_result(), pixels_at, {0, 1, 0, 0}),
            "TileResult.pixels: truncated: 256 elements of 6 bytes, 900 bytes left");  // 384 of pixels, 516 of surfaces
  Welcome welcome = sample<Welcome>();
  size_t method_at = 8 + 8 + 4 + welcome.scene_name.size() + 16 + 12;  // past the environment's 3 floats
  EXPECT_EQ(patched(welcome, method_at, {7}), "Welcome.settings.method: --method: expected pt, ir, igi or lightcuts (0..3), got 7");
  EXPECT_EQ(patched(welcome, method_at - 12, {0, 0, 0x80, 0xbf}),  // -1.0f
            "Welcome.environment: -1, expected a radiance from 0 to 1000000");
  // The map's rotation, 4 bytes before the last (the lamps' units): degrees within +-360.
  const size_t rotation_at = encode(Message{welcome}).size() - 6;  // f32 rotation, u8 light units, u8 pixel codec
  EXPECT_EQ(patched(welcome, rotation_at + 4, {2}), "Welcome.light_units: 2, expected 0 (photometric) or 1 (radiometric)");
  EXPECT_EQ(patched(welcome, rotation_at, {0, 0, 0xc8, 0x43}),  // 400.0f
            "Welcome.environment_rotation: 400, expected degrees within +-360");
  // method u8; path, light and specular depth, interleave, paths_per_set, vpl_draws, aa_samples i32;
  // glossy_threshold f32; glossy_rays i32; clamp f32; compensation_samples i32; then filter.
  EXPECT_EQ(patched(welcome, method_at + 1 + 28 + 4 + 4 + 4 + 4, {2}), "Welcome.settings.filter: boolean byte 2, expected 0 or 1");
}

// ---- Socket helpers, over loopback with bounded waits.

constexpr int kWaitMs = 5000;

struct Pair {
  zmq::context_t context;
  zmq::socket_t router{context, zmq::socket_type::router};
  zmq::socket_t dealer{context, zmq::socket_type::dealer};
  std::string endpoint;

  Pair() {
    configure(router);
    configure(dealer);
    router.bind("tcp://127.0.0.1:*");
    endpoint = router.get(zmq::sockopt::last_endpoint);
    dealer.connect(endpoint);
  }
};

TEST(ProtocolSocket, RouterAndDealerExchangeMessages) {
  Pair p;
  send(p.dealer, sample<Hello>());
  std::optional<Received> hello = receive(p.router, kWaitMs, true);
  ASSERT_TRUE(hello && hello->message) << (hello ? hello->error : "timed out");
  EXPECT_TRUE(same(*hello->message, sample<Hello>()));
  EXPECT_FALSE(hello->identity.empty());
  EXPECT_EQ(hello->bytes, encode(sample<Hello>()).size());

  for (const Message& m : {Message(sample_tile_result()), Message(sample<SceneData>())}) {
    send_to(p.router, hello->identity, m);
    std::optional<Received> back = receive(p.dealer, kWaitMs, false);
    ASSERT_TRUE(back && back->message) << (back ? back->error : "timed out");
    EXPECT_TRUE(same(*back->message, m));
    EXPECT_TRUE(back->identity.empty());
  }
}

TEST(ProtocolSocket, ReceiveTimesOutWithNullopt) {
  Pair p;
  auto start = std::chrono::steady_clock::now();
  EXPECT_FALSE(receive(p.dealer, 50, false));
  double waited = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_GE(waited, 0.04);
  EXPECT_LT(waited, 2.0);
  EXPECT_FALSE(receive(p.router, 0, true));
  EXPECT_FALSE(receive(p.router, -1, true));  // never waits forever
}

TEST(ProtocolSocket, GarbageAndStrayFramesGiveErrorsNotThrows) {
  Pair p;
  p.dealer.send(zmq::str_buffer("garbage"), zmq::send_flags::none);
  std::optional<Received> garbage;
  ASSERT_NO_THROW(garbage = receive(p.router, kWaitMs, true));
  ASSERT_TRUE(garbage);
  EXPECT_FALSE(garbage->message);
  EXPECT_NE(garbage->error.find("shorter than the 8-byte header"), std::string::npos) << garbage->error;
  EXPECT_EQ(garbage->bytes, 7u);

  p.dealer.send(zmq::buffer(encode(Heartbeat{})), zmq::send_flags::sndmore);
  p.dealer.send(zmq::str_buffer("extra"), zmq::send_flags::none);
  std::optional<Received> two = receive(p.router, kWaitMs, true);
  ASSERT_TRUE(two);
  EXPECT_FALSE(two->message);
  EXPECT_EQ(two->error, "3 frames, expected 2 ([identity, message])");

  p.router.send(zmq::buffer(garbage->identity), zmq::send_flags::sndmore);
  p.router.send(zmq::str_buffer("a"), zmq::send_flags::sndmore);
  p.router.send(zmq::str_buffer("b"), zmq::send_flags::none);
  std::optional<Received> stray = receive(p.dealer, kWaitMs, false);
  ASSERT_TRUE(stray);
  EXPECT_EQ(stray->error, "2 frames, expected 1 (one message)");

  send(p.dealer, Bye{"still fine"});  // the sockets still work
  std::optional<Received> bye = receive(p.router, kWaitMs, true);
  ASSERT_TRUE(bye && bye->message);
  EXPECT_TRUE(same(*bye->message, Bye{"still fine"}));
}

// Bytes that are not even ZMTP: zmq drops that connection, the router lives on.
TEST(ProtocolSocket, RawTcpGarbageDoesNotDisturbTheRouter) {
  Pair p;
  int port = std::stoi(p.endpoint.substr(p.endpoint.rfind(':') + 1));
  int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  ASSERT_GE(fd, 0);
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_port = htons(uint16_t(port));
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  ASSERT_EQ(::connect(fd, reinterpret_cast<sockaddr*>(&address), sizeof address), 0);
  const char junk[] = "GET / HTTP/1.0\r\n\r\n\xff\xff\xff\xff\xff\xff\xff\xff\x7f";
  EXPECT_GT(::write(fd, junk, sizeof junk), 0);
  EXPECT_FALSE(receive(p.router, 200, true));
  ::close(fd);

  send(p.dealer, Heartbeat{});
  std::optional<Received> beat = receive(p.router, kWaitMs, true);
  ASSERT_TRUE(beat && beat->message) << (beat ? beat->error : "timed out");
  EXPECT_EQ(type_of(*beat->message), MessageType::Heartbeat);
}

}  // namespace
}  // namespace igi::protocol
