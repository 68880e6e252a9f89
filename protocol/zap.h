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
};

class ZapHandler {
 public:
  // authorized: Z85 public key -> a name (the .pub file's stem) for logs.
  ZapHandler(zmq::context_t& context, std::map<std::string, std::string> authorized);
  zmq::socket_t& socket() { return socket_; }
  // Answers every request waiting now, without blocking.
  std::vector<ZapDecision> answer_waiting();

 private:
  ZapDecision answer(std::vector<zmq::message_t>& request);
  std::map<std::string, std::string> authorized_;
  zmq::socket_t socket_;
};

}  // namespace igi::protocol
