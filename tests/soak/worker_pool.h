#pragma once
// The soak run's igi-worker processes and the faults done to them: killed
// and replaced, stopped past the master's timeout and resumed, slowed by a
// SIGSTOP/SIGCONT duty cycle (stopped 15 ms of every 20: a quarter of the
// speed, heartbeats still on time), and, with a network namespace, one
// worker whose link is cut and restored. Single-threaded: call tick() often
// (every millisecond or two) from the thread that made the pool.
#include <chrono>
#include <string>
#include <vector>

#include "child_process.h"
#include "fault_plan.h"
#include "net_namespace.h"

namespace igi::soak {

class WorkerPool {
 public:
  // `command`: igi-worker and its options, without --connect and --cache (each worker gets its own).
  // With `ns`, one more worker runs inside it and connects to `ns_endpoint`.
  WorkerPool(std::vector<std::string> command, std::string endpoint, std::string log_dir, int loopback_workers,
             NetNamespace* ns, std::string ns_endpoint);
  void start_all();
  // Applies a worker or link fault now; returns the worker it hit, or -1 when none can take it yet
  // (try again later). The fault's own worker is taken when it is running, else the next running one.
  int apply(const Fault& fault);
  // Ends stops and link cuts that are due, drives the slow workers, starts replacements.
  void tick();
  // Workers that ended though nobody killed them (one line each, with their log); each is restarted.
  // One that left with exit code 0 (the master's bye) is only reported if the run goes on for
  // 5 s more: the master says bye to all just before it exits.
  std::vector<std::string> unexpected_exits();
  // After the master's bye: resume everything, wait up to `seconds` for workers to leave, kill the rest.
  // Returns workers that ended badly meanwhile (a crash, a non-zero code).
  std::vector<std::string> finish(double seconds);
  void kill_all();
  int size() const { return int(slots_.size()); }

 private:
  using Clock = std::chrono::steady_clock;
  enum class State { Running, Stopped, Slow, Down, Left };
  struct Slot {
    Child process;
    bool in_namespace = false;
    State state = State::Running;
    Clock::time_point until;        // end of a stop or slow spell; when a killed one is replaced
    Clock::time_point next_toggle;  // slow: next SIGSTOP/SIGCONT
    bool paused = false;            // slow: currently stopped
    int generation = 0;
  };
  void start(int slot);
  int pick(int preferred, bool slow_too) const;  // a running (or slow) loopback slot, preferred first; -1: none

  std::vector<std::string> command_;
  std::string endpoint_, ns_endpoint_;
  std::string log_dir_;
  NetNamespace* ns_;
  std::vector<Slot> slots_;
  bool link_down_ = false;
  Clock::time_point link_up_at_;
};

}  // namespace igi::soak
