#pragma once
// Writes finished frames on a thread of its own, so the master's loop keeps
// feeding workers while an image is compressed and written.
#include <condition_variable>
#include <deque>
#include <mutex>
#include <string>
#include <thread>
#include <utility>

#include "image/image.h"

namespace igi {

class FrameWriter {
 public:
  explicit FrameWriter(float exposure);
  ~FrameWriter();  // writes everything queued, then returns
  void write(Image image, std::string path);
  // The first write error, if any (checked by the caller at the end).
  std::string error() const;

 private:
  void run();
  float exposure_;
  mutable std::mutex mutex_;
  std::condition_variable wake_;
  std::deque<std::pair<Image, std::string>> queue_;
  std::string error_;
  bool stopping_ = false;
  std::thread thread_;
};

}  // namespace igi
