#include "garbage_client.h"

#include <arpa/inet.h>
#include <chrono>
#include <cstring>
#include <netinet/in.h>
#include <sys/socket.h>
#include <thread>
#include <unistd.h>
#include <vector>

#include "fault_plan.h"
#include "protocol/codec.h"

namespace igi::soak {
namespace {

std::vector<uint8_t> random_bytes(Rng& rng, size_t n) {
  std::vector<uint8_t> bytes(n);
  for (uint8_t& b : bytes) b = uint8_t(rng.next());
  return bytes;
}

// A real message of a random type, as a worker or the master would send it.
std::vector<uint8_t> real_message(Rng& rng) {
  switch (rng.below(4)) {
    case 0: return protocol::encode(protocol::Hello{"soak-garbage", "none", uint32_t(rng.below(64))});
    case 1: return protocol::encode(protocol::Heartbeat{});
    case 2: return protocol::encode(protocol::SceneRequest{rng.next()});
    default: {
      protocol::TileResult r;
      r.frame_id = uint64_t(rng.below(400));
      r.job_id = uint64_t(rng.below(10000));
      r.tile = {16 * rng.below(4), 16 * rng.below(3), 16, 16, 1};
      r.pixels.assign(256, glm::vec3(0.5f));
      return protocol::encode(r);
    }
  }
}

// ZMTP 3.0: greeting (NULL mechanism, client), then READY announcing a DEALER.
std::vector<uint8_t> zmtp_handshake() {
  std::vector<uint8_t> g(64, 0);
  g[0] = 0xff;
  g[9] = 0x7f;
  g[10] = 3;  // version 3.0
  std::memcpy(&g[12], "NULL", 4);
  const std::string ready = std::string("\x05READY") + "\x0bSocket-Type" + std::string("\0\0\0\x06", 4) + "DEALER";
  g.push_back(0x04);  // command, short
  g.push_back(uint8_t(ready.size()));
  g.insert(g.end(), ready.begin(), ready.end());
  return g;
}

bool send_all(int fd, const std::vector<uint8_t>& bytes) {
  size_t sent = 0;
  while (sent < bytes.size()) {
    ssize_t n = ::send(fd, bytes.data() + sent, bytes.size() - sent, MSG_NOSIGNAL);
    if (n <= 0) return false;
    sent += size_t(n);
  }
  return true;
}

// True when the peer closes the connection within `seconds` (reading and discarding what it sends).
bool closed_by_peer(int fd, double seconds) {
  timeval tv{time_t(seconds), suseconds_t((seconds - double(time_t(seconds))) * 1e6)};
  setsockopt(fd, SOL_SOCKET, SO_RCVTIMEO, &tv, sizeof tv);
  char buffer[256];
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  while (std::chrono::steady_clock::now() < end) {
    ssize_t n = ::recv(fd, buffer, sizeof buffer, 0);
    if (n == 0 || (n < 0 && errno == ECONNRESET)) return true;
    if (n < 0) return false;  // timed out: still open
  }
  return false;
}

}  // namespace

GarbageClient::GarbageClient(std::string host, int port, bool real_oversized)
    : host_(std::move(host)), port_(port), real_oversized_pending_(real_oversized) {}

int GarbageClient::connect_tcp() const {
  const int fd = socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_port = htons(uint16_t(port_));
  inet_pton(AF_INET, host_.c_str(), &address.sin_addr);
  timeval tv{1, 0};
  setsockopt(fd, SOL_SOCKET, SO_SNDTIMEO, &tv, sizeof tv);
  if (fd >= 0 && ::connect(fd, reinterpret_cast<sockaddr*>(&address), sizeof address) == 0) return fd;
  if (fd >= 0) close(fd);
  return -1;
}

GarbageCounts GarbageClient::burst(uint64_t seed) {
  GarbageCounts counts;
  Rng rng(seed);
  {
    zmq::socket_t dealer(context_, zmq::socket_type::dealer);
    dealer.set(zmq::sockopt::linger, 500);
    dealer.connect("tcp://" + host_ + ":" + std::to_string(port_));
    const int messages = 20 + rng.below(41);
    for (int i = 0; i < messages; ++i) send_zmq(dealer, rng.next(), counts);
  }  // closed; what is queued still goes out within the linger
  const int connections = 1 + rng.below(3);
  for (int i = 0; i < connections; ++i) {
    switch (rng.below(4)) {
      case 0: oversized_header(protocol::kMaxMessageBytes + 1, counts); break;
      case 1: oversized_header(uint64_t(1) << 62, counts); break;
      case 2: raw_bytes(rng.next(), counts); break;
      default: idle_flood(8 + rng.below(57), counts); break;
    }
  }
  if (real_oversized_pending_.exchange(false)) real_oversized(counts);
  return counts;
}

void GarbageCounts::add(const GarbageCounts& other) {
  for (const auto& [kind, n] : other.sent) sent[kind] += n;
  zmq_messages += other.zmq_messages;
}

void GarbageClient::send_zmq(zmq::socket_t& dealer, uint64_t seed, GarbageCounts& counts) const {
  Rng rng(seed);
  std::vector<std::vector<uint8_t>> parts;
  std::string kind;
  switch (rng.below(8)) {
    case 0: kind = "random bytes"; parts.push_back(random_bytes(rng, size_t(rng.below(2048)))); break;
    case 1:
      kind = "wrong frame count";
      for (int n = 2 + rng.below(3); n > 0; --n) parts.push_back(real_message(rng));
      break;
    case 2: kind = "empty message"; parts.emplace_back(); break;
    case 3: {
      kind = "valid header, broken payload";
      std::vector<uint8_t> m = real_message(rng);
      m.resize(8);
      m[6] = uint8_t(1 + rng.below(10));  // any type
      std::vector<uint8_t> tail = random_bytes(rng, size_t(rng.below(512)));
      m.insert(m.end(), tail.begin(), tail.end());
      parts.push_back(m);
      break;
    }
    case 4: {
      kind = "bit-flipped message";
      std::vector<uint8_t> m = real_message(rng);
      for (int n = 1 + rng.below(4); n > 0; --n) m[size_t(rng.below(int(m.size())))] ^= uint8_t(1u << rng.below(8));
      parts.push_back(m);
      break;
    }
    case 5: {
      kind = "other protocol version";
      std::vector<uint8_t> m = protocol::encode(protocol::Hello{"soak", "none", 1});
      m[4] = uint8_t(protocol::kVersion + 1 + rng.below(100));
      parts.push_back(m);
      break;
    }
    case 6:
      kind = "hello from another build";  // refused with a reason, not counted as bad
      parts.push_back(protocol::encode(protocol::Hello{"another-build", "none", 1}));
      break;
    default: kind = "large message (1-4 MB)"; parts.push_back(random_bytes(rng, size_t(1 + rng.below(4)) << 20)); break;
  }
  bool ok = true;
  for (size_t i = 0; i < parts.size() && ok; ++i) {
    const auto flags = (i + 1 < parts.size() ? zmq::send_flags::sndmore : zmq::send_flags::none) | zmq::send_flags::dontwait;
    ok = dealer.send(zmq::buffer(parts[i]), flags).has_value();
  }
  ++counts.sent[ok ? "zmq: " + kind : "zmq: not sent (queue full): " + kind];
  counts.zmq_messages += ok;
}

void GarbageClient::oversized_header(uint64_t announced, GarbageCounts& counts) const {
  const int fd = connect_tcp();
  if (fd < 0) return void(++counts.sent["tcp: connection refused (master down)"]);
  std::vector<uint8_t> bytes = zmtp_handshake();
  bytes.push_back(0x02);  // message, long size, last frame
  for (int shift = 56; shift >= 0; shift -= 8) bytes.push_back(uint8_t(announced >> shift));
  bytes.insert(bytes.end(), 64, 0xab);  // the first bytes of a body that never comes
  const std::string size = announced > (uint64_t(1) << 40) ? "2^62" : "limit + 1";
  if (!send_all(fd, bytes)) ++counts.sent["tcp: frame header announcing " + size + " bytes: send failed"];
  else if (closed_by_peer(fd, 2.0)) ++counts.sent["tcp: frame header announcing " + size + " bytes: dropped by the master"];
  else ++counts.sent["tcp: frame header announcing " + size + " bytes: NOT dropped within 2 s"];
  close(fd);
}

void GarbageClient::raw_bytes(uint64_t seed, GarbageCounts& counts) const {
  Rng rng(seed);
  const int fd = connect_tcp();
  if (fd < 0) return void(++counts.sent["tcp: connection refused (master down)"]);
  std::vector<uint8_t> bytes = random_bytes(rng, size_t(64 + rng.below(4096)));
  bytes[0] = 0x47;  // "G": never the ZMTP signature's 0xff
  send_all(fd, bytes);
  // A first byte other than 0xff reads as ZMTP 1.0: libzmq then waits for frames until its
  // handshake timeout (30 s), so most such connections are held, not dropped; we close them.
  ++counts.sent[closed_by_peer(fd, 2.0) ? "tcp: non-ZMTP bytes: dropped by the master"
                                        : "tcp: non-ZMTP bytes: held open by the master (closed by us after 2 s)"];
  close(fd);
}

void GarbageClient::idle_flood(int connections, GarbageCounts& counts) const {
  std::vector<int> fds;
  for (int i = 0; i < connections; ++i)
    if (int fd = connect_tcp(); fd >= 0) fds.push_back(fd);
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  for (int fd : fds) close(fd);
  counts.sent["tcp: idle connections opened and closed"] += fds.size();
}

void GarbageClient::real_oversized(GarbageCounts& counts) {
  zmq::socket_t dealer(context_, zmq::socket_type::dealer);
  dealer.set(zmq::sockopt::linger, 0);
  dealer.connect("tcp://" + host_ + ":" + std::to_string(port_));
  zmq::message_t big(protocol::kMaxMessageBytes + 1);  // never touched: the header alone must get it dropped
  const auto start = std::chrono::steady_clock::now();
  const bool ok = dealer.send(big, zmq::send_flags::dontwait).has_value();
  std::this_thread::sleep_for(std::chrono::milliseconds(500));
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  ++counts.sent[ok ? "zmq: real message of limit + 1 bytes (" + std::to_string(int(seconds * 1e3)) + " ms)" : "zmq: real oversized: not sent"];
}

}  // namespace igi::soak
