#pragma once
// The viewer's link, measured from the frames themselves: the bytes of the
// last kWindow frames over the time each took from its send to the viewer's
// Ack of it (transfer and one round trip: a lower bound on the link's rate).
// Over a window, not frame by frame: a link with a burst allowance (a token
// bucket, a buffer) passes one frame in no time and the next at its rate.
// Frames too small to fill the link for a round trip say little about its
// rate and are not counted. The H.264 bit rate follows a share of it
// (viewer_run.cpp), so the moving frames fit the link they cross.
#include <algorithm>
#include <cstddef>
#include <deque>
#include <utility>

namespace igi {

class LinkMeter {
 public:
  static constexpr size_t kMinBytes = 16384;  // 2.6 ms at 50 Mbit/s: smaller frames are mostly round trip
  static constexpr size_t kWindow = 8;

  void add(size_t bytes, double seconds) {
    if (bytes < kMinBytes || !(seconds >= 0.0)) return;
    samples_.emplace_back(double(bytes), seconds);
    if (samples_.size() > kWindow) samples_.pop_front();
    double total_bytes = 0.0, total_seconds = 0.0;
    for (const auto& [b, s] : samples_) total_bytes += b, total_seconds += s;
    if (total_seconds > 0.0) mbit_ = total_bytes * 8e-6 / total_seconds;
  }
  // Mbit/s; 0 before the first sample.
  double mbit() const { return mbit_; }
  // What the moving frames may take: `share` of the measured rate, at most `cap` (cap before any sample).
  double budget(double cap, double share) const { return mbit_ > 0.0 ? std::min(cap, share * mbit_) : cap; }

 private:
  std::deque<std::pair<double, double>> samples_;  // bytes, seconds
  double mbit_ = 0.0;
};

}  // namespace igi
