#pragma once
// The wire format between igi-master and igi-worker, as plain data.
//
// Every message is one ZeroMQ frame: an 8-byte header (magic "IGI1", protocol
// version, type, flags = 0) and a payload, all little-endian. encode() and
// decode() in codec.h are written side by side; decode() validates every
// length, count, enum and number before use and never trusts the peer.
//
// Conversation:
//   worker -> master  Hello                  (version, build, threads, libraries)
//   master -> worker  Welcome | Refuse       (scene by content hash, settings)
//   worker -> master  SceneRequest           (only when it has no file with that hash)
//   master -> worker  SceneData
//   master -> worker  FrameSetup, TileJob... (jobs up to the worker's credits)
//   worker -> master  TileResult...          (one per job; returns a credit)
//   master -> worker  CancelFrame            (the view left the frame behind: the
//                                             worker drops its queued jobs of it)
//   both ways         Heartbeat              (every heartbeat interval)
//   either way        Bye                    (leaving; the peer forgets the other)
#include <cstdint>
#include <string>
#include <variant>
#include <vector>

#include <glm/glm.hpp>

#include "core/frame.h"
#include "core/settings.h"
#include "image/frame_buffer.h"
#include "scene/light_units.h"

namespace igi::protocol {

inline constexpr uint32_t kMagic = 0x31494749;  // "IGI1" read little-endian
// 2: RenderSettings carries compensation_samples. 3: Welcome carries the master's timeout and
// the pixel format; TileResult its pixel format and count of non-finite pixels the worker zeroed;
// Bye says why (leaving, quarantined, failed). 4: settings split path lengths, anti-aliasing,
// glossy gather, lightcuts. 5: glass branches, caustic photons. 6: settings
// carry light importance and bidirectional IR. 7: FrameSetup carries the
// frame's settings (the window changes them live). 8: FrameSetup carries the
// scene's pose (animation time, moved lights). 9: settings.clamp is a fraction of the
// scene's mean chord, at most kMaxClamp; FrameSetup.sample_begin is the ir/igi/lightcuts
// pass the clamp relaxes with (core/clamp.h). 10: settings carry the wavelet
// filter's levels. 11: Welcome carries the scene's environment (a constant sky, or a map
// that workers ask for by hash as they ask for the scene). 12: settings carry vpl_draws.
// 13: settings carry lightcuts_block. 14: FrameSetup carries want_surfaces and
// TileResult its pixels' surfaces (the window's reprojection); CancelFrame. 15: Hello
// carries the runtime libraries. 16: Welcome carries the units the scene's lamps are read in.
// 17: Welcome and TileResult carry the pixel block's codec (raw or zstd). 18: pixels
// as rgb9e5 (a shared exponent, 4 bytes); the codec packs the surfaces too; lz4.
// 19: settings carry light_guide. 20: settings carry light_divisor (sharp previews).
inline constexpr uint16_t kVersion = 20;

// Size limits, checked before anything is allocated.
inline constexpr size_t kMaxString = 4096;
inline constexpr size_t kMaxSceneBytes = 512u << 20;
inline constexpr int kMaxImageSide = 16384;
inline constexpr int kMaxTileSide = 1024;
inline constexpr size_t kMaxMessageBytes = kMaxSceneBytes + 65536;
inline constexpr double kMaxSceneTime = 1e9;  // seconds
inline constexpr double kMaxEnvironment = 1e6;  // a sky's radiance, per channel (--environment)
// Welcome's liveness and flow control: the decoder refuses a Welcome outside
// these, and the master's command line refuses the options that would fill
// them in (master/options/liveness_options.h, --credits), so both say the same.
inline constexpr uint32_t kMinTimeoutMs = 50, kMaxTimeoutMs = 3600000;
inline constexpr uint32_t kMinHeartbeatMs = 10, kMaxHeartbeatMs = 60000;
inline constexpr uint32_t kMaxCredits = 64;  // jobs a worker holds at once

enum class MessageType : uint8_t {
  Hello = 1,
  Welcome = 2,
  Refuse = 3,
  SceneRequest = 4,
  SceneData = 5,
  FrameSetup = 6,
  TileJob = 7,
  TileResult = 8,
  Heartbeat = 9,
  Bye = 10,
  CancelFrame = 11,
};

const char* message_name(MessageType type);

struct Hello {
  std::string build_id;   // must equal the master's: same binary, same floats
  std::string simd;       // unread: workers send "native" (the build id names the compiler and Embree's ISA);
                          // kept so that the wire stays as it is until a version changes it anyway
  uint32_t threads = 1;
  std::string libraries;  // scene/libraries.h: "glibc 2.36, Embree 3.13.5"; named when VPL sets differ
};

// How a TileResult's pixel block (and its surfaces, when it has them) travel:
// as they are, or packed losslessly (the decoder gets the very bytes back),
// each block one zstd frame (level 1) or one lz4 block. Rendered display
// frames: zstd takes the fewest bytes, lz4 about 1.6 times as many and the
// master a third of zstd's time to unpack them (tests/bench/RESULTS.md,
// "Pixels on the wire").
enum class PixelCodec : uint8_t { Raw = 0, Zstd = 1, Lz4 = 2 };
const char* pixel_codec_name(PixelCodec codec);

struct Welcome {
  uint64_t session = 0;
  std::string scene_name;   // built-in scene name, or the file's name (no directories)
  uint64_t scene_hash = 0;  // XXH3-64 of the file's bytes (scene/scene_file.h); 0 for built-in scenes
  uint64_t scene_size = 0;  // bytes of the file; 0 for built-in scenes
  // The sky the master's scene stands under (its own, or --environment's):
  // the worker's copy takes it, whatever the file says. Zero: none.
  glm::vec3 environment{0.0f};
  RenderSettings settings;
  uint32_t credits = 2;         // jobs the worker may hold at once
  uint32_t heartbeat_ms = 500;  // both sides send at least this often
  // The master declares a worker dead after this much silence; the worker
  // waits longer than this for the master (so the master always gives up first).
  uint32_t timeout_ms = 1500;
  PixelFormat pixel_format = PixelFormat::Float32;  // how TileResults carry pixels
  // With an environment map (scene/environment_map.h): the sky is the map
  // times `environment`. A worker without the file asks for it by hash
  // (SceneRequest), as for the scene. Empty name: a constant sky.
  std::string environment_map;  // the file's name (no directories)
  uint64_t environment_map_hash = 0, environment_map_size = 0;
  float environment_rotation = 0.0f;  // degrees about +y
  // How the glTF file's lamps are read (--light-units): the master's choice,
  // so that every copy of the scene is lit alike.
  LightUnits light_units = LightUnits::Photometric;
  PixelCodec pixel_codec = PixelCodec::Raw;  // how TileResults pack their pixel and surface blocks
};

struct Refuse {
  std::string reason;
};

struct SceneRequest {
  uint64_t scene_hash = 0;  // the scene's, or the environment map's
};

struct SceneData {
  uint64_t scene_hash = 0;
  std::string file_name;
  std::vector<uint8_t> bytes;
};

// A frame is rendered with its own settings (Welcome's are the session's
// first): the window changes them between frames, no reconnect, no new BVH.
struct FrameSetupMsg {
  igi::FrameSetup frame;
  RenderSettings settings;
};

struct TileJobMsg {
  uint64_t frame_id = 0;
  uint64_t job_id = 0;  // unique within the session; results carry it back
  igi::TileJob tile;
};

struct TileResult {
  uint64_t frame_id = 0;
  uint64_t job_id = 0;
  igi::TileJob tile;
  float render_seconds = 0.0f;
  uint64_t frame_state_hash = 0;  // the worker's VPL-set hash for this frame
  igi::RayCounts rays;
  uint32_t nonfinite_pixels = 0;  // pixels the method left NaN or infinite, sent as 0 (at most w * h)
  PixelFormat pixel_format = PixelFormat::Float32;  // on the wire; `pixels` holds floats either way
  // tile.w * tile.h, row-major, linear RGB, finite; as Float16 each is a half
  // value (encode() rounds to nearest even; protocol::wire_pixels prepares them),
  // as Rgb9e5 a shared-exponent colour (encode() rounds, image/rgb9e5.h).
  std::vector<glm::vec3> pixels;
  // None, or tile.w * tile.h as the pixels (when the frame wants them): depth
  // finite and >= 0, flags only PixelSurface::kViewDependent. 8 bytes each.
  std::vector<PixelSurface> surfaces;
  PixelCodec pixel_codec = PixelCodec::Raw;  // the pixel and surface blocks on the wire (a master accepts either)
};

struct Heartbeat {};

enum class ByeKind : uint8_t {
  Leaving = 0,      // done: the session ended, or the worker stops
  Quarantined = 1,  // master -> worker: your VPL sets differ from the frame's reference (the master's own,
                    // or a vote's), or your results keep failing validation; no more work (exit 5)
  Failed = 2,       // worker -> master: cannot go on (e.g. the scene does not load)
};

struct Bye {
  std::string reason;
  ByeKind kind = ByeKind::Leaving;
};

// The view left the frame behind (the window's camera moved on): its jobs
// still queued are dropped; tiles already rendering are sent as usual and
// the master ignores them.
struct CancelFrame {
  uint64_t frame_id = 0;
};

using Message = std::variant<Hello, Welcome, Refuse, SceneRequest, SceneData, FrameSetupMsg, TileJobMsg,
                             TileResult, Heartbeat, Bye, CancelFrame>;

MessageType type_of(const Message& message);

}  // namespace igi::protocol
