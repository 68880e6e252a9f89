#pragma once
// The viewer's end of the display link (igi-view --connect): a DEALER with
// CURVE (the viewer's own key pair, the master's public key). Every way the
// link can fail ends in a ViewerError whose message says what happened and
// what to do: the master refused the key, refused a second viewer, spoke
// another version, said Bye, went silent for kViewerTimeout, or never
// answered. Single-threaded: the window's thread owns it.
#include <chrono>
#include <optional>
#include <stdexcept>
#include <string>

#include <zmq.hpp>

#include "protocol/curve.h"
#include "protocol/monitor.h"
#include "viewer/display_messages.h"

namespace igi {

struct ViewerError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

class ViewerClient {
 public:
  // Connects (nothing is sent yet). Throws std::runtime_error for a malformed endpoint.
  ViewerClient(const std::string& endpoint, const protocol::CurveClientKeys& keys);
  ~ViewerClient();
  // Says Hello and waits up to `patience` for the Welcome.
  display::Welcome join(std::chrono::milliseconds patience);
  // The next Frame or Reply, waiting up to `wait`; nullopt when none came.
  // Pings the master when the viewer has said nothing for a while.
  std::optional<display::Message> receive(std::chrono::milliseconds wait);
  void send(const display::Message& message);
  // Bye (the window closed), given a moment to leave.
  void close(const std::string& reason);
  uint64_t bytes_received() const { return bytes_received_; }

 private:
  void check_connection();
  std::string silent_hint(std::chrono::milliseconds waited) const;

  std::string endpoint_;
  bool curve_mismatch_ = false, welcomed_ = false;
  int failed_handshakes_ = 0;
  zmq::context_t context_;
  zmq::socket_t socket_;
  protocol::SocketMonitor monitor_;
  std::chrono::steady_clock::time_point heard_, said_;
  uint64_t bytes_received_ = 0;
};

}  // namespace igi
