#pragma once
// A socket's connection and handshake events (zmq_socket_monitor), read by
// the owner's loop without blocking: how a CURVE client learns that the
// master refused its key, which no message would tell it.
//
// Declare it after the socket it watches (it stops watching in its
// destructor, which needs the socket alive). Same thread as that socket.
#include <cstdint>
#include <string>
#include <vector>

#include <zmq.hpp>

namespace igi::protocol {

struct SocketEvent {
  uint16_t event = 0;    // ZMQ_EVENT_*
  uint32_t value = 0;    // e.g. the ZAP status code, or a ZMQ_PROTOCOL_ERROR_*
  std::string endpoint;  // as zmq reports it
};

class SocketMonitor {
 public:
  SocketMonitor(zmq::context_t& context, zmq::socket_t& watched, int events);
  ~SocketMonitor();
  SocketMonitor(const SocketMonitor&) = delete;
  SocketMonitor& operator=(const SocketMonitor&) = delete;
  // Every event that arrived since the last call, oldest first.
  std::vector<SocketEvent> take_events();

 private:
  zmq::socket_t& watched_;
  zmq::socket_t pair_;
};

}  // namespace igi::protocol
