#pragma once
// The master's ZAP handler (ZeroMQ RFC 27): libzmq asks it whether a CURVE
// client's public key may connect, on a socket bound to
// inproc://zeromq.zap.01 in the same context. It must be bound before any
// CURVE server socket binds: without a handler libzmq lets every key in.
//
// No thread of its own: the owner polls socket() with its other sockets and
// calls answer_waiting(); a client's handshake waits until then (libzmq gives
// a handshake 30 s). Single-threaded, like the socket it serves.
#include <map>
#include <set>
#include <string>
#include <vector>

#include <zmq.hpp>

namespace igi::protocol {

inline constexpr const char* kZapEndpoint = "inproc://zeromq.zap.01";

struct ZapDecision {
  std::string public_key;  // Z85; empty when the request was not CURVE
  std::string address;     // the peer's IP address
  std::string name;        // the authorised key's name; empty when refused
  bool allowed = false;
  bool quarantined = false;  // an authorised key, refused: the master quarantined it this session
};

class ZapHandler {
 public:
  // authorized: Z85 public key -> a name (the .pub file's stem) for logs.
  ZapHandler(zmq::context_t& context, std::map<std::string, std::string> authorized);
  zmq::socket_t& socket() { return socket_; }
  // Answers every request waiting now, without blocking.
  std::vector<ZapDecision> answer_waiting();
  // The key named `name` (an authorised key's name: the "User-Id" property of
  // its messages) is refused from now on: quarantine by key, not by connection.
  void quarantine(const std::string& name) { quarantined_.insert(name); }

 private:
  ZapDecision answer(std::vector<zmq::message_t>& request);
  std::map<std::string, std::string> authorized_;
  std::set<std::string> quarantined_;  // key names
  zmq::socket_t socket_;
};

}  // namespace igi::protocol
