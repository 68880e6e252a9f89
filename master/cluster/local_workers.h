#pragma once
// igi-worker processes started by the master on this machine. They die with
// the master however it ends: a normal exit or Ctrl-C stops them here, and a
// crash or kill -9 reaches them through PR_SET_PDEATHSIG.
//
// With CURVE, each worker reads its keys from a pipe inherited as fd 3
// (--curve-fd 3): never on a command line, where `ps` shows it to every user.
#include <chrono>
#include <string>
#include <sys/types.h>
#include <vector>

#include "protocol/curve.h"

namespace igi {

class LocalWorkers {
 public:
  LocalWorkers() = default;
  ~LocalWorkers() { stop_all(); }
  LocalWorkers(const LocalWorkers&) = delete;
  LocalWorkers& operator=(const LocalWorkers&) = delete;

  // Starts `count` workers connecting to `endpoint`. Throws when the worker
  // binary cannot be found or started. `curve`: the keys they connect with, or null.
  void start(int count, const std::string& endpoint, int threads_each, const std::vector<std::string>& extra_args,
             const protocol::CurveClientKeys* curve = nullptr);
  void kill_one(size_t index, int signal);
  // Asks every worker to end and waits at most `grace` (a stopped one too), then kills what is left.
  void stop_all(std::chrono::milliseconds grace = std::chrono::milliseconds(2000));
  const std::vector<pid_t>& pids() const { return pids_; }

 private:
  std::vector<pid_t> pids_;
};

// The igi-worker next to this program (same folder, or ../worker/ in a build tree).
std::string find_worker_binary();

}  // namespace igi
