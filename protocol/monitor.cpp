#include "protocol/monitor.h"

#include <atomic>
#include <cstring>

#include "protocol/socket.h"

namespace igi::protocol {
namespace {

std::string monitor_endpoint() {
  static std::atomic<uint64_t> next{0};  // inproc names are per context; a counter keeps them apart
  return "inproc://igi-monitor-" + std::to_string(next++);
}

}  // namespace

SocketMonitor::SocketMonitor(zmq::context_t& context, zmq::socket_t& watched, int events)
    : watched_(watched), pair_(context, zmq::socket_type::pair) {
  const std::string endpoint = monitor_endpoint();
  if (zmq_socket_monitor(watched_.handle(), endpoint.c_str(), events) != 0) throw zmq::error_t();
  configure(pair_);
  pair_.connect(endpoint);
}

SocketMonitor::~SocketMonitor() { zmq_socket_monitor(watched_.handle(), nullptr, 0); }

// Each event is two frames: [u16 event, u32 value] in host order, then the endpoint.
std::vector<SocketEvent> SocketMonitor::take_events() {
  std::vector<SocketEvent> events;
  for (;;) {
    zmq::message_t header, endpoint;
    if (!pair_.recv(header, zmq::recv_flags::dontwait)) return events;
    if (!header.more() || !pair_.recv(endpoint, zmq::recv_flags::dontwait) || header.size() != 6) continue;
    SocketEvent e;
    std::memcpy(&e.event, header.data(), 2);
    std::memcpy(&e.value, static_cast<const char*>(header.data()) + 2, 4);
    e.endpoint = endpoint.to_string();
    events.push_back(std::move(e));
  }
}

}  // namespace igi::protocol
