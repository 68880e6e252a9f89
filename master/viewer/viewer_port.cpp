#include "viewer/viewer_port.h"

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <utility>

#include "protocol/socket.h"

namespace igi {
namespace {

using Clock = std::chrono::steady_clock;

std::string key_name(zmq::message_t& payload) {
  const char* user = zmq_msg_gets(payload.handle(), "User-Id");
  return user ? user : "";
}

}  // namespace

ViewerPort::ViewerPort(const std::string& listen, const protocol::CurveServerKeys& keys, display::Welcome welcome,
                       bool quiet)
    : quiet_(quiet), welcome_(std::move(welcome)), context_(1),
      zap_(std::make_unique<protocol::ZapHandler>(context_, keys.authorized)),
      router_(context_, zmq::socket_type::router) {
  protocol::configure(router_, display::kMaxMessageBytes);
  router_.set(zmq::sockopt::router_mandatory, 1);
  router_.set(zmq::sockopt::handshake_ivl, 5000);
  // Frames are credited (kFramesInFlight): a deep queue would only hold stale ones.
  router_.set(zmq::sockopt::sndhwm, 64);
  protocol::make_curve_server(router_, keys.own);
  monitor_ = std::make_unique<protocol::SocketMonitor>(
      context_, router_, ZMQ_EVENT_HANDSHAKE_FAILED_PROTOCOL | ZMQ_EVENT_HANDSHAKE_FAILED_NO_DETAIL);
  protocol::bind(router_, listen);
  endpoint_ = router_.get(zmq::sockopt::last_endpoint);
}

ViewerPort::~ViewerPort() {
  monitor_.reset();  // before the socket it watches
}

void ViewerPort::log(const std::string& text) const {
  if (!quiet_) std::fprintf(stderr, "igi-master: %s\n", text.c_str());
}

bool ViewerPort::send(const std::string& identity, const display::Message& message) {
  const std::vector<uint8_t> bytes = display::encode(message);
  try {
    if (!router_.send(zmq::buffer(identity), zmq::send_flags::sndmore | zmq::send_flags::dontwait)) return false;
    router_.send(zmq::buffer(bytes), zmq::send_flags::dontwait);
  } catch (const zmq::error_t& e) {
    if (e.num() == EHOSTUNREACH) return false;  // its connection closed
    throw;
  }
  if (identity == viewer_) said_ = Clock::now();
  return true;
}

ViewerPort::Incoming ViewerPort::poll(std::chrono::milliseconds wait) {
  std::vector<zmq::pollitem_t> items{{router_.handle(), 0, ZMQ_POLLIN, 0}, {zap_->socket().handle(), 0, ZMQ_POLLIN, 0}};
  try {
    zmq::poll(items, wait);
  } catch (const zmq::error_t& e) {
    if (e.num() != EINTR) throw;
  }
  for (const protocol::ZapDecision& d : zap_->answer_waiting())
    if (d.allowed) log("viewer key '" + d.name + "' from " + d.address + " accepted");
    else log("refused viewer key " + (d.public_key.empty() ? std::string("(not CURVE)") : d.public_key) + " from " +
             d.address + ": not among --viewer-keys");
  for (size_t n = monitor_->take_events().size(); n > 0; --n)
    if (++failed_handshakes_ <= 5)
      log("a peer failed the viewer port's CURVE handshake (no CURVE, or another master public key)");
  for (int n = 0; n < 64; ++n) {  // a batch; the rest waits for the next poll
    zmq::message_t identity;
    if (!router_.recv(identity, zmq::recv_flags::dontwait)) break;
    std::vector<zmq::message_t> parts;
    for (bool more = identity.more(); more;) {  // parts of a message arrive together
      zmq::message_t part;
      if (!router_.recv(part, zmq::recv_flags::dontwait)) break;
      more = part.more();
      parts.push_back(std::move(part));
    }
    if (parts.size() == 1) handle(identity.to_string(), parts[0]);
    else log("a viewer sent a message of " + std::to_string(parts.size()) + " parts, expected 1 (dropped)");
  }
  const auto now = Clock::now();
  if (connected() && now - heard_ > kViewerTimeout) drop("silent for " + std::to_string(kViewerTimeout.count()) +
                                                         " ms (killed, or its link broke)");
  if (connected() && now - said_ > kViewerPing && !send(viewer_, display::Ping{}))
    drop("is gone (its connection closed)");
  return std::exchange(incoming_, {});
}

void ViewerPort::handle(const std::string& identity, zmq::message_t& payload) {
  const std::string name = key_name(payload);
  display::Decoded d = display::decode({static_cast<const uint8_t*>(payload.data()), payload.size()});
  if (!d.message) {
    log("viewer '" + name + "': " + d.error + " (message dropped)");
    if (identity != viewer_) send(identity, display::Refuse{d.error});
    return;
  }
  if (auto* hello = std::get_if<display::Hello>(&*d.message)) return on_hello(identity, name, *hello);
  if (identity != viewer_) {  // not the viewer (one that was dropped, or never said Hello)
    send(identity, display::Bye{"this viewer is no longer connected (silent for too long): start it again"});
    return;
  }
  heard_ = Clock::now();
  if (auto* view = std::get_if<display::View>(&*d.message)) incoming_.view = std::move(*view);
  else if (auto* ack = std::get_if<display::Ack>(&*d.message)) on_ack(ack->frame);
  else if (auto* request = std::get_if<display::Request>(&*d.message)) incoming_.requests.push_back(*request);
  else if (auto* bye = std::get_if<display::Bye>(&*d.message)) drop("left (" + bye->reason + ")");
  else if (!std::holds_alternative<display::Ping>(*d.message))
    log("viewer '" + name + "' sent a " + display::type_name(display::type_of(*d.message)) + " (ignored)");
}

void ViewerPort::on_ack(uint64_t frame) {
  acknowledged_ = std::max(acknowledged_, std::min(frame, sequence_));
  const auto now = Clock::now();
  while (!in_flight_.empty() && in_flight_.front().sequence <= acknowledged_) {
    const InFlight& f = in_flight_.front();
    if (f.sequence == frame) link_.add(f.bytes, std::chrono::duration<double>(now - f.sent).count());
    in_flight_.pop_front();
  }
}

void ViewerPort::on_hello(const std::string& identity, const std::string& name, const display::Hello& hello) {
  // A viewer whose process ended has a closed connection (ROUTER_MANDATORY
  // says so at a send): its successor need not wait for the timeout.
  if (connected() && identity != viewer_ && !send(viewer_, display::Ping{})) drop("is gone (its connection closed)");
  if (connected() && identity != viewer_) {
    log("refused a second viewer, '" + name + "': '" + viewer_name_ + "' is connected");
    send(identity, display::Refuse{"another viewer ('" + viewer_name_ + "') is connected; igi-master takes one "
                                   "viewer at a time: close that one, or wait " +
                                   std::to_string(kViewerTimeout.count() / 1000) + " s after it was killed"});
    return;
  }
  viewer_ = identity;
  viewer_name_ = name;
  heard_ = Clock::now();
  sequence_ = acknowledged_ = 0;
  in_flight_.clear();
  incoming_ = {};
  incoming_.joined = true;
  log("viewer '" + name + "' (" + hello.program + ") joined");
  send(viewer_, welcome_);
}

void ViewerPort::drop(const std::string& why) {
  log("viewer '" + viewer_name_ + "' " + why + "; rendering goes on, the port takes the next viewer");
  viewer_.clear();
  viewer_name_.clear();
}

bool ViewerPort::can_send_frame() const {
  return connected() && sequence_ - acknowledged_ < uint64_t(display::kFramesInFlight);
}

size_t ViewerPort::send_frame(display::Frame frame) {
  if (!can_send_frame()) return 0;
  frame.sequence = sequence_ + 1;
  const size_t bytes = frame.pixels.size();
  if (!send(viewer_, frame)) return 0;  // its queue is full or it has gone: the next poll sees
  ++sequence_;
  in_flight_.push_back({sequence_, bytes, Clock::now()});
  ++frames_sent_;
  return bytes;
}

void ViewerPort::reply(const display::Reply& reply) {
  if (connected()) send(viewer_, reply);
}

void ViewerPort::close(const std::string& reason, int linger_ms) {
  if (connected()) send(viewer_, display::Bye{reason});
  router_.set(zmq::sockopt::linger, linger_ms);
}

}  // namespace igi
