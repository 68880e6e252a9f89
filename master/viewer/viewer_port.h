#pragma once
// The master's end of the display link (igi-master --viewer-listen): one
// ROUTER socket with CURVE, whose ZAP handler lets in only the viewers' keys
// (--viewer-keys), in a ZeroMQ context of its own (a context has one ZAP
// handler, and the workers' keys are not the viewers'). One viewer at a time:
// a second is refused, saying who holds the port. A viewer whose connection
// closed (its process ended) is gone at the next send to it (ROUTER_MANDATORY),
// one silent for kViewerTimeout (its link broke) at the timeout, and the port
// is free again; the render never waits for it.
//
// Frames: at most kFramesInFlight unacknowledged (display_messages.h); the
// caller asks can_send_frame() and sends the newest image only then.
// Single-threaded: the thread that sends frames owns it.
#include <chrono>
#include <cstdint>
#include <deque>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <zmq.hpp>

#include "protocol/curve.h"
#include "protocol/monitor.h"
#include "protocol/zap.h"
#include "viewer/display_messages.h"
#include "viewer/link_meter.h"

namespace igi {

inline constexpr std::chrono::milliseconds kViewerPing{500};     // either side, when it has nothing else to say
inline constexpr std::chrono::milliseconds kViewerTimeout{3000};  // silent this long: gone

class ViewerPort {
 public:
  // Binds `listen` (throws std::runtime_error naming it when it cannot).
  // `welcome`: what a joining viewer is told (set_welcome() updates it).
  ViewerPort(const std::string& listen, const protocol::CurveServerKeys& keys, display::Welcome welcome, bool quiet);
  ~ViewerPort();
  const std::string& endpoint() const { return endpoint_; }

  // What the viewer said since the last call (waits up to `wait` for the first message).
  struct Incoming {
    bool joined = false;  // a new viewer (the image starts over for it)
    std::optional<display::View> view;  // the latest
    std::vector<display::Request> requests;
  };
  Incoming poll(std::chrono::milliseconds wait);

  bool connected() const { return !viewer_.empty(); }
  // Connected, and fewer than kFramesInFlight frames unacknowledged.
  bool can_send_frame() const;
  // Gives the frame its sequence number; returns the bytes sent (0: the viewer was not reachable).
  size_t send_frame(display::Frame frame);
  void reply(const display::Reply& reply);
  void set_welcome(display::Welcome welcome) { welcome_ = std::move(welcome); }
  // Bye to the viewer (the master is going), given up to `linger_ms` to leave.
  void close(const std::string& reason, int linger_ms);

  uint64_t frames_sent() const { return frames_sent_; }
  // The link to the viewer, as its Acks of the frames sent measure it.
  const LinkMeter& link() const { return link_; }

 private:
  void handle(const std::string& identity, zmq::message_t& payload);
  void on_hello(const std::string& identity, const std::string& key_name, const display::Hello& hello);
  void on_ack(uint64_t frame);
  void drop(const std::string& why);
  bool send(const std::string& identity, const display::Message& message);
  void log(const std::string& text) const;

  bool quiet_;
  display::Welcome welcome_;
  zmq::context_t context_;  // its own: its ZAP handler knows the viewers' keys only
  std::unique_ptr<protocol::ZapHandler> zap_;  // bound before router_
  zmq::socket_t router_;
  std::unique_ptr<protocol::SocketMonitor> monitor_;
  std::string endpoint_;
  std::string viewer_, viewer_name_;  // routing id and key name of the viewer, "" when none
  std::chrono::steady_clock::time_point heard_, said_;
  uint64_t sequence_ = 0, acknowledged_ = 0, frames_sent_ = 0, failed_handshakes_ = 0;
  struct InFlight {
    uint64_t sequence;
    size_t bytes;
    std::chrono::steady_clock::time_point sent;
  };
  std::deque<InFlight> in_flight_;  // at most kFramesInFlight
  LinkMeter link_;
  Incoming incoming_;
};

}  // namespace igi
