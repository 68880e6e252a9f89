#pragma once
// The workers behind the master's socket, by ZeroMQ identity: their names
// and numbers, when each was last heard from, and how long each may be
// silent before it is declared dead (its patience); peers dropped lately,
// whose backlog is then not "bad"; and the log of joins and departures,
// which a churn of ghost connections must not flood.
//
// Liveness: a peer silent past its patience is dead; one not sent anything
// for a heartbeat gets a Heartbeat. The patience follows the peer's measured
// silences: four times the longest of its last 16 gaps between messages, at
// least the timeout, at most four times it. Time the master itself was not
// listening (its process stopped or descheduled, a caller that did not pump)
// is nobody's silence: their messages are queued, not lost.
#include <array>
#include <chrono>
#include <cstdint>
#include <deque>
#include <map>
#include <set>
#include <string>
#include <utility>
#include <vector>

namespace igi {

struct Peer {
  using Clock = std::chrono::steady_clock;
  std::string name;  // "worker-N"
  Clock::time_point last_heard, last_sent;
  // Its last few silences between messages (seconds), for its patience.
  std::array<float, 16> gaps{};
  uint32_t gap_count = 0;
  std::set<uint64_t> frames_sent;  // open frames whose setup it has
  int failed_results = 0;
  uint32_t number = 0, threads = 0, credits = 0;
  std::map<uint64_t, Clock::time_point> sent;  // job id -> when (detailed statistics only)
  double round_trip_ms = 0.0;
  std::string libraries;  // as its Hello said (scene/libraries.h)
  std::string key_name;   // its CURVE key's name (the ZAP handler's User-Id); empty without CURVE
};

// A worker as the window's cluster panel shows it.
struct PeerView {
  std::string name;            // "worker-N"
  uint32_t number = 0;         // N
  uint32_t threads = 0;        // as its Hello said
  double since_heard_s = 0.0;  // since its last message (heartbeat or result)
  double round_trip_ms = 0.0;  // job sent to result back, smoothed; 0 before any (detailed statistics only)
};

class Peers {
 public:
  using Clock = Peer::Clock;
  Peers(int heartbeat_ms, int timeout_ms, bool quiet);

  Peer* find(const std::string& identity);
  const Peer* find(const std::string& identity) const;
  bool known(const std::string& identity) const { return peers_.count(identity) > 0; }
  size_t size() const { return peers_.size(); }
  std::map<std::string, Peer>& all() { return peers_; }
  const std::map<std::string, Peer>& all() const { return peers_; }
  // A Hello on a connection: a peer with a fresh number and name (a known one is reset).
  Peer& join(const std::string& identity, uint32_t threads, const std::string& libraries, const std::string& key_name);
  // Forgets the peer: drop() remembers it as dropped (what it still sends is
  // stale, not bad, until it says hello again), quarantine() as quarantined
  // (everything it sends is ignored), erase() not at all.
  void drop(const std::string& identity);
  void quarantine(const std::string& identity);
  void erase(const std::string& identity) { peers_.erase(identity); }
  void clear() { peers_.clear(); }
  bool quarantined(const std::string& identity) const { return quarantined_.count(identity) > 0; }
  bool dropped(const std::string& identity) const { return !known(identity) && dropped_.count(identity) > 0; }

  static void heard(Peer& peer, Clock::time_point now);
  // How long the peer may be silent before it is declared dead.
  Clock::duration patience(const Peer& peer) const;
  // Due every sweep_interval(): the peers declared dead now (with the
  // patience they had), and those to send a heartbeat to.
  struct Sweep {
    std::vector<std::pair<std::string, Clock::duration>> dead;
    std::vector<std::string> heartbeat;
  };
  Sweep sweep(Clock::time_point now);
  Clock::time_point next_sweep() const { return next_sweep_; }
  double unlistened_seconds() const { return unlistened_seconds_; }  // stalls: not counted as silence
  // "silent for 1500 ms: declared dead, ...": why a dead peer was dropped.
  std::string why_dead(Clock::duration patience) const;

  // Smoothed over about ten results: what the cluster panel shows.
  static void note_round_trip(Peer& peer, uint64_t job_id);
  std::vector<PeerView> views() const;
  // A join or a departure: a line each, up to 100 a minute; the rest are
  // counted, and summed up in a line when the minute ends or at flush_log().
  void log_join_or_leave(const std::string& text);
  void flush_log();

 private:
  void log(const std::string& text) const;

  const std::chrono::milliseconds heartbeat_, timeout_;
  const bool quiet_;
  std::map<std::string, Peer> peers_;
  std::set<std::string> quarantined_;  // their later messages are ignored
  // Peers dropped lately (dead, gone, congested): what they still send (a
  // stopped worker's backlog when it resumes) is ignored, not counted as bad,
  // until they say hello again. At most kRememberDropped, oldest forgotten first.
  std::set<std::string> dropped_;
  std::deque<std::string> dropped_order_;
  uint64_t next_number_ = 0;
  Clock::time_point next_sweep_, last_sweep_;
  double unlistened_seconds_ = 0.0;
  Clock::time_point log_minute_{};
  int lines_ = 0;
  uint64_t lines_held_ = 0;
};

}  // namespace igi
