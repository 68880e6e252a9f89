#include "cluster/peer_socket.h"

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <utility>

#include "protocol/codec.h"
#include "protocol/socket.h"

namespace igi {
namespace {

constexpr uint64_t kLogFirst = 5;  // repeated conditions are logged this often, then counted

}  // namespace

PeerSocket::PeerSocket(zmq::context_t& context, const std::string& listen, int send_hwm,
                       const protocol::CurveServerKeys* curve, bool quiet)
    : quiet_(quiet), router_(context, zmq::socket_type::router) {
  protocol::configure(router_, protocol::kMaxWorkerMessageBytes);
  router_.set(zmq::sockopt::router_mandatory, 1);  // a send to a vanished peer fails instead of vanishing
  if (send_hwm > 0) router_.set(zmq::sockopt::sndhwm, send_hwm);
  // A peer that has not finished the ZMTP handshake in 5 s (a port scanner,
  // non-ZMTP bytes) is disconnected, rather than holding a descriptor for
  // libzmq's default 30 s.
  router_.set(zmq::sockopt::handshake_ivl, 5000);
  if (curve) {
    zap_ = std::make_unique<protocol::ZapHandler>(context, curve->authorized);
    protocol::make_curve_server(router_, curve->own);
    monitor_ = std::make_unique<protocol::SocketMonitor>(
        context, router_, ZMQ_EVENT_HANDSHAKE_FAILED_PROTOCOL | ZMQ_EVENT_HANDSHAKE_FAILED_NO_DETAIL);
  }
  protocol::bind(router_, listen);
  endpoint_ = router_.get(zmq::sockopt::last_endpoint);
}

void PeerSocket::log(const std::string& text) const {
  if (!quiet_) std::fprintf(stderr, "igi-master: %s\n", text.c_str());
}

size_t PeerSocket::send(const std::string& identity, zmq::message_t&& payload) {
  const size_t bytes = payload.size();
  try {
    if (!router_.send(zmq::buffer(identity), zmq::send_flags::sndmore | zmq::send_flags::dontwait)) {
      congested_.push_back(identity);  // its queue is full: it stopped reading
      return 0;
    }
    router_.send(payload, zmq::send_flags::dontwait);  // the rest of a message is never refused
  } catch (const zmq::error_t& e) {
    // ROUTER_MANDATORY: its connection has closed (it exited, or its TCP
    // connection was re-established under a new routing id, as a loaded
    // machine's can be while it joins). Its jobs go back now, not after the timeout.
    if (e.num() == EHOSTUNREACH) vanished_.push_back(identity);
    return 0;
  }
  return bytes;
}

size_t PeerSocket::send(const std::string& identity, const protocol::Message& message) {
  std::vector<uint8_t> bytes = protocol::encode(message);
  zmq::message_t payload(bytes.data(), bytes.size());
  return send(identity, std::move(payload));
}

void PeerSocket::wait(std::chrono::steady_clock::time_point until, int extra_fd) {
  const auto wait = std::chrono::duration_cast<std::chrono::milliseconds>(until - std::chrono::steady_clock::now());
  std::vector<zmq::pollitem_t> items{{router_.handle(), 0, ZMQ_POLLIN, 0}};
  if (zap_) items.push_back({zap_->socket().handle(), 0, ZMQ_POLLIN, 0});
  if (extra_fd >= 0) items.push_back({nullptr, extra_fd, ZMQ_POLLIN, 0});
  try {
    // Round up: a wake a millisecond early would only poll again.
    zmq::poll(items, std::chrono::milliseconds(std::max<int64_t>(0, wait.count() + 1)));
  } catch (const zmq::error_t& e) {
    if (e.num() != EINTR) throw;  // a signal: the caller's loop decides
  }
}

void PeerSocket::receive(int batch, const Receiver& receiver) {
  for (int n = 0; n < batch; ++n) {
    zmq::message_t identity, payload;
    if (!router_.recv(identity, zmq::recv_flags::dontwait)) return;
    size_t parts = 1;
    bool more = identity.more();
    while (more) {
      zmq::message_t part;
      if (!router_.recv(part, zmq::recv_flags::dontwait)) break;  // parts of a message arrive together
      more = part.more();
      if (parts++ == 1) payload = std::move(part);
    }
    receiver(identity.to_string(), payload, parts - 1);
  }
}

std::string PeerSocket::user_id(zmq::message_t& payload) {
  const char* user = zmq_msg_gets(payload.handle(), "User-Id");
  return user ? user : "";
}

// Handshakes wait for these answers; a peer is only a peer once they pass.
void PeerSocket::serve_security() {
  if (zap_)
    for (const protocol::ZapDecision& d : zap_->answer_waiting()) on_zap_decision(d);
  if (!monitor_) return;
  for (size_t n = monitor_->take_events().size(); n > 0; --n) {
    // A flood of these is an attack or a misconfigured farm: log the first few, count all.
    if (++failed_handshakes_ <= kLogFirst)
      log("a peer failed the CURVE handshake (it does not use CURVE, or has another master public key)");
  }
}

void PeerSocket::on_zap_decision(const protocol::ZapDecision& d) {
  if (d.allowed) return log("CURVE key '" + d.name + "' from " + d.address + " accepted");
  if (d.quarantined) {
    ++refused_keys_;
    if (++quarantined_keys_logged_ <= kLogFirst || quarantined_keys_logged_ % 1000 == 0)
      std::fprintf(stderr, "igi-master: refused CURVE key '%s' from %s: it was quarantined in this session\n",
                   d.name.c_str(), d.address.c_str());
    return;
  }
  ++refused_keys_;
  // Each key once, and a bounded set: a peer may try a new key per connection.
  if (refused_logged_.size() < 1000 && refused_logged_.insert(d.public_key).second)
    std::fprintf(stderr,
                 "igi-master: refused worker key %s from %s: not among --authorized-keys (%llu refused so far)\n",
                 d.public_key.empty() ? "(not CURVE)" : d.public_key.c_str(), d.address.c_str(),
                 static_cast<unsigned long long>(refused_keys_));
}

void PeerSocket::refuse_key(const std::string& key_name) {
  if (zap_ && !key_name.empty()) zap_->quarantine(key_name);
}

}  // namespace igi
