// The display link's moving frames (master/viewer/video_codec.h): H.264
// through libavcodec comes back close to what went in, within the bit rate
// asked for, one packet per frame, and follows a new rate mid-stream; bytes
// that are not the stream are refused. The link's measure (link_meter.h).
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "viewer/link_meter.h"
#include "viewer/video_codec.h"

namespace igi {
namespace {

constexpr int kW = 160, kH = 120;

// A smooth gradient with a moving bright square: what a turning camera shows, roughly.
std::vector<uint8_t> picture(int t) {
  std::vector<uint8_t> rgb(size_t(kW) * kH * 3);
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      uint8_t* p = &rgb[(size_t(y) * kW + x) * 3];
      const bool square = std::abs(x - 40 - 4 * t) < 12 && std::abs(y - 60) < 12;
      p[0] = square ? 250 : uint8_t(x * 255 / kW);
      p[1] = square ? 240 : uint8_t(y * 255 / kH);
      p[2] = 90;
    }
  return rgb;
}

double mean_abs_difference(const std::vector<uint8_t>& a, const std::vector<uint8_t>& b) {
  double sum = 0.0;
  for (size_t i = 0; i < a.size(); ++i) sum += std::abs(int(a[i]) - int(b[i]));
  return sum / double(a.size());
}

TEST(VideoCodec, FramesComeBackCloseWithinTheBitRate) {
  if (!have_h264_encoder()) GTEST_SKIP() << "no libx264 in this libavcodec";
  const double mbit = 2.0, fps = 25.0;
  VideoEncoder encoder(kW, kH, mbit, fps);
  VideoDecoder decoder;
  size_t bytes = 0;
  for (int t = 0; t < 20; ++t) {
    const std::vector<uint8_t> in = picture(t);
    const std::vector<uint8_t> packet = encoder.encode(in);
    ASSERT_FALSE(packet.empty()) << "frame " << t << ": no packet (a frame held back adds a frame of delay)";
    bytes += packet.size();
    std::string error;
    const std::optional<std::vector<uint8_t>> out = decoder.decode(packet, kW, kH, error);
    ASSERT_TRUE(out) << "frame " << t << ": " << error;
    EXPECT_LT(mean_abs_difference(in, *out), 6.0) << "frame " << t;  // of 255: chroma subsampling and quantisation
  }
  // The first frame is a key frame; over 20 frames the stream stays near the rate (x264's VBV, one frame's buffer).
  EXPECT_LT(double(bytes) * 8.0 / (20.0 / fps), 2.0 * mbit * 1e6);
}

TEST(VideoCodec, BytesThatAreNotTheStreamAreRefused) {
  if (!have_h264_encoder()) GTEST_SKIP() << "no libx264 in this libavcodec";
  VideoDecoder decoder;
  std::string error;
  const std::vector<uint8_t> garbage(500, 0x5a);
  EXPECT_FALSE(decoder.decode(garbage, kW, kH, error));
  EXPECT_NE(error.find("Frame.pixels: H.264"), std::string::npos) << error;
  // A good frame of another size than the Frame message says.
  VideoEncoder encoder(kW, kH, 2.0, 25.0);
  VideoDecoder fresh;
  EXPECT_FALSE(fresh.decode(encoder.encode(picture(0)), kW * 2, kH, error));
  EXPECT_NE(error.find("expected 320 x 120"), std::string::npos) << error;
}

// A lower bit rate set mid-stream (what the measured link asks for) makes the
// next frames smaller, without a new key frame the decoder would need.
TEST(VideoCodec, ALowerBitRateMidStreamShrinksTheFrames) {
  if (!have_h264_encoder()) GTEST_SKIP() << "no libx264 in this libavcodec";
  VideoEncoder encoder(kW, kH, 8.0, 25.0);
  VideoDecoder decoder;
  std::string error;
  size_t high = 0, low = 0;
  std::mt19937 noise(62);
  for (int t = 0; t < 40; ++t) {
    if (t == 20) encoder.set_bit_rate(0.5);
    std::vector<uint8_t> in(size_t(kW) * kH * 3);  // noise, new each frame: more bits than either rate allows
    for (uint8_t& v : in) v = uint8_t(noise() >> 24);
    const std::vector<uint8_t> packet = encoder.encode(in);
    ASSERT_TRUE(decoder.decode(packet, kW, kH, error)) << "frame " << t << ": " << error;
    if (t >= 5 && t < 20) high += packet.size();
    if (t >= 25) low += packet.size();
  }
  EXPECT_NEAR(encoder.bit_rate(), 0.5, 1e-9);
  EXPECT_LT(double(low), 0.5 * double(high)) << "15 frames at 8 Mbit/s: " << high << " bytes, at 0.5: " << low;
}

TEST(LinkMeter, FollowsTheFramesItTimesAndCapsTheBudget) {
  LinkMeter link;
  EXPECT_EQ(link.budget(20.0, 0.7), 20.0) << "the cap before any sample";
  link.add(1000, 0.001);  // too small to say anything about the link
  EXPECT_EQ(link.mbit(), 0.0);
  link.add(250000, 0.2);  // 10 Mbit/s
  EXPECT_NEAR(link.mbit(), 10.0, 1e-9);
  EXPECT_NEAR(link.budget(20.0, 0.7), 7.0, 1e-9);
  link.add(50000, 0.0);  // a burst the link let through at once: averaged over the window, not 'infinite'
  EXPECT_NEAR(link.mbit(), 12.0, 1e-9);
  for (int n = 0; n < 8; ++n) link.add(250000, 0.05);  // then 40 Mbit/s: the window forgets the old rate
  EXPECT_NEAR(link.mbit(), 40.0, 1e-9);
  EXPECT_EQ(link.budget(20.0, 0.7), 20.0) << "never above --viewer-mbit";
}

}  // namespace
}  // namespace igi
