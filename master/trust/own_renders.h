#pragma once
// What the master renders itself (trust/master_renderer.h, on a thread of
// its own), as the session asks for it:
//  - each frame's VPL-set hash, the reference its workers are judged by: for
//    a frame as it is added, or ahead for a frame to come (expect(), at most
//    kMaxExpected), so that its workers' results need not wait for it;
//  - the tiles no worker's result passed validation for, and those of a
//    frame in doubt that its workers contest (render_tile()).
// Once the master follows its workers (its hashes lost to authenticated
// workers that agreed: trust/referee.h), it computes neither any more.
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "trust/master_renderer.h"

namespace igi {

class OwnRenders {
 public:
  static constexpr size_t kMaxExpected = 8;  // frames whose hashes are computed before they are added

  OwnRenders(Scene scene, bool quiet);
  int fd() const { return renderer_.fd(); }  // readable while answers wait
  bool follows_workers() const { return follows_workers_; }
  void follow_workers() { follows_workers_ = true; }

  // A frame to come: its hash is computed now, and kept for take_expected().
  void expect(const FrameSetup& frame, const RenderSettings& settings);
  // The frame is added: true when it was expected (then `answer` holds its
  // hash, if it came; none inside: the master could not compute it).
  bool take_expected(uint64_t frame_id, std::optional<std::optional<uint64_t>>& answer);
  // The frame's hash, for take_hashes().
  void request(const FrameSetup& frame, const RenderSettings& settings);
  // Hashes of frames added, as they come (none: the master could not
  // compute it, and the frame's workers vote; the log says why).
  struct Hash {
    uint64_t frame_id = 0;
    std::optional<uint64_t> hash;
  };
  std::vector<Hash> take_hashes();

  // A job no worker's result passed, or one its workers contest: `what` says
  // so in the log (when `say`: a contested frame is said once for all its
  // tiles), and is kept for take_what().
  void render_tile(const FrameSetup& frame, const RenderSettings& settings, uint64_t job_id, const TileJob& tile,
                   PixelFormat format, const std::string& what, bool say = true);
  std::vector<MasterRenderer::TileAnswer> take_tiles() { return renderer_.take_tiles(); }
  std::string take_what(uint64_t job_id);

  uint64_t hash_frames() const { return hash_frames_; }     // hashes computed
  double hash_seconds() const { return hash_seconds_; }     // the thread's time on them

 private:
  bool quiet_;
  MasterRenderer renderer_;
  bool follows_workers_ = false;
  // Hashes of expected frames: requested (no answer yet) or answered.
  std::map<uint64_t, std::optional<MasterRenderer::Answer>> expected_;
  std::map<uint64_t, std::string> what_;  // jobs it renders: what the log said of each
  uint64_t hash_frames_ = 0, hash_errors_ = 0, tiles_logged_ = 0;
  double hash_seconds_ = 0.0;
};

}  // namespace igi
