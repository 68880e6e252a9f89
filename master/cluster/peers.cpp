#include "cluster/peers.h"

#include <algorithm>
#include <cstdio>

namespace igi {
namespace {

constexpr int kLinesPerMinute = 100;       // joins and departures logged one by one
constexpr size_t kRememberDropped = 4096;  // dropped peers whose later messages are ignored

}  // namespace

Peers::Peers(int heartbeat_ms, int timeout_ms, bool quiet)
    : heartbeat_(heartbeat_ms), timeout_(timeout_ms), quiet_(quiet) {
  next_sweep_ = last_sweep_ = Clock::now();
}

void Peers::log(const std::string& text) const {
  if (!quiet_) std::fprintf(stderr, "igi-master: %s\n", text.c_str());
}

Peer* Peers::find(const std::string& identity) {
  auto it = peers_.find(identity);
  return it == peers_.end() ? nullptr : &it->second;
}

const Peer* Peers::find(const std::string& identity) const {
  auto it = peers_.find(identity);
  return it == peers_.end() ? nullptr : &it->second;
}

Peer& Peers::join(const std::string& identity, uint32_t threads, const std::string& libraries,
                  const std::string& key_name) {
  Peer& peer = peers_[identity];
  peer.number = uint32_t(next_number_);
  peer.threads = threads;
  peer.sent.clear();
  peer.round_trip_ms = 0.0;
  peer.name = "worker-" + std::to_string(next_number_++);
  peer.last_heard = peer.last_sent = Clock::now();
  peer.gap_count = 0;
  peer.frames_sent.clear();
  peer.failed_results = 0;
  peer.libraries = libraries;
  peer.key_name = key_name;
  return peer;
}

void Peers::drop(const std::string& identity) {
  peers_.erase(identity);
  if (!dropped_.insert(identity).second) return;
  dropped_order_.push_back(identity);
  if (dropped_order_.size() > kRememberDropped) {
    dropped_.erase(dropped_order_.front());
    dropped_order_.pop_front();
  }
}

void Peers::quarantine(const std::string& identity) {
  peers_.erase(identity);
  quarantined_.insert(identity);
}

void Peers::heard(Peer& peer, Clock::time_point now) {
  peer.gaps[peer.gap_count++ % peer.gaps.size()] = std::chrono::duration<float>(now - peer.last_heard).count();
  peer.last_heard = now;
}

// --timeout-ms, or four times the longest of its last 16 silences, at most
// four timeouts. A worker on a loaded machine whose messages come ever later
// gets longer; one that answers steadily, none (its silences stay near a heartbeat).
Peers::Clock::duration Peers::patience(const Peer& peer) const {
  const size_t n = std::min<size_t>(peer.gap_count, peer.gaps.size());
  const float longest = n ? *std::max_element(peer.gaps.begin(), peer.gaps.begin() + long(n)) : 0.0f;
  const auto learned = std::chrono::duration_cast<Clock::duration>(std::chrono::duration<float>(4.0f * longest));
  return std::clamp<Clock::duration>(learned, timeout_, 4 * timeout_);
}

// A few times per heartbeat interval: O(peers), not per message.
Peers::Sweep Peers::sweep(Clock::time_point now) {
  const auto interval = std::clamp(heartbeat_ / 4, std::chrono::milliseconds(5), std::chrono::milliseconds(100));
  // A master that was not listening has its peers' messages still queued: that time is not their silence.
  if (const auto away = now - last_sweep_; away > 2 * interval + heartbeat_) {
    const auto stall = away - interval;
    for (auto& [identity, peer] : peers_) peer.last_heard += stall;
    unlistened_seconds_ += std::chrono::duration<double>(stall).count();
  }
  last_sweep_ = now;
  Sweep sweep;
  for (auto& [identity, peer] : peers_) {
    if (const auto wait = patience(peer); now - peer.last_heard > wait) sweep.dead.emplace_back(identity, wait);
    else if (now - peer.last_sent > heartbeat_) sweep.heartbeat.push_back(identity);
  }
  next_sweep_ = now + interval;
  return sweep;
}

std::string Peers::why_dead(Clock::duration patience) const {
  const long ms = long(std::chrono::duration_cast<std::chrono::milliseconds>(patience).count());
  const long timeout = long(timeout_.count());
  return "silent for " + std::to_string(ms) + " ms" +
         (ms > timeout ? " (four times its longest recent silence; --timeout-ms " + std::to_string(timeout) + ")"
                       : "") +
         ": declared dead, its jobs go to others (a worker on a loaded machine can be this slow to answer: "
         "--timeout-ms gives it longer)";
}

void Peers::note_round_trip(Peer& peer, uint64_t job_id) {
  auto sent = peer.sent.find(job_id);
  if (sent == peer.sent.end()) return;
  const double ms = std::chrono::duration<double, std::milli>(Clock::now() - sent->second).count();
  peer.round_trip_ms = peer.round_trip_ms > 0.0 ? 0.9 * peer.round_trip_ms + 0.1 * ms : ms;
  peer.sent.erase(sent);
}

std::vector<PeerView> Peers::views() const {
  std::vector<PeerView> views;
  const auto now = Clock::now();
  for (const auto& [identity, p] : peers_)
    views.push_back({p.name, p.number, p.threads, std::chrono::duration<double>(now - p.last_heard).count(),
                     p.round_trip_ms});
  std::sort(views.begin(), views.end(), [](const PeerView& a, const PeerView& b) { return a.number < b.number; });
  return views;
}

void Peers::log_join_or_leave(const std::string& text) {
  const Clock::time_point now = Clock::now();
  if (now - log_minute_ >= std::chrono::minutes(1)) {
    flush_log();
    log_minute_ = now;
    lines_ = 0;
  }
  if (lines_++ < kLinesPerMinute) log(text);
  else ++lines_held_;
}

void Peers::flush_log() {
  if (lines_held_ > 0)
    log(std::to_string(lines_held_) + " more joins and departures in the last minute, not logged one by one");
  lines_held_ = 0;
}

}  // namespace igi
