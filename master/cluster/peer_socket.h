#pragma once
// The master's one ROUTER socket, which every worker dials: sends that never
// block, a batch of messages received at a time, and with CURVE keys the
// security around it (the ZAP handler that lets only authorised worker keys
// complete a handshake, and the monitor that counts failed handshakes). Who
// the peers behind it are is cluster/peers.h's; what they say is the session's.
//
// Single-threaded: the session thread owns it. The ZAP handler is answered in
// serve_security(), no thread of its own.
#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <set>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include <zmq.hpp>

#include "protocol/curve.h"
#include "protocol/messages.h"
#include "protocol/monitor.h"
#include "protocol/zap.h"

namespace igi {

class PeerSocket {
 public:
  // `curve`: null for a plain socket. `send_hwm` > 0 sets ZMQ_SNDHWM (a test
  // hook). Binds `listen`; throws zmq::error_t when it cannot.
  PeerSocket(zmq::context_t& context, const std::string& listen, int send_hwm,
             const protocol::CurveServerKeys* curve, bool quiet);
  const std::string& endpoint() const { return endpoint_; }
  bool curve() const { return zap_ != nullptr; }

  // Bytes queued, or 0 when the peer is gone (take_vanished()) or its queue
  // is full: it stopped reading (take_congested()). Never blocks.
  size_t send(const std::string& identity, zmq::message_t&& payload);
  size_t send(const std::string& identity, const protocol::Message& message);
  std::vector<std::string> take_congested() { return std::exchange(congested_, {}); }
  std::vector<std::string> take_vanished() { return std::exchange(vanished_, {}); }

  // Sleeps in poll() until a message, a ZAP request or `extra_fd` (-1: none)
  // is readable, or `until`.
  void wait(std::chrono::steady_clock::time_point until, int extra_fd);
  // Up to `batch` messages waiting now, each as [identity, payload]: `parts`
  // counts the frames after the identity (a good message has one).
  using Receiver = std::function<void(const std::string& identity, zmq::message_t& payload, size_t parts)>;
  void receive(int batch, const Receiver& receiver);
  // The CURVE key name (the ZAP handler's User-Id) a message came with; "" without CURVE.
  static std::string user_id(zmq::message_t& payload);

  // Answers the handshakes waiting (ZAP) and counts the failed ones.
  void serve_security();
  // The key named `key_name` is refused from now on (a quarantined worker's).
  void refuse_key(const std::string& key_name);
  uint64_t refused_keys() const { return refused_keys_; }            // keys the ZAP handler refused
  uint64_t failed_handshakes() const { return failed_handshakes_; }  // peers without CURVE or the right master key
  // The goodbyes sent last must leave before the process does: up to `ms`, then they are abandoned.
  void linger(int ms) { router_.set(zmq::sockopt::linger, ms); }

 private:
  void on_zap_decision(const protocol::ZapDecision& decision);
  void log(const std::string& text) const;

  bool quiet_;
  std::unique_ptr<protocol::ZapHandler> zap_;  // bound before router_, or CURVE would let every key in
  zmq::socket_t router_;
  std::unique_ptr<protocol::SocketMonitor> monitor_;  // after router_: it watches it
  std::string endpoint_;
  std::vector<std::string> congested_;  // peers whose send queue was full
  std::vector<std::string> vanished_;   // peers whose connection had closed when sent to
  uint64_t refused_keys_ = 0, failed_handshakes_ = 0, quarantined_keys_logged_ = 0;
  std::set<std::string> refused_logged_;  // each refused key is logged once
};

}  // namespace igi
