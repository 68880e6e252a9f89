#pragma once
// The window's frames a second: frames shown over about the last second,
// not one over the gap since the last (which read 4883 fps beside a 50 ms
// frame when two frames came together).
#include <chrono>
#include <deque>

namespace igi {

class FrameRate {
 public:
  using Clock = std::chrono::steady_clock;
  static constexpr std::chrono::milliseconds kWindow{1000};

  void shown(Clock::time_point now) {
    times_.push_back(now);
    forget(now);
  }
  // Frames a second over the window ending `now`; 0 before two frames.
  double fps(Clock::time_point now) {
    forget(now);
    if (times_.size() < 2) return 0.0;
    const double span = std::chrono::duration<double>(times_.back() - times_.front()).count();
    return span > 0.0 ? double(times_.size() - 1) / span : 0.0;
  }
  // Seconds since the last frame shown (0 before any).
  double waiting(Clock::time_point now) const {
    return last_ == Clock::time_point{} && times_.empty()
               ? 0.0
               : std::chrono::duration<double>(now - (times_.empty() ? last_ : times_.back())).count();
  }

 private:
  void forget(Clock::time_point now) {
    while (!times_.empty() && now - times_.front() > kWindow) {
      last_ = times_.front();
      times_.pop_front();
    }
  }
  std::deque<Clock::time_point> times_;
  Clock::time_point last_{};
};

}  // namespace igi
