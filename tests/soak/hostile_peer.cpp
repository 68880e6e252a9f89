#include "hostile_peer.h"

#include <chrono>
#include <memory>
#include <thread>
#include <vector>

#include <zmq.hpp>

#include "build_id.h"
#include "protocol/socket.h"

namespace igi::soak {
namespace {

using Clock = std::chrono::steady_clock;
constexpr uint64_t kMadeUpHash = 0x5eed5eed5eed5eedull;

std::unique_ptr<zmq::socket_t> join(zmq::context_t& context, const std::string& endpoint, uint32_t threads) {
  auto socket = std::make_unique<zmq::socket_t>(context, zmq::socket_type::dealer);
  socket->set(zmq::sockopt::linger, 0);
  protocol::connect(*socket, endpoint);
  protocol::send(*socket, protocol::Hello{igi::build_id(), "hostile", threads});
  return socket;
}

// The reply a sybil or a failer sends for a job.
protocol::TileResult answer(HostileKind kind, const protocol::TileJobMsg& job) {
  protocol::TileResult r;
  r.frame_id = job.frame_id;
  r.job_id = job.job_id;
  r.tile = job.tile;
  if (kind == HostileKind::Failer) r.tile.w = std::max(1, job.tile.w - 1);  // not its job's rectangle
  r.pixels.assign(size_t(r.tile.w) * r.tile.h, glm::vec3(0.25f));
  r.frame_state_hash = kMadeUpHash;
  r.render_seconds = 0.001f;
  return r;
}

void ghosts(const std::string& endpoint, double seconds, HostileReport& report) {
  zmq::context_t context;
  const auto end = Clock::now() + std::chrono::duration<double>(seconds);
  while (Clock::now() < end) {
    auto socket = join(context, endpoint, 32);
    socket->set(zmq::sockopt::linger, 200);  // the hello leaves, then the connection closes
    ++report.connections;
    socket.reset();
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
}

}  // namespace

const char* hostile_name(HostileKind kind) {
  switch (kind) {
    case HostileKind::Sybil: return "sybil pair";
    case HostileKind::Hoarder: return "hoarder";
    case HostileKind::Failer: return "failer";
    case HostileKind::Ghosts: return "ghosts";
  }
  return "?";
}

HostileReport run_hostile(const std::string& endpoint, HostileKind kind, double seconds) {
  HostileReport report;
  report.kind = kind;
  if (kind == HostileKind::Ghosts) {
    ghosts(endpoint, seconds, report);
    return report;
  }
  zmq::context_t context;
  std::vector<std::unique_ptr<zmq::socket_t>> peers;
  for (int i = 0; i < (kind == HostileKind::Sybil ? 2 : 1); ++i) peers.push_back(join(context, endpoint, 32));
  report.connections = int(peers.size());
  std::vector<bool> gone(peers.size(), false);
  const auto end = Clock::now() + std::chrono::duration<double>(seconds);
  auto next_heartbeat = Clock::now();
  while (Clock::now() < end) {
    const bool beat = Clock::now() >= next_heartbeat;
    if (beat) next_heartbeat = Clock::now() + std::chrono::milliseconds(100);
    for (size_t i = 0; i < peers.size(); ++i) {
      if (gone[i]) continue;
      zmq::socket_t& socket = *peers[i];
      if (beat) protocol::try_send(socket, protocol::Heartbeat{});  // alive: only what it does can betray it
      while (auto received = protocol::receive(socket, 0, false)) {
        if (!received->message) continue;
        if (auto* bye = std::get_if<protocol::Bye>(&*received->message)) {
          if (bye->kind == protocol::ByeKind::Quarantined) ++report.quarantined;
          gone[i] = true;
          break;
        }
        auto* job = std::get_if<protocol::TileJobMsg>(&*received->message);
        if (!job) continue;
        ++report.jobs_taken;
        if (kind == HostileKind::Hoarder) continue;
        if (protocol::try_send(socket, answer(kind, *job))) ++report.results_sent;
      }
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  return report;
}

}  // namespace igi::soak
