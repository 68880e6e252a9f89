#include "viewer/viewer_client.h"

#include <cerrno>

#include "protocol/socket.h"
#include "viewer/viewer_port.h"

namespace igi {
namespace {

using Clock = std::chrono::steady_clock;

constexpr int kEvents = ZMQ_EVENT_HANDSHAKE_SUCCEEDED | ZMQ_EVENT_HANDSHAKE_FAILED_NO_DETAIL |
                        ZMQ_EVENT_HANDSHAKE_FAILED_PROTOCOL | ZMQ_EVENT_HANDSHAKE_FAILED_AUTH |
                        ZMQ_EVENT_DISCONNECTED;

}  // namespace

ViewerClient::ViewerClient(const std::string& endpoint, const protocol::CurveClientKeys& keys)
    : endpoint_(endpoint), context_(1), socket_(context_, zmq::socket_type::dealer),
      monitor_(context_, socket_, kEvents) {
  protocol::configure(socket_, display::kMaxMessageBytes);
  protocol::make_curve_client(socket_, keys);
  protocol::connect(socket_, endpoint);
  heard_ = said_ = Clock::now();
}

ViewerClient::~ViewerClient() = default;

std::string ViewerClient::silent_hint(std::chrono::milliseconds waited) const {
  std::string hint = "no answer in " + std::to_string(waited.count() / 1000) + " s from a master at " + endpoint_;
  if (curve_mismatch_) return hint + ": it does not use CURVE there (is that --viewer-listen's port?)";
  if (failed_handshakes_ > 0)
    return hint + ": " + std::to_string(failed_handshakes_) +
           " CURVE handshakes failed: is --master-key the public key of that master's --key?";
  return hint + " (is igi-master running with --viewer-listen there, and the ssh tunnel open?)";
}

// A refused handshake never becomes a message: zmq would retry it for ever.
void ViewerClient::check_connection() {
  for (const protocol::SocketEvent& e : monitor_.take_events()) {
    if (e.event == ZMQ_EVENT_HANDSHAKE_FAILED_AUTH)
      throw ViewerError("the master at " + endpoint_ + " refused this viewer's key (ZAP status " +
                        std::to_string(e.value) + "): its operator must add this viewer's NAME.pub to the master's "
                        "--viewer-keys");
    if (e.event == ZMQ_EVENT_DISCONNECTED && welcomed_)
      throw ViewerError("the master at " + endpoint_ + " closed the connection (it exited, or the tunnel closed)");
    if (e.event == ZMQ_EVENT_HANDSHAKE_FAILED_PROTOCOL && e.value == ZMQ_PROTOCOL_ERROR_ZMTP_MECHANISM_MISMATCH)
      curve_mismatch_ = true;
    else if (e.event != ZMQ_EVENT_HANDSHAKE_SUCCEEDED && e.event != ZMQ_EVENT_DISCONNECTED)
      ++failed_handshakes_;
  }
}

void ViewerClient::send(const display::Message& message) {
  const std::vector<uint8_t> bytes = display::encode(message);
  // A full queue (the master is away): the message is dropped; the timeout says so.
  socket_.send(zmq::buffer(bytes), zmq::send_flags::dontwait);
  said_ = Clock::now();
}

std::optional<display::Message> ViewerClient::receive(std::chrono::milliseconds wait) {
  std::vector<zmq::pollitem_t> items{{socket_.handle(), 0, ZMQ_POLLIN, 0}};
  try {
    zmq::poll(items, wait);
  } catch (const zmq::error_t& e) {
    if (e.num() != EINTR) throw;
  }
  zmq::message_t payload;
  const bool got = socket_.recv(payload, zmq::recv_flags::dontwait).has_value();
  check_connection();  // after the message: a Bye sent before the master closed is read first
  const auto now = Clock::now();
  if (!got) {
    if (welcomed_ && now - heard_ > kViewerTimeout)
      throw ViewerError("the master at " + endpoint_ + " has been silent for " +
                        std::to_string(kViewerTimeout.count() / 1000) + " s (it stopped, or the link is down)");
    if (welcomed_ && now - said_ > kViewerPing) send(display::Ping{});
    return std::nullopt;
  }
  heard_ = now;
  bytes_received_ += payload.size();
  display::Decoded d = display::decode({static_cast<const uint8_t*>(payload.data()), payload.size()});
  if (!d.message) throw ViewerError("the master at " + endpoint_ + " sent a malformed message: " + d.error);
  if (auto* refuse = std::get_if<display::Refuse>(&*d.message))
    throw ViewerError("the master at " + endpoint_ + " refused this viewer: " + refuse->reason);
  if (auto* bye = std::get_if<display::Bye>(&*d.message))
    throw ViewerError("the master at " + endpoint_ + " said goodbye: " + bye->reason);
  if (std::holds_alternative<display::Ping>(*d.message)) return std::nullopt;
  if (now - said_ > kViewerPing) send(display::Ping{});
  return std::move(d.message);
}

display::Welcome ViewerClient::join(std::chrono::milliseconds patience) {
  send(display::Hello{"igi-view " + std::to_string(display::kVersion)});
  const auto until = Clock::now() + patience;
  while (Clock::now() < until) {
    std::optional<display::Message> m = receive(std::chrono::milliseconds(20));
    if (!m) continue;
    if (auto* welcome = std::get_if<display::Welcome>(&*m)) {
      welcomed_ = true;
      return std::move(*welcome);
    }
  }
  throw ViewerError(silent_hint(patience));
}

void ViewerClient::close(const std::string& reason) {
  send(display::Bye{reason});
  socket_.set(zmq::sockopt::linger, 500);
}

}  // namespace igi
