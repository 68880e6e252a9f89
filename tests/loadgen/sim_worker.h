#pragma once
// A simulated igi-worker: a real DEALER socket speaking the real protocol,
// answering each TileJob with a pre-rendered tile after a set render time.
// It joins, stalls, dies and misbehaves on a schedule (SimBehaviour), so the
// master's limits and faults can be measured with hundreds of workers on one
// machine. Single-threaded: a SimPool's thread drives it.
#include <chrono>
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <zmq.hpp>

#include "protocol/curve.h"
#include "protocol/messages.h"
#include "tile_cache.h"

namespace igi::loadgen {

using Clock = std::chrono::steady_clock;

struct SimBehaviour {
  double tile_seconds = 0.0;   // render time of one tile (0: answer at once)
  int threads = 1;             // tiles rendered at once; Hello says so (the master grants 2 credits a thread)
  double join_at = 0.0;        // seconds after the start
  double die_at = -1.0;        // the socket closes without a word, as a killed process's does
  double rejoin_after = -1.0;  // after dying: a replacement joins this much later (< 0: none)
  double stall_from = -1.0, stall_until = -1.0;  // reads and sends nothing meanwhile (SIGSTOP)
  uint64_t hash_offset = 0;    // not 0: its VPL sets differ from everyone else's
  int nan_every = 0;           // every n-th answer has a NaN pixel (0: never)
  int wrong_tile_every = 0;    // every n-th answer claims another rectangle (0: never)
  int truncate_every = 0;      // every n-th answer loses its last bytes (it does not decode)
  std::optional<std::pair<int, int>> poison_pixel;  // the tile holding this pixel always has a NaN
  bool hoard = false;          // takes jobs and heartbeats, never answers
  std::string key_file;        // its own CURVE secret key file (a run over CURVE); empty: the run's key
  // Once welcomed, this many results a second for jobs never issued, each a
  // decompression bomb (TileCache::bomb(): under 1 KB that unpack to a
  // 1024 x 1024 float tile with surfaces); 0: none.
  double flood_per_second = 0.0;
};

// Where a simulated worker connects, and with which CURVE keys (none: plain).
struct SimConnection {
  std::string endpoint;
  std::optional<protocol::CurveClientKeys> curve;
};

struct SimOutcome {
  bool welcomed = false;
  bool quarantined = false;    // the master said Bye (Quarantined)
  bool said_bye = false;       // the master said Bye (done)
  bool refused = false;
  int connections = 0;         // Hellos sent (reconnects after stalls, replacements)
  uint64_t answers = 0;
  std::string last_bye;
  uint64_t flooded = 0;          // flood messages sent
  double first_flood_at = -1.0;  // seconds after the start
  double quarantined_at = -1.0;  // seconds after the start: when the master's Bye (Quarantined) came
};

class SimWorker {
 public:
  SimWorker(zmq::context_t& context, SimConnection connection, SimBehaviour behaviour, TileCache& tiles,
            Clock::time_point start);
  // The socket to poll, or null while not connected (not joined yet, dead, stalled or done).
  zmq::socket_t* socket(Clock::time_point now);
  void on_readable(Clock::time_point now);
  // Joins, dies, sends due answers and heartbeats; returns when it next needs a tick.
  Clock::time_point tick(Clock::time_point now);
  bool finished() const { return finished_; }
  const SimOutcome& outcome() const { return outcome_; }

 private:
  struct Due {
    Clock::time_point at;
    uint64_t frame_id, job_id;
    TileJob tile;
  };
  double since_start(Clock::time_point now) const;
  bool stalled(Clock::time_point now) const;
  void connect(Clock::time_point now);
  void disconnect();
  void handle(const protocol::Message& m, Clock::time_point now);
  void take_job(const protocol::TileJobMsg& job, Clock::time_point now);
  void send_answer(const Due& due);
  Clock::time_point flood(Clock::time_point now);  // sends what is due; returns when the next is
  void send(const protocol::Message& m, Clock::time_point now);

  zmq::context_t& context_;
  SimConnection connection_;
  SimBehaviour behaviour_;
  TileCache& tiles_;
  Clock::time_point start_;
  std::unique_ptr<zmq::socket_t> socket_;
  std::optional<protocol::Welcome> welcome_;
  std::map<uint64_t, protocol::FrameSetupMsg> frames_;  // the newest few
  std::vector<Due> due_;
  std::vector<Clock::time_point> lanes_;   // when each "thread" is free
  Clock::time_point last_sent_, last_heard_;
  bool dead_ = false, finished_ = false;
  std::optional<Clock::time_point> rejoin_at_;
  std::optional<Clock::time_point> next_flood_;
  uint64_t answers_ = 0;
  SimOutcome outcome_;
};

}  // namespace igi::loadgen
