#pragma once
// One worker process's whole state: the connection to the master, the scene,
// and the render pool. The socket loop runs on the calling thread and only
// moves messages; finding, hashing, storing and loading the scene and
// rendering run on other threads, so heartbeats keep flowing.
//
// Liveness: the master declares a worker dead after Welcome::timeout_ms of
// silence; the worker waits longer for the master (that timeout plus two
// heartbeats), so the master always gives up first and no worker reconnects
// while the master still counts on it. A closed connection (the master
// process ended) is noticed at once. The worker then reconnects with back-off
// 0.25 s, 1 s, 2 s, ... 32 s and gives up `give_up_seconds` after it last
// heard from a master.
//
// A reconnect keeps the loaded scene and its BVH when the new Welcome names
// the same scene (name and content hash): a master restart costs no reload.
//
// With CURVE keys the DEALER is a CURVE client. A handshake the master turns
// down is reported by the socket monitor, not by a message. A refused key or
// a mechanism mismatch (CURVE on one side only) ends the worker at once
// (Refused); other failed handshakes (a wrong --master-key looks like a
// dropped connection) are retried as a lost master, and giving up says so.
#include <chrono>
#include <functional>
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
#include "scene/load_scene.h"
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
  bool fail_scene_load = false;  // test hook: every scene fails to load
  uint64_t memory_bytes = 0;     // what frames' memory checks assume; 0: this machine's (tests: less)
};

// The process's exit status.
enum class WorkerExit {
  Bye = 0,          // the master said goodbye
  Refused = 3,      // another build or protocol version, an unknown key, CURVE on one side only
  GaveUp = 4,       // no master for give_up_seconds
  Quarantined = 5,  // the master will not use this worker's results (its VPL sets differ from the others')
  SceneFailed = 6,  // the scene the master named does not load here
  RenderFailed = 7, // a frame cannot be rendered here (its settings need more memory than this machine has)
};

class WorkerSession {
 public:
  explicit WorkerSession(WorkerOptions options);
  ~WorkerSession();
  WorkerExit run();

 private:
  enum class Outcome { Bye, Refused, MasterLost, Quarantined, SceneFailed, RenderFailed };
  using Clock = std::chrono::steady_clock;
  struct Loaded;  // scene, BVH, lights, pool
  // What the loading thread found: a loaded scene, or the file the master must send, or why not.
  struct LoadResult {
    std::shared_ptr<Loaded> loaded;
    uint64_t need_hash = 0;  // the scene's or the environment map's
    std::string error;
    bool refused = false;  // bytes from the master that do not match their hash or name
  };
  // The scene and its map (built in, in a search folder or the cache), loaded; or the one to ask for.
  static LoadResult find_and_load(const SceneCache& cache, const protocol::Welcome& welcome, bool fail);
  static LoadResult load(const std::string& scene, const SceneOptions& options, bool fail);

  Outcome serve(zmq::context_t& context);
  void wait_for_work(zmq::socket_t& socket);
  std::optional<Outcome> check_connection(protocol::SocketMonitor& monitor);
  void announce(const std::string& text) const;  // log() even when quiet
  Outcome refused(const std::string& why) const;
  std::string handshake_hint() const;
  std::optional<Outcome> handle(protocol::Message& message);
  void on_welcome(const protocol::Welcome& welcome);
  void start_loading(std::function<LoadResult()> work);
  std::optional<Outcome> poll_loading(zmq::socket_t& socket);
  void start_pool();
  void feed_pool(protocol::Message& message);  // a frame or a job; a frame the pool refuses is a failure
  static std::optional<uint64_t> frame_of(const protocol::Message& message);
  std::optional<Outcome> check_failure(zmq::socket_t& socket);
  void send(zmq::socket_t& socket, const protocol::Message& message);
  void send_results(zmq::socket_t& socket);
  void log(const std::string& text) const;

  WorkerOptions options_;
  std::shared_ptr<const SceneCache> cache_;
  std::optional<protocol::Welcome> welcome_;  // of this connection
  std::future<LoadResult> loading_;
  std::string loading_key_;                  // the scene being loaded (name and hash)
  std::shared_ptr<Loaded> loaded_;           // survives reconnects
  std::string loaded_key_;
  std::vector<protocol::Message> waiting_;   // frames and jobs that came before the scene was ready
  std::string failure_;                      // why a frame was refused here; the session ends with it
  Clock::time_point last_sent_;
  int failed_handshakes_ = 0;  // in a row; reset by a handshake that succeeds
  protocol::SocketEvent last_failure_;  // the last of them, named in the hint
  uint64_t nonfinite_pixels_ = 0, nonfinite_logged_ = 0;
  int loads_ = 0;  // scenes loaded by this process (logged: a reconnect should not add one)
};

}  // namespace igi
