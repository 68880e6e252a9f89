#pragma once
// Moving frames on the display link as H.264 (FFmpeg's libavcodec with
// libx264, Debian's): the master encodes each 8-bit display frame while the
// view moves, the viewer decodes them in order. Low-latency settings: x264's
// ultrafast preset and zerolatency tune (no B-frames, no look-ahead, one
// frame in, one packet out), a bit rate capped by --viewer-mbit with a VBV
// buffer of one frame, so a frame's size follows the link. Once the view is
// still the master sends lossless frames instead (display_messages.h).
//
// One encoder per viewer connection: a new viewer starts at a key frame. The
// decoder keeps the stream's state: every H.264 frame must reach it, in order
// (the link is TCP; frames the viewer does not show are decoded all the same).
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace igi {

// Whether this build's libavcodec has an H.264 encoder (libx264).
bool have_h264_encoder();

class VideoEncoder {
 public:
  // Even width and height. Throws std::runtime_error when libx264 cannot be opened.
  VideoEncoder(int width, int height, double mbit_per_second, double frames_per_second);
  ~VideoEncoder();
  VideoEncoder(const VideoEncoder&) = delete;
  VideoEncoder& operator=(const VideoEncoder&) = delete;
  // 8-bit sRGB, three bytes a pixel, row 0 at the top: one H.264 access unit (Annex B).
  std::vector<uint8_t> encode(std::span<const uint8_t> rgb);
  // From the next frame on (x264 reconfigures the stream; no new key frame). 0: no cap.
  void set_bit_rate(double mbit_per_second);
  double bit_rate() const;  // Mbit/s

 private:
  struct State;
  std::unique_ptr<State> state_;
};

class VideoDecoder {
 public:
  VideoDecoder();
  ~VideoDecoder();
  VideoDecoder(const VideoDecoder&) = delete;
  VideoDecoder& operator=(const VideoDecoder&) = delete;
  // One access unit to width x height 8-bit sRGB pixels; nullopt with `error`
  // set when the bytes do not decode to a frame of that size.
  std::optional<std::vector<uint8_t>> decode(std::span<const uint8_t> packet, int width, int height,
                                            std::string& error);

 private:
  struct State;
  std::unique_ptr<State> state_;
};

}  // namespace igi
