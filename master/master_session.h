#pragma once
// The master's side of a cluster session: one ROUTER socket, the peers behind
// it, the scheduler, and the frames being assembled. Single-threaded: every
// call below runs on the thread that owns the socket.
//
// Reliability lives here and only here: heartbeats both ways, a peer silent
// for timeout_ms is dead and its jobs are issued again, the first result for
// a job wins, and a frame is complete only when every job id is back.
//
// With CURVE keys the ROUTER is a CURVE server and the session answers
// libzmq's ZAP requests itself (in pump(), no thread): only authorised worker
// keys complete a handshake; others are logged and counted.
#include <chrono>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include <zmq.hpp>

#include "image/image.h"
#include "master_options.h"
#include "protocol/curve.h"
#include "protocol/messages.h"
#include "protocol/monitor.h"
#include "protocol/zap.h"
#include "scheduler.h"

namespace igi {

// What workers are told about the scene, and its bytes for those without it.
struct SceneSource {
  std::string name;        // built-in name or file name
  uint64_t hash = 0;       // 0 for built-in scenes
  std::vector<uint8_t> bytes;
};

struct PeerStats {
  uint64_t tiles = 0;
  double busy_seconds = 0.0;
  uint64_t bytes_in = 0, bytes_out = 0;
};

struct FrameRecord {
  uint64_t frame_id = 0;
  double seconds = 0.0;  // from its first job out to its last result in
  uint64_t tiles = 0;
  RayCounts rays;
  std::map<std::string, PeerStats> workers;  // by peer name
  uint64_t reissued = 0, duplicated = 0, late_dropped = 0;
};

struct CompletedFrame {
  FrameSetup setup;
  Image image;
  FrameRecord record;
};

class MasterSession {
 public:
  // `curve`: null for a plain socket. Binds options.listen; throws zmq::error_t when it cannot.
  MasterSession(const MasterOptions& options, SceneSource scene, zmq::context_t& context,
                const protocol::CurveServerKeys* curve = nullptr);
  std::string endpoint() const { return endpoint_; }

  // Queues a frame; jobs go out as workers have credit (at most two frames open).
  bool can_add_frame() const { return scheduler_.can_add_frame(); }
  void add_frame(const FrameSetup& frame);
  // Runs the loop for up to timeout_ms; returns the frames completed meanwhile, in order.
  std::vector<CompletedFrame> pump(int timeout_ms);
  // Tells every worker goodbye.
  void close(const std::string& reason);

  size_t worker_count() const { return scheduler_.worker_count(); }
  uint64_t bad_messages() const { return bad_messages_; }
  uint64_t refused_keys() const { return refused_keys_; }              // CURVE keys the ZAP handler refused
  uint64_t failed_handshakes() const { return failed_handshakes_; }    // peers without CURVE or the right master key
  // Called with every accepted result (test hooks, progress).
  std::function<void(uint64_t accepted)> on_accepted;

 private:
  using Clock = std::chrono::steady_clock;
  struct Peer {
    std::string name;
    Clock::time_point last_heard, last_sent;
    std::set<uint64_t> frames_sent;
  };
  struct OpenFrame {
    FrameSetup setup;
    Image image;
    FrameRecord record;
    std::optional<Clock::time_point> started;
  };

  void wait_for_traffic(int timeout_ms);
  void serve_security();
  void on_zap_decision(const protocol::ZapDecision& decision);
  void handle(const std::string& identity, const protocol::Message& message, size_t bytes);
  void on_hello(const std::string& identity, const protocol::Hello& hello);
  void on_result(const std::string& identity, protocol::TileResult& result);
  void on_bad_message(const std::string& identity, const std::string& error);
  void drop_peer(const std::string& identity, const std::string& why);
  void check_liveness();
  void assign_jobs();
  void send_heartbeats();
  std::vector<CompletedFrame> take_completed();
  void send(const std::string& identity, const protocol::Message& message);
  void log(const std::string& text) const;

  MasterOptions options_;
  SceneSource scene_;
  std::unique_ptr<protocol::ZapHandler> zap_;  // bound before router_, or CURVE would let every key in
  zmq::socket_t router_;
  std::unique_ptr<protocol::SocketMonitor> monitor_;  // after router_: it watches it
  std::string endpoint_;
  Scheduler scheduler_;
  std::map<std::string, Peer> peers_;
  std::map<uint64_t, OpenFrame> frames_;
  uint64_t accepted_ = 0;
  uint64_t bad_messages_ = 0;
  uint64_t refused_keys_ = 0, failed_handshakes_ = 0;
  std::set<std::string> refused_logged_;  // each refused key is logged once
  uint64_t next_peer_ = 0;
  uint64_t session_id_;
};

}  // namespace igi
