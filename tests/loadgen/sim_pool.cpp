#include "sim_pool.h"

#include <algorithm>
#include <cerrno>

namespace igi::loadgen {

SimPool::SimPool(zmq::context_t& context, const SimConnection& connection, const std::vector<SimBehaviour>& behaviours,
                 TileCache& tiles, Clock::time_point start) {
  for (const SimBehaviour& b : behaviours) workers_.push_back(std::make_unique<SimWorker>(context, connection, b, tiles, start));
  thread_ = std::thread([this] { run(); });
}

SimPool::~SimPool() { stop(); }

void SimPool::stop() {
  stop_ = true;
  if (thread_.joinable()) thread_.join();
}

std::vector<SimOutcome> SimPool::outcomes() const {
  std::vector<SimOutcome> out;
  for (const auto& w : workers_) out.push_back(w->outcome());
  return out;
}

void SimPool::run() {
  std::vector<zmq::pollitem_t> items;
  std::vector<SimWorker*> polled;
  Clock::time_point next = Clock::now();
  while (!stop_) {
    const Clock::time_point now = Clock::now();
    items.clear();
    polled.clear();
    for (const auto& w : workers_)
      if (zmq::socket_t* s = w->socket(now)) {
        items.push_back({s->handle(), 0, ZMQ_POLLIN, 0});
        polled.push_back(w.get());
      }
    const auto wait = std::chrono::duration_cast<std::chrono::microseconds>(next - now);
    // zmq_poll counts milliseconds: round up rather than spin (an answer is at most 1 ms late).
    const long timeout_ms = std::clamp<long>(long((wait.count() + 999) / 1000), 0, 20);
    try {
      zmq::poll(items, std::chrono::milliseconds(timeout_ms));
    } catch (const zmq::error_t& e) {
      if (e.num() != EINTR) throw;
    }
    const Clock::time_point woke = Clock::now();
    for (size_t i = 0; i < items.size(); ++i)
      if (items[i].revents & ZMQ_POLLIN) polled[i]->on_readable(woke);
    next = woke + std::chrono::milliseconds(20);
    for (const auto& w : workers_) next = std::min(next, w->tick(woke));
  }
}

}  // namespace igi::loadgen
