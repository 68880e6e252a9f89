#pragma once
// Pre-rendered tiles for simulated workers. The encoded TileResult of each
// tile rectangle is made once per pixel format and codec; an answer is a copy
// with the frame id, job id and VPL-set hash written in. The pixels are a
// pure function of their image coordinates: a gradient (expected_pixel, exact
// in half and float) or a rendered picture's (real pixels, for measuring what
// a codec saves), so a test can check every pixel of the master's frames
// (sent_pixel: what arrives after the format's rounding).
#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <tuple>
#include <vector>

#include <glm/glm.hpp>
#include <zmq.hpp>

#include "core/frame.h"
#include "core/settings.h"
#include "image/frame_buffer.h"
#include "image/image.h"
#include "protocol/messages.h"
#include "render/scene_state.h"

namespace igi::loadgen {

glm::vec3 expected_pixel(int x, int y);

class TileCache {
 public:
  TileCache() = default;
  // The tiles' pixels are the picture's; a frame must not be larger.
  explicit TileCache(Image picture) : picture_(std::move(picture)) {}

  // The pixel at (x, y) as a simulated worker renders it, and as the master
  // gets it in `format` (rounded as encode() rounds).
  glm::vec3 pixel(int x, int y) const;
  glm::vec3 sent_pixel(int x, int y, PixelFormat format) const;

  // Thread-safe; the bytes stay valid while the cache lives.
  const std::vector<uint8_t>& encoded(const TileJob& tile, PixelFormat format, protocol::PixelCodec codec);

  // An answer to (frame, job) from `encoded`; `claimed` is the rectangle it
  // says it covers (the job's own, or another one for a faulty worker).
  static zmq::message_t answer(const std::vector<uint8_t>& encoded, uint64_t frame_id, uint64_t job_id,
                               uint64_t frame_state_hash, const TileJob& claimed);
  // Makes the answer's first pixel NaN (its format's encoding). Raw half or
  // float pixels only: a shared-exponent word has no NaN, and a zstd block
  // would no longer unpack.
  static void poison(zmq::message_t& answer, PixelFormat format);
  static bool can_poison(PixelFormat format, protocol::PixelCodec codec);

  // A decompression bomb: an encoded TileResult of kBombSide x kBombSide
  // black float pixels and surfaces packed by zstd (under 1 KB; thread-safe,
  // made once). answer() gives it a frame, job and hash.
  static constexpr int kBombSide = 1024;
  const std::vector<uint8_t>& bomb();

  // The VPL-set hash a correct worker of the built-in Cornell box reports for
  // this frame (the master computes the same one: master/trust/master_renderer.h);
  // thread-safe, computed once per frame setup.
  uint64_t frame_hash(const FrameSetup& frame, const RenderSettings& settings);

 private:
  using Key = std::tuple<int, int, int, int, int, int, int>;
  std::optional<Image> picture_;
  std::mutex mutex_;
  std::map<Key, std::unique_ptr<std::vector<uint8_t>>> tiles_;
  std::vector<uint8_t> bomb_;  // under mutex_
  std::mutex hash_mutex_;
  std::unique_ptr<SceneState> scene_;    // the Cornell box, built on first use
  std::map<uint64_t, uint64_t> hashes_;  // content hash of (setup, settings) -> frame hash
};

}  // namespace igi::loadgen
