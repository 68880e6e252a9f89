#pragma once
// The master's side of a cluster session: one ROUTER socket, the peers behind
// it, the scheduler, and the frames being assembled. Single-threaded: every
// call below runs on the thread that owns the socket (the session thread);
// nothing here writes files or draws, so that thread only moves messages.
//
// Reliability lives here and only here: heartbeats both ways, a peer silent
// for timeout_ms is dead and its jobs are issued again, a result is checked
// against the scheduler's own job before its pixels are used, a result that
// fails validation sends its job to another worker (one that failed on every
// worker that could take it, or on two, the master renders itself: no
// failing peer can end the run), a worker whose VPL sets
// differ from the master's own (judge_by()) or, without it, lose the vote is
// quarantined (told so: it exits with status 5), and a frame is complete only
// when every job id is back and its hash is decided.
// Sends never block: a peer whose queue is full (it stopped reading) is
// dropped like a dead one.
//
// The loop sleeps in poll() until a message arrives or a timer is due (the
// liveness sweep, a straggler becoming late): no busy waiting. Results are
// decoded in place and their pixels copied straight from the ZeroMQ frame
// into the frame buffer, in the session's pixel format.
//
// With CURVE keys the ROUTER is a CURVE server and the session answers
// libzmq's ZAP requests itself (in pump(), no thread): only authorised worker
// keys complete a handshake; others are logged and counted.
#include <array>
#include <chrono>
#include <functional>
#include <deque>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <stdexcept>
#include <string>
#include <tuple>
#include <vector>

#include <zmq.hpp>

#include "frames/frame_buffer_pool.h"
#include "options/master_options.h"
#include "protocol/codec.h"
#include "protocol/curve.h"
#include "protocol/messages.h"
#include "protocol/monitor.h"
#include "protocol/zap.h"
#include "trust/master_renderer.h"
#include "scheduler/scheduler.h"

namespace igi {

// What workers are told about the scene, and its bytes for those without it:
// encoded once as a SceneData message and sent without a copy.
struct SceneSource {
  std::string name;        // built-in name or file name
  uint64_t hash = 0;       // 0 for built-in scenes
  uint64_t size = 0;       // bytes of the file
  std::shared_ptr<const std::vector<uint8_t>> message;  // the encoded SceneData; null for built-in scenes
  glm::vec3 environment{0.0f};  // the sky the master's scene stands under (Welcome carries it)
  // Its map, when it has one: workers ask for it by hash as for the scene.
  std::string map_name;
  uint64_t map_hash = 0, map_size = 0;
  float map_rotation = 0.0f;
  std::shared_ptr<const std::vector<uint8_t>> map_message;  // the encoded SceneData
  LightUnits light_units = LightUnits::Photometric;  // how the file's lamps are read (Welcome carries it)
};
// Reads a scene file (or names a built-in scene) and encodes what workers may ask for.
SceneSource make_scene_source(const std::string& scene);
// Reads the environment map `path` into `source`, for workers to ask for.
void add_environment_map(SceneSource& source, const std::string& path, float rotation);

struct PeerStats {
  uint64_t tiles = 0;
  double busy_seconds = 0.0;
  uint64_t bytes_in = 0, bytes_out = 0;
};

// Which worker's result filled a tile (the window's tile overlay).
struct TileSource {
  TileJob tile;
  uint32_t worker = 0;  // the N of its peer name "worker-N"
};

struct FrameRecord {
  uint64_t frame_id = 0;
  double seconds = 0.0;  // from its first job out to its last result in
  double completed_at = 0.0;  // seconds from the session's start to its last result (frames overlap: rates from these)
  uint64_t tiles = 0;    // results whose pixels were used
  RayCounts rays;
  uint64_t nonfinite_pixels = 0;  // zeroed by workers (they send finite pixels only)
  std::map<std::string, PeerStats> workers;  // by peer name; only with detailed statistics
  std::vector<TileSource> tile_sources;      // one per used result; only with record_tile_sources()
  // Session totals when the frame completed.
  uint64_t reissued = 0, duplicated = 0, late_dropped = 0, verified = 0, failed_results = 0, quarantined = 0;
  uint64_t own_tiles = 0;  // jobs the master rendered itself
};

struct CompletedFrame {
  FrameSetup setup;
  std::shared_ptr<FrameBuffer> pixels;  // back to the session's pool when the last copy goes
  FrameRecord record;
  std::vector<PixelSurface> surfaces;  // one a pixel when setup.want_surfaces, else none
};

// A worker as the window's cluster panel shows it.
struct PeerView {
  std::string name;            // "worker-N"
  uint32_t number = 0;         // N
  uint32_t threads = 0;        // as its Hello said
  double since_heard_s = 0.0;  // since its last message (heartbeat or result)
  double round_trip_ms = 0.0;  // job sent to result back, smoothed; 0 before any (detailed statistics only)
};

// The run cannot go on (a job failed validation on every worker that could
// take it, and the master could not render it either); what() says which and why.
struct SessionError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

class MasterSession {
 public:
  // `curve`: null for a plain socket. Binds options.listen; throws zmq::error_t when it cannot.
  MasterSession(const MasterOptions& options, SceneSource scene, zmq::context_t& context,
                const protocol::CurveServerKeys* curve = nullptr);
  std::string endpoint() const { return endpoint_; }
  PixelFormat pixel_format() const { return pixel_format_; }
  const std::string& pixel_codec() const { return options_.pixel_codec; }  // what workers are asked to send

  // Judges every worker's VPL sets against the master's own, computed from
  // `scene` as the workers load it (master_renderer.h), instead of by a vote
  // among workers; and lets the master render a job no worker's result for
  // passed validation. Before the first frame.
  void judge_by(Scene scene);
  // Queues a frame; jobs go out as workers have credit (at most two frames open).
  // Its settings travel with its FrameSetup (default: the options').
  bool can_add_frame() const { return scheduler_.can_add_frame(); }
  void add_frame(const FrameSetup& frame);
  void add_frame(const FrameSetup& frame, const RenderSettings& settings);
  // A frame to come with the options' settings (a headless run knows its
  // camera path): the master computes its VPL-set hash now, so that when the
  // frame is added its workers' results need not wait for it.
  void expect_frame(const FrameSetup& frame);
  // The view moved on: the frame is dropped and every worker that holds a
  // job of it is told to drop its queued ones (CancelFrame); their credit
  // comes back at once. The frame never completes.
  void cancel_frame(uint64_t frame_id);
  std::vector<uint64_t> open_frames() const;  // oldest first
  // Per-worker figures in each FrameRecord (on with --stats; the window turns them on).
  void set_detailed_stats(bool on) { detailed_stats_ = on; }
  // Which worker filled each tile, in each FrameRecord (the window's tile overlay).
  void record_tile_sources(bool on) { tile_sources_ = on; }
  std::vector<PeerView> peer_views() const;
  // Runs the loop for up to timeout_ms; returns the frames completed meanwhile, in order.
  // Throws SessionError when a frame can never complete.
  std::vector<CompletedFrame> pump(int timeout_ms);
  // Tells every worker goodbye.
  void close(const std::string& reason);

  size_t worker_count() const { return scheduler_.worker_count(); }
  uint64_t bad_messages() const { return bad_messages_; }
  // The last worker that could not go on (a Bye saying why: its scene does not
  // load, a frame does not fit), "" when none did; and when.
  const std::string& last_worker_failure() const { return last_failure_; }
  std::chrono::steady_clock::time_point last_worker_failure_time() const { return last_failure_at_; }
  // Messages from peers dropped lately that had not said hello again (ignored, not bad).
  uint64_t stale_messages() const { return stale_messages_; }
  uint64_t refused_keys() const { return refused_keys_; }              // CURVE keys the ZAP handler refused
  uint64_t failed_handshakes() const { return failed_handshakes_; }    // peers without CURVE or the right master key
  uint64_t declared_dead() const { return declared_dead_; }            // workers silent past the timeout, or not reading
  double unlistened_seconds() const { return unlistened_seconds_; }   // stalls: not counted as workers' silence
  uint64_t nonfinite_pixels() const { return nonfinite_pixels_; }
  uint64_t own_tiles() const { return own_tiles_; }  // jobs the master rendered itself (no worker's result passed)
  uint64_t benched() const { return scheduler_.stats().benched; }  // hoarders given no jobs until they answer
  // The master's VPL sets lost to its authenticated workers', which agreed: votes decide from then on.
  bool follows_workers() const { return follows_workers_; }
  // The master's own VPL-set hashes: frames computed and the time its thread spent on them.
  uint64_t reference_frames() const { return reference_frames_; }
  double reference_seconds() const { return reference_seconds_; }
  uint64_t quarantined_count() const { return quarantined_count_; }  // workers quarantined, for any reason
  const SchedulerStats& scheduler_stats() const { return scheduler_.stats(); }
  const std::vector<std::string>& quarantined() const { return quarantined_names_; }  // "worker-3: why"
  // Why no frame can complete now, when that is so (two workers disagree on a
  // frame's VPL sets and no third breaks the tie); empty otherwise.
  std::string stall() const;
  double session_cpu_seconds() const { return session_cpu_; }  // this thread's CPU inside pump()
  // Called with every accepted result (test hooks, progress).
  std::function<void(uint64_t accepted)> on_accepted;

 private:
  using Clock = std::chrono::steady_clock;
  struct Peer {
    std::string name;
    Clock::time_point last_heard, last_sent;
    // Its last few silences between messages (seconds), for its patience().
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
  struct OpenFrame {
    FrameSetup setup;
    RenderSettings settings;
    std::shared_ptr<FrameBuffer> pixels;
    FrameRecord record;
    std::vector<PixelSurface> surfaces;
    std::optional<Clock::time_point> started;
  };

  void add_frame(const FrameSetup& frame, const RenderSettings& settings, bool request_hash);
  static void heard(Peer& peer, Clock::time_point now);
  Clock::duration patience(const Peer& peer) const;
  void step(Clock::time_point now, std::vector<CompletedFrame>& done);
  void wait_for_traffic(Clock::time_point until);
  void serve_security();
  void receive_batch();
  void on_frame(const std::string& identity, std::span<const uint8_t> payload);
  void on_zap_decision(const protocol::ZapDecision& decision);
  void handle(const std::string& identity, const protocol::Message& message);
  void on_hello(const std::string& identity, const protocol::Hello& hello);
  protocol::Welcome welcome(uint32_t credits) const;  // what a joining peer is told
  void on_result(const std::string& identity, std::span<const uint8_t> bytes);
  void note_round_trip(Peer& peer, uint64_t job_id);
  void use_result(const std::string& identity, Peer& peer, const protocol::TileResultView& view, size_t bytes);
  void on_bad_result(const std::string& identity, uint64_t job_id, const std::string& error);
  void on_bad_message(const std::string& identity, const std::string& error);
  void drop_peer(const std::string& identity, const std::string& why);
  void quarantine_peer(const std::string& identity, const std::string& why);
  void take_quarantined();
  void take_references();
  void render_own_jobs();
  void on_dispute(const HashDispute& dispute);
  void count_failures_against_workers(uint64_t job_id);
  void use_own_result(const MasterRenderer::TileAnswer& answer);
  void sweep(Clock::time_point now);
  void dispatch(const std::vector<JobAssignment>& jobs);
  void report_stall();
  std::vector<CompletedFrame> take_completed();
  // Bytes queued, or 0 when the peer is gone or its queue is full (it is then dropped).
  size_t send(const std::string& identity, const protocol::Message& message);
  size_t send_frame(const std::string& identity, zmq::message_t&& payload);
  void log(const std::string& text) const;
  // A join or a departure: a line each, up to kPeerLinesPerMinute a minute (a
  // churn of ghosts must not flood the log); the rest are counted, and
  // summed up in a line when the minute ends. Quarantines are always logged.
  void log_peer(const std::string& text);
  void forget_peer(const std::string& identity);  // remembered as dropped: its backlog is not "bad"

  MasterOptions options_;
  SceneSource scene_;
  PixelFormat pixel_format_;
  bool detailed_stats_;
  bool tile_sources_ = false;
  std::unique_ptr<protocol::ZapHandler> zap_;  // bound before router_, or CURVE would let every key in
  zmq::socket_t router_;
  std::unique_ptr<protocol::SocketMonitor> monitor_;  // after router_: it watches it
  std::string endpoint_;
  Scheduler scheduler_;
  std::unique_ptr<MasterRenderer> referee_;  // the master's own frame hashes and tiles; null: workers vote
  FrameBufferPool pool_;
  std::map<std::string, Peer> peers_;
  std::set<std::string> quarantined_ids_;        // their later messages are ignored
  // Peers dropped lately (dead, gone, congested): what they still send (a
  // stopped worker's backlog when it resumes) is ignored, not counted as bad,
  // until they say hello again. At most kRememberDropped, oldest forgotten first.
  std::set<std::string> dropped_ids_;
  std::deque<std::string> dropped_order_;
  uint64_t stale_messages_ = 0;
  std::string last_failure_;
  Clock::time_point last_failure_at_{};
  Clock::time_point peer_log_minute_{};
  int peer_lines_ = 0;
  uint64_t peer_lines_held_ = 0;
  std::vector<std::string> quarantined_names_;   // for the statistics (at most 1000)
  uint64_t quarantined_count_ = 0;
  // A job's failed results wait here until another worker's result for it
  // passes (then they count against their workers: the fault was theirs) or
  // every worker has failed it (then none does: the fault is the job's, or the
  // path's, and the master renders it). At most 4096 jobs.
  struct JobFailures {
    std::vector<std::string> workers;  // identities
    std::string text;                  // "worker-1 (why), ...": what the log names
  };
  std::map<uint64_t, JobFailures> job_failures_;
  std::map<uint64_t, std::string> own_failures_;  // jobs the master renders: what it said of each
  uint64_t own_tiles_ = 0;
  bool follows_workers_ = false;
  // Hashes of expected frames (expect_frame()): requested (no answer yet) or answered; at most kMaxExpected.
  std::map<uint64_t, std::optional<MasterRenderer::Answer>> expected_;
  uint64_t reference_frames_ = 0;
  double reference_seconds_ = 0.0;  // its own hashes were outvoted once (CURVE only): workers vote from then on
  std::map<uint64_t, OpenFrame> frames_;
  std::vector<TileJob> tiles_;             // the tiles of a frame as tiles_cut_ says
  std::tuple<int, int, int> tiles_cut_{0, 0, 0};  // width, height, border of tiles_
  std::vector<std::string> congested_;           // peers whose send queue was full: dropped after the batch
  std::vector<std::string> vanished_;            // peers whose connection had closed when sent to: dropped after the batch
  Clock::time_point next_sweep_, last_sweep_;
  double unlistened_seconds_ = 0.0;  // time the session was not listening (a stalled master), not counted as silence
  const Clock::time_point began_ = Clock::now();
  uint64_t accepted_ = 0;
  uint64_t bad_messages_ = 0;
  uint64_t refused_keys_ = 0, failed_handshakes_ = 0, declared_dead_ = 0;
  uint64_t nonfinite_pixels_ = 0, nonfinite_logged_ = 0, failures_logged_ = 0, referee_errors_ = 0, own_logged_ = 0;
  uint64_t quarantined_keys_logged_ = 0;
  std::optional<uint64_t> stall_reported_;  // the frame whose split was logged
  std::string fatal_;
  std::string user_id_;  // the CURVE key name of the message being handled (receive_batch)
  double session_cpu_ = 0.0;
  std::set<std::string> refused_logged_;  // each refused key is logged once
  uint64_t next_peer_ = 0;
  uint64_t session_id_;
};

}  // namespace igi
