#pragma once
// A TCP relay between the network namespace's worker and the master: it
// listens on the veth address and forwards each connection to the master's
// loopback port. The master stays on 127.0.0.1 (a non-loopback --listen
// needs CURVE keys), while the worker's path still crosses the veth link
// that the soak run cuts. A write that would block (the link is down and the
// kernel's buffer is full) drops that connection, as a broken link would.
#include <atomic>
#include <string>
#include <thread>

namespace igi::soak {

class TcpRelay {
 public:
  // Throws std::runtime_error naming the address when it cannot listen.
  TcpRelay(const std::string& listen_host, const std::string& target_host, int target_port);
  ~TcpRelay();
  TcpRelay(const TcpRelay&) = delete;
  TcpRelay& operator=(const TcpRelay&) = delete;
  int port() const { return port_; }

 private:
  void run();
  int listen_fd_ = -1;
  int port_ = 0;
  std::string target_host_;
  int target_port_;
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

}  // namespace igi::soak
