#pragma once
// The display link: what igi-view and igi-master --viewer-listen say to each
// other. Not the workers' protocol (protocol/messages.h): its own magic and
// version, so that neither side takes the other's bytes, and a viewer of
// another version is told so before anything else is read.
//
//   viewer -> master  Hello                 (first; answered by Welcome or Refuse)
//                     View                  (the camera, settings and display the user has now;
//                                            on every change, stamped with the input's time)
//                     Ack                   (a frame shown: the master may send the next)
//                     Request               (M: meter the image; F12: save the master's float image)
//                     Ping                  (nothing else to say for a while)
//                     Bye                   (the window closed)
//   master -> viewer  Welcome | Refuse      (the image's size, the session's settings and camera)
//                     Frame                 (display pixels, tone-mapped at the View's exposure)
//                     Reply                 (what a Request did)
//                     Ping | Bye            (alive; the master is going)
//
// The master sends a Frame only while fewer than kFramesInFlight are
// unacknowledged, and always the newest image: a viewer that falls behind
// gets fewer frames, never a queue. The format is the workers' (header
// u32 magic, u16 version, u8 type, u8 flags 0; fields little-endian,
// protocol/wire.h), so decode() checks every length and value before use
// and never throws on bad bytes.
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <variant>
#include <vector>

#include "core/settings.h"
#include "image/view_transform.h"
#include "scene/camera.h"

namespace igi::display {

inline constexpr uint32_t kMagic = 0x56494749;  // "IGIV" read little-endian
// 1: the first display link (issue 62).
inline constexpr uint16_t kVersion = 1;
inline constexpr size_t kMaxText = 4096;
inline constexpr int kMaxSide = 8192;
inline constexpr size_t kMaxLevels = 16;
inline constexpr int kFramesInFlight = 2;
// The most either side sends: a frame's pixels, unpacked or not, and room for its fields.
inline constexpr size_t kMaxMessageBytes = size_t(kMaxSide) * kMaxSide * 3 + 65536;

enum class Type : uint8_t { Hello = 1, Welcome, Refuse, View, Ack, Request, Reply, Frame, Ping, Bye };
inline constexpr int kTypes = 10;

struct Hello {
  std::string program;  // "igi-view 1" (for the master's log)
};

struct Welcome {
  std::string scene;  // the master's --scene, for the title
  int32_t width = 0, height = 0;  // the image
  RenderSettings settings;  // the session's at the start
  Camera camera;            // the scene's (or --camera-file's)
  float speed = 1.0f;       // the camera's walking speed, scene units a second
  ToneMapping tone;         // --exposure and --view
  bool metering = true;     // the exposure is metered from the first frames (--exposure auto)
  std::vector<std::string> preview_levels;  // "budget" first, then the levels' names (the panel's choice)
};

struct Refuse {
  std::string reason;
};

struct View {
  Camera camera;
  RenderSettings settings;
  uint64_t camera_generation = 0, settings_generation = 0;  // the viewer's: bumped by each change
  glm::vec3 light_offset{0.0f};
  int32_t preview = -1;  // -1: the frame budget picks the level, else this level every frame
  ToneMapping tone;
  bool metering = false;  // meter each frame's exposure until a full frame (the opening meter)
  uint64_t stamp_us = 0;  // the viewer's clock when the input behind this view came
};

struct Ack {
  uint64_t frame = 0;  // the sequence number of the frame shown
};

enum class RequestKind : uint8_t { Meter = 1, SaveImage = 2 };
struct Request {
  RequestKind kind = RequestKind::Meter;
};

struct Reply {
  std::string text;     // shown on the viewer's screen and terminal
  float exposure = 0.0f;  // > 0: the metered exposure (Meter)
  std::vector<uint8_t> exr;  // SaveImage: the master's float image as an OpenEXR file, for the viewer to keep
};

// Zstd: 8-bit sRGB, three bytes a pixel, zstd (lossless): unpack_pixels().
// H264: one access unit of the connection's H.264 stream (video_codec.h): lossy, decoded in order.
enum class FrameCodec : uint8_t { Zstd = 1, H264 = 2 };
struct Frame {
  uint64_t sequence = 0;             // counts up from 1; Ack names it
  uint64_t stamp_us = 0;             // the stamp of the View whose camera this frame shows
  uint64_t settings_generation = 0;  // the viewer's, of the settings it was rendered with
  int32_t width = 0, height = 0;
  FrameCodec codec = FrameCodec::Zstd;
  bool full = false;         // a full frame (not a preview of a moving view)
  float metered = 0.0f;      // > 0: the exposure it was tone-mapped at, metered (View.metering)
  float accumulated = 0.0f;  // frames behind the image
  float seconds = 0.0f;      // the last frame's render time (the panel's read-out and graph)
  std::string level;         // its level's name ("full", "preview 1/4")
  std::string status;        // the master's status line ("12.3 fps  full  38 ms/frame ...")
  std::vector<uint8_t> pixels;  // in `codec`
};

struct Ping {};

struct Bye {
  std::string reason;
};

using Message = std::variant<Hello, Welcome, Refuse, View, Ack, Request, Reply, Frame, Ping, Bye>;

const char* type_name(Type type);
Type type_of(const Message& message);

std::vector<uint8_t> encode(const Message& message);

struct Decoded {
  std::optional<Message> message;
  std::string error;  // empty on success; otherwise names the message and field
};
// Never throws on bad bytes and never reads past them. A peer of another
// display version gets "display link version N, this build speaks M".
Decoded decode(std::span<const uint8_t> bytes);

// A Zstd frame's pixels: 8-bit sRGB (three bytes a pixel, row 0 at the top)
// packed with zstd, and unpacked to exactly width * height * 3 bytes or refused
// (nullopt, `error` set; an H264 frame too: video_codec.h decodes those).
std::vector<uint8_t> pack_pixels(std::span<const uint8_t> rgb);
std::optional<std::vector<uint8_t>> unpack_pixels(const Frame& frame, std::string& error);

}  // namespace igi::display
