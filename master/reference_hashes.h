#pragma once
// The master's own VPL-set hash for each frame. Every worker gets the same
// scene, settings and frame setup, so the master can make and begin the same
// method itself and judge each worker's hash against what it must have
// computed: no vote among workers, which two fake peers that agree could win.
//
// One thread of its own: the scene's BVH is built there (the session thread
// goes on answering peers meanwhile), then frames are begun one after another,
// each at its own pose. Answers come back through take(); fd() is readable
// while any wait, so the session's poll() wakes for them.
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "core/frame.h"
#include "core/settings.h"
#include "scene/scene.h"

namespace igi {

class ReferenceHashes {
 public:
  explicit ReferenceHashes(Scene scene);
  ~ReferenceHashes();  // abandons frames not yet begun
  ReferenceHashes(const ReferenceHashes&) = delete;
  ReferenceHashes& operator=(const ReferenceHashes&) = delete;

  void request(const FrameSetup& frame, const RenderSettings& settings);

  struct Answer {
    uint64_t frame_id = 0;
    std::optional<uint64_t> hash;  // none when the master could not compute it (error says why)
    std::string error;
  };
  std::vector<Answer> take();
  int fd() const { return fd_; }

 private:
  struct Request {
    FrameSetup frame;
    RenderSettings settings;
  };
  void run(Scene scene);

  std::mutex mutex_;
  std::condition_variable wake_;
  std::deque<Request> requests_;
  std::vector<Answer> answers_;
  bool stopping_ = false;
  int fd_ = -1;  // eventfd
  std::thread thread_;
};

}  // namespace igi
