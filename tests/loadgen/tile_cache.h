#pragma once
// Pre-rendered tiles for simulated workers. The encoded TileResult of each
// tile rectangle is made once per pixel format; an answer is a copy with the
// frame id, job id and VPL-set hash written in. The pixels are a pure
// function of their image coordinates (expected_pixel), exact in half and
// float, so a test can check every pixel of the master's frames.
#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <tuple>
#include <vector>

#include <glm/glm.hpp>
#include <zmq.hpp>

#include "core/frame.h"
#include "core/settings.h"
#include "image/frame_buffer.h"
#include "render/scene_state.h"

namespace igi::loadgen {

glm::vec3 expected_pixel(int x, int y);

class TileCache {
 public:
  // Thread-safe; the bytes stay valid while the cache lives.
  const std::vector<uint8_t>& encoded(const TileJob& tile, PixelFormat format);

  // An answer to (frame, job) from `encoded`; `claimed` is the rectangle it
  // says it covers (the job's own, or another one for a faulty worker).
  static zmq::message_t answer(const std::vector<uint8_t>& encoded, uint64_t frame_id, uint64_t job_id,
                               uint64_t frame_state_hash, const TileJob& claimed);
  // Makes the answer's first pixel NaN (its format's encoding).
  static void poison(zmq::message_t& answer, PixelFormat format);

  // The VPL-set hash a correct worker of the built-in Cornell box reports for
  // this frame (the master computes the same one: master/master_renderer.h);
  // thread-safe, computed once per frame setup.
  uint64_t frame_hash(const FrameSetup& frame, const RenderSettings& settings);

 private:
  using Key = std::tuple<int, int, int, int, int, int>;
  std::mutex mutex_;
  std::map<Key, std::unique_ptr<std::vector<uint8_t>>> tiles_;
  std::mutex hash_mutex_;
  std::unique_ptr<SceneState> scene_;    // the Cornell box, built on first use
  std::map<uint64_t, uint64_t> hashes_;  // content hash of (setup, settings) -> frame hash
};

}  // namespace igi::loadgen
