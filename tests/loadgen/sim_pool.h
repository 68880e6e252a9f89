#pragma once
// Many simulated workers driven by one thread: it polls their sockets, hands
// each readable one its messages, and ticks every worker (answers due,
// heartbeats, its schedule). A run uses a few pools, so hundreds of workers
// cost a few threads.
#include <atomic>
#include <memory>
#include <thread>
#include <vector>

#include "sim_worker.h"

namespace igi::loadgen {

class SimPool {
 public:
  SimPool(zmq::context_t& context, const SimConnection& connection, const std::vector<SimBehaviour>& behaviours,
          TileCache& tiles, Clock::time_point start);
  ~SimPool();  // stops and joins
  void stop();
  std::vector<SimOutcome> outcomes() const;  // after stop()

 private:
  void run();
  std::vector<std::unique_ptr<SimWorker>> workers_;
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

}  // namespace igi::loadgen
