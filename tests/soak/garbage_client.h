#pragma once
// A hostile peer on the master's port. Over ZeroMQ (a DEALER, as a worker
// would connect): random bytes, messages of the wrong frame count, empty
// ones, valid headers over broken payloads, bit-flipped real messages,
// another protocol version, a Hello from another build, large legal-size
// messages. Over plain TCP: bytes that are not ZMTP at all, a ZMTP handshake
// followed by a frame header announcing more than the master's limit
// (ZMQ_MAXMSGSIZE must drop the connection on the header, before any byte
// of the body), and a flood of idle connections.
#include <atomic>
#include <cstdint>
#include <map>
#include <string>

#include <zmq.hpp>

namespace igi::soak {

// What a burst sent, by kind (and how the master answered the raw connections).
struct GarbageCounts {
  std::map<std::string, uint64_t> sent;
  uint64_t zmq_messages = 0;
  void add(const GarbageCounts& other);
};

// Bursts may run on several threads at once (each has its own sockets).
class GarbageClient {
 public:
  GarbageClient(std::string host, int port, bool real_oversized);
  // One burst of 20-60 bad messages and 1-3 bad connections, drawn from `seed`.
  GarbageCounts burst(uint64_t seed);

 private:
  void send_zmq(zmq::socket_t& dealer, uint64_t seed, GarbageCounts& counts) const;
  void oversized_header(uint64_t announced, GarbageCounts& counts) const;
  void raw_bytes(uint64_t seed, GarbageCounts& counts) const;
  void idle_flood(int connections, GarbageCounts& counts) const;
  void real_oversized(GarbageCounts& counts);
  int connect_tcp() const;

  std::string host_;
  int port_;
  std::atomic<bool> real_oversized_pending_;
  zmq::context_t context_;
};

}  // namespace igi::soak
