#pragma once
// Where a headless run's finished frames go, on a thread of its own: the
// progressive sum, the conversion from the wire's pixel format, and the image
// file. The session thread only queues a frame and goes back to its workers;
// it stops adding frames while backlog() is at its limit, so a slow disk
// bounds the frames in memory instead of growing a queue.
#include <condition_variable>
#include <deque>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

#include "image/exposure_check.h"
#include "image/frame_buffer.h"
#include "image/image.h"
#include "render/accumulator.h"

namespace igi {

class FrameSink {
 public:
  // progressive: each frame joins a running sum and the sum is written; an
  // 8-bit file shows it at `exposure` (metered from each image written, when
  // asked) through `view`.
  FrameSink(int width, int height, ExposureChoice exposure, ViewTransform view, bool progressive);
  ~FrameSink() { finish(); }
  // Finishes everything queued, then stops the thread (idempotent).
  void finish();
  // path empty: the frame only joins the sum (or is dropped, when not progressive).
  void push(std::shared_ptr<FrameBuffer> pixels, std::string path);
  size_t backlog() const;  // frames queued and not yet done
  // The first write error, if any (checked by the caller at the end).
  std::string error() const;
  // The last image written (after finish(): the run's last), if any, and the exposure it was written at.
  std::optional<Image> last_written() const;
  float last_exposure() const;

 private:
  void run();
  void consume(const FrameBuffer& pixels, const std::string& path);
  const ExposureChoice exposure_;
  const ViewTransform view_;
  std::optional<Accumulator> accumulator_;  // progressive only; touched by the sink's thread alone
  mutable std::mutex mutex_;
  std::condition_variable wake_;
  std::deque<std::pair<std::shared_ptr<FrameBuffer>, std::string>> queue_;
  size_t busy_ = 0;
  std::string error_;
  std::optional<Image> last_written_;
  float last_exposure_ = 1.0f;
  bool stopping_ = false;
  std::thread thread_;
};

}  // namespace igi
