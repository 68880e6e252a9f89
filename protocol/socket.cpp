#include "protocol/socket.h"

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "protocol/codec.h"

namespace igi::protocol {
namespace {

// The encoded bytes handed to zmq without a copy (scenes run to hundreds of
// MB); zmq frees them when the frame has been sent.
zmq::message_t to_frame(const Message& m) {
  auto bytes = std::make_unique<std::vector<uint8_t>>(encode(m));
  auto free_bytes = [](void*, void* hint) { delete static_cast<std::vector<uint8_t>*>(hint); };
  zmq::message_t frame(bytes->data(), bytes->size(), free_bytes, bytes.get());
  bytes.release();  // owned by the frame now
  return frame;
}

bool wait_readable(zmq::socket_t& socket, int timeout_ms) {
  zmq::pollitem_t item{socket.handle(), 0, ZMQ_POLLIN, 0};
  try {
    return zmq::poll(&item, 1, std::chrono::milliseconds(std::max(timeout_ms, 0))) > 0;
  } catch (const zmq::error_t& e) {
    if (e.num() == EINTR) return false;  // a signal: the caller's loop decides
    throw;
  }
}

// The HOST of tcp://HOST:PORT (brackets kept); empty for other transports.
std::string tcp_host(const std::string& endpoint) {
  if (endpoint.rfind("tcp://", 0) != 0) return {};
  const std::string address = endpoint.substr(6);
  return address.substr(0, address.rfind(':'));
}

// ZMQ_IPV6 where the host is an IPv6 address; IPv4 still works on such a socket.
void allow_ipv6(zmq::socket_t& socket, const std::string& endpoint) {
  if (tcp_host(endpoint).find(':') != std::string::npos) socket.set(zmq::sockopt::ipv6, true);
}

// Receives every frame of one message; keeps the first `keep`, counts all.
struct Frames {
  std::vector<zmq::message_t> kept;
  size_t count = 0;
  size_t bytes = 0;  // all frames
};

Frames receive_frames(zmq::socket_t& socket, size_t keep) {
  Frames frames;
  bool more = true;
  while (more) {
    zmq::message_t part;
    if (!socket.recv(part, zmq::recv_flags::dontwait)) break;  // frames of a message arrive together
    more = part.more();
    ++frames.count;
    frames.bytes += part.size();
    if (frames.kept.size() < keep) frames.kept.push_back(std::move(part));
  }
  return frames;
}

}  // namespace

void configure(zmq::socket_t& socket, size_t max_bytes) {
  socket.set(zmq::sockopt::maxmsgsize, static_cast<int64_t>(max_bytes));
  socket.set(zmq::sockopt::linger, 0);
}

void bind(zmq::socket_t& socket, const std::string& endpoint) {
  std::string address = endpoint;
  if (tcp_host(endpoint) == "localhost") address = "tcp://127.0.0.1" + endpoint.substr(endpoint.rfind(':'));
  allow_ipv6(socket, address);
  // Connections the kernel queues before zmq accepts them. libzmq's default
  // is 100, fewer than a cluster of 128 workers connecting at once. (Not the
  // cause of lost joins on its own: see the repeated Hello in worker_session.)
  socket.set(zmq::sockopt::backlog, kListenBacklog);
  try {
    socket.bind(address);
  } catch (const zmq::error_t& e) {
    throw std::runtime_error(endpoint + ": cannot listen there (" + e.what() + ")");
  }
}

void connect(zmq::socket_t& socket, const std::string& endpoint) {
  allow_ipv6(socket, endpoint);
  try {
    socket.connect(endpoint);
  } catch (const zmq::error_t& e) {
    throw std::runtime_error(endpoint + ": cannot connect there (" + e.what() + ")");
  }
}

void send(zmq::socket_t& socket, const Message& m) {
  socket.send(to_frame(m), zmq::send_flags::none);
}

bool try_send(zmq::socket_t& socket, const Message& m) {
  return socket.send(to_frame(m), zmq::send_flags::dontwait).has_value();
}

void send_to(zmq::socket_t& router, const std::string& identity, const Message& m) {
  router.send(zmq::buffer(identity), zmq::send_flags::sndmore);
  router.send(to_frame(m), zmq::send_flags::none);
}

std::optional<Received> receive(zmq::socket_t& socket, int timeout_ms, bool router) {
  if (!wait_readable(socket, timeout_ms)) return std::nullopt;
  const size_t expected = router ? 2 : 1;
  Frames frames = receive_frames(socket, expected);
  if (frames.count == 0) return std::nullopt;  // woken, but nothing to read
  Received received;
  received.bytes = frames.bytes;
  if (router) {
    received.identity = frames.kept[0].to_string();
    received.bytes -= frames.kept[0].size();
  }
  if (frames.count != expected) {
    received.error = std::to_string(frames.count) + " frames, expected " +
                     (router ? "2 ([identity, message])" : "1 (one message)");
    return received;
  }
  const zmq::message_t& payload = frames.kept.back();
  DecodeResult decoded = decode({payload.data<uint8_t>(), payload.size()});
  received.message = std::move(decoded.message);
  received.error = std::move(decoded.error);
  return received;
}

}  // namespace igi::protocol
