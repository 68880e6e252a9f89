#pragma once
// Thin helpers over cppzmq so master and worker stay short. One message is
// one frame; a ROUTER sees and sends [identity, message].
//
// Threading: a zmq socket belongs to one thread, and so do these calls on it.
// Errors: bad frames from a peer come back as values (Received::error); only
// socket failures (a terminated context, a closed socket) throw zmq::error_t.
#include <cstddef>
#include <optional>
#include <string>

#include <zmq.hpp>

#include "protocol/messages.h"

namespace igi::protocol {

// The most a worker ever sends: a TileResult of the largest tile, plus room
// for its header. The master's socket takes no more from any peer, so an
// unauthenticated one cannot make it allocate a scene's worth per message.
inline constexpr size_t kMaxWorkerMessageBytes = size_t(kMaxTileSide) * kMaxTileSide * 3 * sizeof(float) + 65536;

// Options every socket gets, before bind/connect: ZMQ_MAXMSGSIZE = max_bytes
// (zmq drops the connection of a peer that sends more, and the rest go on),
// linger 0 (close never waits for unsent messages).
void configure(zmq::socket_t& socket, size_t max_bytes = kMaxMessageBytes);

// Bind and connect as the command lines accept endpoints (--listen,
// --connect): tcp://localhost:P binds to 127.0.0.1 (libzmq binds only to
// interface names and addresses, and would fail with "No such device"), and
// an IPv6 address (tcp://[::1]:P) turns on ZMQ_IPV6 for the socket first.
// Throws std::runtime_error naming the endpoint when it cannot.
// A bound socket queues up to kListenBacklog connections not yet accepted
// (the kernel caps it at net.core.somaxconn, 4096 on current Linux).
inline constexpr int kListenBacklog = 1024;
void bind(zmq::socket_t& socket, const std::string& endpoint);
void connect(zmq::socket_t& socket, const std::string& endpoint);

// Sends one message as one frame (DEALER side). Queues without blocking until
// the socket's high-water mark (1000 messages by default); blocks past it.
void send(zmq::socket_t& socket, const Message& m);

// Sends without blocking: false, and nothing queued, when the socket's queue
// is full (the peer stopped reading) or no peer can take it.
bool try_send(zmq::socket_t& socket, const Message& m);

// Sends [identity, message] (ROUTER side). A ROUTER drops messages for an
// identity it does not know or whose queue is full, without an error.
void send_to(zmq::socket_t& router, const std::string& identity, const Message& m);

struct Received {
  std::string identity;            // ROUTER side: the peer's routing id (binary)
  std::optional<Message> message;  // empty when the frame(s) did not decode
  std::string error;               // why not; empty when message is set
  size_t bytes = 0;                // bytes received, identity frame excluded
};

// Waits up to timeout_ms (0 = poll once; negative counts as 0, never forever)
// and receives one message, draining all of its frames. nullopt on timeout.
// A ROUTER expects [identity, message], a DEALER [message]; any other number
// of frames, or bytes that do not decode, give a Received with error set.
std::optional<Received> receive(zmq::socket_t& socket, int timeout_ms, bool router);

}  // namespace igi::protocol
