#include "tcp_relay.h"

#include <arpa/inet.h>
#include <map>
#include <netinet/in.h>
#include <poll.h>
#include <stdexcept>
#include <sys/socket.h>
#include <unistd.h>
#include <vector>

namespace igi::soak {
namespace {

sockaddr_in address_of(const std::string& host, int port) {
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_port = htons(uint16_t(port));
  if (inet_pton(AF_INET, host.c_str(), &a.sin_addr) != 1) throw std::runtime_error(host + ": not an IPv4 address");
  return a;
}

// Moves what `from` has to `to`; false when the pair should close.
bool forward(int from, int to) {
  char buffer[65536];
  const ssize_t n = ::recv(from, buffer, sizeof buffer, MSG_DONTWAIT);
  if (n == 0 || (n < 0 && errno != EAGAIN && errno != EINTR)) return false;
  for (ssize_t sent = 0; n > 0 && sent < n;) {
    const ssize_t m = ::send(to, buffer + sent, size_t(n - sent), MSG_DONTWAIT | MSG_NOSIGNAL);
    if (m <= 0) return false;  // would block or failed: the link is as good as broken
    sent += m;
  }
  return true;
}

}  // namespace

TcpRelay::TcpRelay(const std::string& listen_host, const std::string& target_host, int target_port)
    : target_host_(target_host), target_port_(target_port) {
  listen_fd_ = socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
  const int one = 1;
  setsockopt(listen_fd_, SOL_SOCKET, SO_REUSEADDR, &one, sizeof one);
  sockaddr_in a = address_of(listen_host, 0);
  socklen_t length = sizeof a;
  if (bind(listen_fd_, reinterpret_cast<sockaddr*>(&a), sizeof a) != 0 || listen(listen_fd_, 16) != 0 ||
      getsockname(listen_fd_, reinterpret_cast<sockaddr*>(&a), &length) != 0) {
    close(listen_fd_);
    throw std::runtime_error("relay: cannot listen on " + listen_host);
  }
  port_ = ntohs(a.sin_port);
  thread_ = std::thread([this] { run(); });
}

TcpRelay::~TcpRelay() {
  stop_ = true;
  thread_.join();
  close(listen_fd_);
}

void TcpRelay::run() {
  std::map<int, int> peer;  // each end of a relayed connection -> the other end
  const sockaddr_in target = address_of(target_host_, target_port_);
  while (!stop_) {
    std::vector<pollfd> fds{{listen_fd_, POLLIN, 0}};
    for (const auto& [fd, other] : peer) fds.push_back({fd, POLLIN, 0});
    if (poll(fds.data(), fds.size(), 20) <= 0) continue;
    std::vector<int> closing;
    for (const pollfd& p : fds) {
      if (!(p.revents & (POLLIN | POLLHUP | POLLERR))) continue;
      if (p.fd == listen_fd_) {
        const int client = accept4(listen_fd_, nullptr, nullptr, SOCK_CLOEXEC);
        const int server = socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
        if (client >= 0 && server >= 0 && connect(server, reinterpret_cast<const sockaddr*>(&target), sizeof target) == 0) {
          peer[client] = server;
          peer[server] = client;
        } else {
          if (client >= 0) close(client);
          if (server >= 0) close(server);
        }
      } else if (peer.count(p.fd) && !forward(p.fd, peer[p.fd])) {
        closing.push_back(p.fd);
      }
    }
    for (int fd : closing) {
      if (!peer.count(fd)) continue;
      const int other = peer[fd];
      close(fd);
      close(other);
      peer.erase(fd);
      peer.erase(other);
    }
  }
  for (const auto& [fd, other] : peer) close(fd);
}

}  // namespace igi::soak
