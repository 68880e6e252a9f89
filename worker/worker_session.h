#pragma once
// One worker process's whole state: the connection to the master, the scene,
// and the render pool. The socket loop runs on the calling thread; scene
// loading and rendering run on others, so heartbeats keep flowing.
//
// Liveness: the master is presumed lost after 4 heartbeat intervals of
// silence; the worker then reconnects with back-off 1 s, 2 s, ... 32 s and
// gives up `give_up_seconds` after it last heard from a master.
//
// With CURVE keys the DEALER is a CURVE client. A handshake the master turns
// down is reported by the socket monitor, not by a message. A refused key or
// a mechanism mismatch (CURVE on one side only) ends the worker at once
// (Refused); other failed handshakes (a wrong --master-key looks like a
// dropped connection) are retried as a lost master, and giving up says so.
#include <chrono>
#include <future>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <zmq.hpp>

#include "protocol/curve.h"
#include "protocol/messages.h"
#include "protocol/monitor.h"
#include "render_pool.h"
#include "scene_cache.h"

namespace igi {

struct WorkerOptions {
  std::string endpoint;
  int threads = 0;  // 0: all hardware threads
  std::string cache_dir = "igi-worker-cache";
  std::vector<std::string> search_dirs{"."};
  double give_up_seconds = 60.0;
  std::string build_id;          // empty: this binary's
  std::optional<protocol::CurveClientKeys> curve;  // empty: a plain connection
  bool quiet = false;
};

enum class WorkerExit { Bye = 0, Refused = 3, GaveUp = 4 };

class WorkerSession {
 public:
  explicit WorkerSession(WorkerOptions options);
  ~WorkerSession();
  WorkerExit run();

 private:
  enum class Outcome { Bye, Refused, MasterLost };
  using Clock = std::chrono::steady_clock;
  struct Loaded;  // scene, BVH, lights, pool

  Outcome serve(zmq::context_t& context);
  void wait_for_work(zmq::socket_t& socket);
  std::optional<Outcome> check_handshakes(protocol::SocketMonitor& monitor);
  void announce(const std::string& text) const;  // log() even when quiet
  Outcome refused(const std::string& why) const;
  std::string handshake_hint() const;
  std::optional<Outcome> handle(zmq::socket_t& socket, const protocol::Message& message);
  void on_welcome(zmq::socket_t& socket, const protocol::Welcome& welcome);
  void start_loading(const std::string& scene_path_or_name);
  void poll_loading();
  void send(zmq::socket_t& socket, const protocol::Message& message);
  void log(const std::string& text) const;

  WorkerOptions options_;
  SceneCache cache_;
  std::optional<protocol::Welcome> welcome_;
  std::future<std::shared_ptr<Loaded>> loading_;
  std::shared_ptr<Loaded> loaded_;
  std::vector<protocol::Message> waiting_;  // frames and jobs that came before the scene was ready
  Clock::time_point last_sent_;
  int failed_handshakes_ = 0;  // in a row; reset by a handshake that succeeds
};

}  // namespace igi
