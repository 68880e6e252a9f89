// The display link's messages (master/viewer/display_messages.h): every
// message round-trips field by field, and bytes that are not a valid message
// (cut short, of another version, out of range, a worker's) are refused with
// an error that names the field. Cut-short seeds: tests/fuzz/replay_test.cpp.
#include <cstring>

#include <gtest/gtest.h>

#include "protocol/codec.h"
#include "viewer/display_messages.h"

namespace igi::display {
namespace {

template <typename M>
M round_trip(const M& m) {
  const std::vector<uint8_t> bytes = encode(m);
  Decoded d = decode(bytes);
  EXPECT_TRUE(d.message) << d.error;
  EXPECT_TRUE(d.error.empty());
  if (!d.message || !std::holds_alternative<M>(*d.message)) return M{};
  EXPECT_EQ(encode(*d.message), bytes);
  return std::get<M>(*d.message);
}

Camera a_camera() { return {{1.0f, 2.0f, 3.0f}, {0.0f, 0.0f, -1.0f}, {0.0f, 1.0f, 0.0f}, 0.5f}; }

RenderSettings some_settings() {
  RenderSettings s;
  s.method = MethodKind::InstantRadiosity;
  s.path_depth = 3;
  s.clamp = 0.25f;
  return s;
}

TEST(DisplayMessages, WelcomeAndViewRoundTripEveryField) {
  Welcome w{"cornell", 640, 480, some_settings(), a_camera(), 2.5f, {3.0f, ViewTransform::Agx}, false,
            {"full", "preview 1/2"}};
  const Welcome w2 = round_trip(w);
  EXPECT_EQ(w2.scene, "cornell");
  EXPECT_EQ(w2.width, 640);
  EXPECT_EQ(w2.height, 480);
  EXPECT_EQ(w2.settings.method, MethodKind::InstantRadiosity);
  EXPECT_EQ(w2.settings.path_depth, 3);
  EXPECT_EQ(w2.settings.clamp, 0.25f);
  EXPECT_EQ(w2.camera.position, glm::vec3(1, 2, 3));
  EXPECT_EQ(w2.camera.vfov, 0.5f);
  EXPECT_EQ(w2.speed, 2.5f);
  EXPECT_EQ(w2.tone.exposure, 3.0f);
  EXPECT_EQ(w2.tone.view, ViewTransform::Agx);
  EXPECT_FALSE(w2.metering);
  EXPECT_EQ(w2.preview_levels, (std::vector<std::string>{"full", "preview 1/2"}));

  const View v{a_camera(), some_settings(), 7, 9, {0.5f, 0.0f, -1.0f}, 2, {0.5f, ViewTransform::Neutral}, true,
               123456789};
  const View v2 = round_trip(v);
  EXPECT_EQ(v2.camera.forward, glm::vec3(0, 0, -1));
  EXPECT_EQ(v2.settings.path_depth, 3);
  EXPECT_EQ(v2.camera_generation, 7u);
  EXPECT_EQ(v2.settings_generation, 9u);
  EXPECT_EQ(v2.light_offset, glm::vec3(0.5f, 0.0f, -1.0f));
  EXPECT_EQ(v2.preview, 2);
  EXPECT_EQ(v2.tone.view, ViewTransform::Neutral);
  EXPECT_TRUE(v2.metering);
  EXPECT_EQ(v2.stamp_us, 123456789u);
}

TEST(DisplayMessages, TheSmallMessagesRoundTrip) {
  EXPECT_EQ(round_trip(Hello{"igi-view 1"}).program, "igi-view 1");
  EXPECT_EQ(round_trip(Refuse{"no"}).reason, "no");
  EXPECT_EQ(round_trip(Ack{42}).frame, 42u);
  EXPECT_EQ(round_trip(Request{RequestKind::SaveImage}).kind, RequestKind::SaveImage);
  const Reply r = round_trip(Reply{"metered", 1.5f, {'v', '/', '1', 1}});
  EXPECT_EQ(r.text, "metered");
  EXPECT_EQ(r.exposure, 1.5f);
  EXPECT_EQ(r.exr, (std::vector<uint8_t>{'v', '/', '1', 1}));
  round_trip(Ping{});
  EXPECT_EQ(round_trip(Bye{"closed"}).reason, "closed");
}

TEST(DisplayMessages, AFrameRoundTripsAndItsPixelsUnpackExactly) {
  std::vector<uint8_t> rgb(5 * 3 * 3);
  for (size_t i = 0; i < rgb.size(); ++i) rgb[i] = uint8_t(i * 7);
  Frame f{9, 1234, 2, 5, 3, FrameCodec::Zstd, true, 2.0f, 16.0f, 0.04f, "preview 1/2", "12 fps", pack_pixels(rgb)};
  const Frame f2 = round_trip(f);
  EXPECT_EQ(f2.sequence, 9u);
  EXPECT_EQ(f2.stamp_us, 1234u);
  EXPECT_EQ(f2.settings_generation, 2u);
  EXPECT_TRUE(f2.full);
  EXPECT_EQ(f2.metered, 2.0f);
  EXPECT_EQ(f2.accumulated, 16.0f);
  EXPECT_EQ(f2.seconds, 0.04f);
  EXPECT_EQ(f2.level, "preview 1/2");
  EXPECT_EQ(f2.status, "12 fps");
  std::string error;
  EXPECT_EQ(unpack_pixels(f2, error), std::optional(rgb)) << error;
  // Pixels of another size, or not zstd at all, are refused naming what was expected.
  Frame wrong = f2;
  wrong.width = 4;
  EXPECT_FALSE(unpack_pixels(wrong, error));
  EXPECT_NE(error.find("expected 36"), std::string::npos) << error;
  wrong = f2;
  wrong.pixels = {1, 2, 3, 4, 5, 6, 7, 8};
  EXPECT_FALSE(unpack_pixels(wrong, error));
  EXPECT_NE(error.find("Frame.pixels"), std::string::npos) << error;
}

std::string error_of(const std::vector<uint8_t>& bytes) {
  const Decoded d = decode(bytes);
  EXPECT_FALSE(d.message);
  return d.error;
}

TEST(DisplayMessages, BadHeadersAreRefusedSayingWhy) {
  std::vector<uint8_t> bytes = encode(Ack{1});
  std::vector<uint8_t> other = bytes;
  other[4] = uint8_t(kVersion + 1);
  EXPECT_NE(error_of(other).find("display link version " + std::to_string(kVersion + 1)), std::string::npos);
  other = bytes;
  other[6] = 77;
  EXPECT_NE(error_of(other).find("unknown display message type 77"), std::string::npos);
  other = bytes;
  other[7] = 1;
  EXPECT_NE(error_of(other).find("flags"), std::string::npos);
  other = bytes;
  other.push_back(0);
  EXPECT_NE(error_of(other).find("trailing"), std::string::npos);
  // A worker's message on the viewer port, and a viewer's on the workers' port.
  EXPECT_NE(error_of(protocol::encode(protocol::Heartbeat{})).find("bad magic"), std::string::npos);
  EXPECT_FALSE(protocol::decode(bytes).message);
}

TEST(DisplayMessages, ValuesOutOfRangeAreRefusedNamingTheField) {
  View v{a_camera(), some_settings(), 0, 0, {}, -1, {}, false, 0};
  v.camera.forward = glm::vec3(0.0f);
  EXPECT_NE(error_of(encode(v)).find("View.camera.forward"), std::string::npos);
  v.camera = a_camera();
  v.tone.exposure = std::nanf("");
  EXPECT_NE(error_of(encode(v)).find("View.tone.exposure"), std::string::npos);
  v.tone.exposure = 1.0f;
  v.settings.path_depth = -4;
  EXPECT_NE(error_of(encode(v)).find("View.settings"), std::string::npos);
  v.settings = some_settings();
  v.preview = 99;
  EXPECT_NE(error_of(encode(v)).find("View.preview"), std::string::npos);
  Frame f{1, 0, 0, 0, 10, FrameCodec::Zstd, false, 0.0f, 0.0f, 0.0f, "", "", {}};
  EXPECT_NE(error_of(encode(f)).find("Frame.width"), std::string::npos);
  f.width = 10;
  f.seconds = -1.0f;
  EXPECT_NE(error_of(encode(f)).find("Frame.seconds"), std::string::npos);
  f.seconds = 0.0f;
  f.codec = FrameCodec(9);
  EXPECT_NE(error_of(encode(f)).find("Frame.codec"), std::string::npos);
  std::vector<uint8_t> request = encode(Request{});
  request.back() = 3;
  EXPECT_NE(error_of(request).find("Request.kind"), std::string::npos);
}

}  // namespace
}  // namespace igi::display
