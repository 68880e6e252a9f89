#pragma once
// The session thread of the two runs that follow a user's view (the window,
// interactive_run.cpp, and a remote viewer, viewer_run.cpp): it plans frames
// for the latest view (motion_planner.h), pumps the session and hands each
// finished frame to the thread that shows or sends it, through a Handover.
// The hand-over queue is short: the session adds no frame while the other
// thread has frames it has not taken.
#include <chrono>
#include <condition_variable>
#include <deque>
#include <mutex>
#include <string>
#include <utility>
#include <vector>

#include "options/master_options.h"
#include "session/master_session.h"
#include "view/motion_planner.h"
#include "scene/scene.h"

namespace igi {

struct Shown {
  CompletedFrame frame;
  PlannedFrame planned;
  std::string level;  // the read-out's name of its level
  double weight = 1.0;  // what it counts for in the accumulated image
  size_t workers = 0;  // when it completed (the display thread must not ask the session)
  std::vector<PeerView> peers;
};

// What the two threads share, under one mutex.
class Handover {
 public:
  using View = MovingView;
  void publish(const View& view) {
    std::lock_guard lock(mutex_);
    view_ = view;
  }
  View view() {
    std::lock_guard lock(mutex_);
    return view_;
  }
  void deliver(Shown shown) {
    {
      std::lock_guard lock(mutex_);
      frames_.push_back(std::move(shown));
    }
    arrived_.notify_one();
  }
  size_t waiting() {
    std::lock_guard lock(mutex_);
    return frames_.size();
  }
  // Waits up to `wait` for a frame (the window keeps polling input meanwhile).
  std::deque<Shown> take(std::chrono::milliseconds wait) {
    std::unique_lock lock(mutex_);
    arrived_.wait_for(lock, wait, [&] { return !frames_.empty() || stop_; });
    return std::exchange(frames_, {});
  }
  void stop(const std::string& error = {}) {
    {
      std::lock_guard lock(mutex_);
      stop_ = true;
      if (error_.empty()) error_ = error;
    }
    arrived_.notify_all();
  }
  bool stopped() {
    std::lock_guard lock(mutex_);
    return stop_;
  }
  std::string error() {
    std::lock_guard lock(mutex_);
    return error_;
  }

 private:
  std::mutex mutex_;
  std::condition_variable arrived_;
  View view_;
  std::deque<Shown> frames_;
  bool stop_ = false;
  std::string error_;
};

// The session thread's loop until handover.stop(); an exception stops the handover with its message.
void session_loop(const MasterOptions& o, const Scene& scene, MasterSession& session, Handover& handover,
                  double budget_ms);

// The status lines: "waiting for a frame (1.2 s)", and for a frame shown
// "12.3 fps  preview 1/4  38 ms/frame ...": frames a second over the last
// second, the level of the frame shown, and what waits.
std::string waiting_line(double seconds);
std::string status_line(const Shown& shown, double accumulated, double fps, bool animated);

}  // namespace igi
