#pragma once
// The master's side of a cluster session: the rooms of master/ at work on
// one thread. The socket and the peers behind it (cluster/), which job goes
// where (scheduler/), which results count and what the master renders itself
// (trust/), and the frames being assembled (frames/). Single-threaded: every
// call below runs on the thread that owns the socket (the session thread);
// nothing here writes files or draws, so that thread only moves messages.
//
// Reliability lives here and only here: heartbeats both ways, a peer silent
// past its patience is dead and its jobs are issued again, a result is
// checked against the scheduler's own job before its pixels are used, a
// result that fails validation sends its job to another worker (one that
// failed on every worker that could take it, or on two, the master renders
// itself: no failing peer can end the run), a worker whose VPL sets differ
// from the master's own (judge_by()) or, without it, lose the vote is
// quarantined (told so: it exits with status 5), and a frame is complete
// only when every job id is back and its hash is decided. Sends never
// block: a peer whose queue is full (it stopped reading) is dropped like a
// dead one.
//
// The loop sleeps in poll() until a message arrives or a timer is due (the
// liveness sweep, a straggler becoming late): no busy waiting. Results are
// decoded in place and their pixels copied straight from the ZeroMQ frame
// into the frame buffer, in the session's pixel format.
#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include <zmq.hpp>

#include "cluster/peer_socket.h"
#include "cluster/peers.h"
#include "cluster/scene_source.h"
#include "frames/frame_assembly.h"
#include "protocol/codec.h"
#include "protocol/messages.h"
#include "scheduler/scheduler.h"
#include "session/session_settings.h"
#include "trust/job_failures.h"
#include "trust/own_renders.h"

namespace igi {

// The run cannot go on (a job failed validation on every worker that could
// take it, and the master could not render it either); what() says which and why.
struct SessionError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

class MasterSession {
 public:
  // `curve`: null for a plain socket. Binds settings.listen; throws zmq::error_t when it cannot.
  MasterSession(const SessionSettings& settings, SceneSource scene, zmq::context_t& context,
                const protocol::CurveServerKeys* curve = nullptr);
  std::string endpoint() const { return socket_.endpoint(); }
  PixelFormat pixel_format() const { return settings_.pixel_format; }
  const std::string& pixel_codec() const { return settings_.pixel_codec; }  // what workers are asked to send

  // Judges every worker's VPL sets against the master's own, computed from
  // `scene` as the workers load it (trust/own_renders.h), instead of by a
  // vote among workers; and lets the master render a job no worker's result
  // for passed validation. Before the first frame.
  void judge_by(Scene scene);
  // Queues a frame; jobs go out as workers have credit (at most two frames open).
  // Its settings travel with its FrameSetup (default: the session's).
  bool can_add_frame() const { return scheduler_.can_add_frame(); }
  void add_frame(const FrameSetup& frame);
  void add_frame(const FrameSetup& frame, const RenderSettings& settings);
  // A frame to come with the session's settings (a headless run knows its
  // camera path): the master computes its VPL-set hash now, so that when the
  // frame is added its workers' results need not wait for it.
  void expect_frame(const FrameSetup& frame);
  // The view moved on: the frame is dropped and every worker that holds a
  // job of it is told to drop its queued ones (CancelFrame); their credit
  // comes back at once. The frame never completes.
  void cancel_frame(uint64_t frame_id);
  std::vector<uint64_t> open_frames() const { return frames_.ids(); }  // oldest first
  // Per-worker figures in each FrameRecord (on with --stats; the window turns them on).
  void set_detailed_stats(bool on) { settings_.detailed_stats = on; }
  // Which worker filled each tile, in each FrameRecord (the window's tile overlay).
  void record_tile_sources(bool on) { tile_sources_ = on; }
  std::vector<PeerView> peer_views() const { return peers_.views(); }
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
  uint64_t refused_keys() const { return socket_.refused_keys(); }            // CURVE keys the ZAP handler refused
  uint64_t failed_handshakes() const { return socket_.failed_handshakes(); }  // peers without CURVE or the right master key
  uint64_t declared_dead() const { return declared_dead_; }  // workers silent past the timeout, or not reading
  double unlistened_seconds() const { return peers_.unlistened_seconds(); }  // stalls: not counted as workers' silence
  uint64_t nonfinite_pixels() const { return nonfinite_pixels_; }
  uint64_t own_tiles() const { return own_tiles_; }  // jobs the master rendered itself (no worker's result passed)
  uint64_t benched() const { return scheduler_.stats().benched; }  // hoarders given no jobs until they answer
  uint64_t doubted() const { return scheduler_.stats().doubted; }  // frames decided in doubt
  // The master's VPL sets lost to its authenticated workers', which agreed: votes decide from then on.
  bool follows_workers() const { return own_ && own_->follows_workers(); }
  // The master's own VPL-set hashes: frames computed and the time its thread spent on them.
  uint64_t reference_frames() const { return own_ ? own_->hash_frames() : 0; }
  double reference_seconds() const { return own_ ? own_->hash_seconds() : 0.0; }
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

  void open_frame(const FrameSetup& frame, const RenderSettings& settings);
  void step(Clock::time_point now, std::vector<CompletedFrame>& done);
  void on_message(const std::string& identity, zmq::message_t& payload, size_t parts);
  void on_frame(const std::string& identity, std::span<const uint8_t> payload);
  void handle(const std::string& identity, const protocol::Message& message);
  void on_scene_request(const std::string& identity, const Peer& peer, const protocol::SceneRequest& request);
  void on_hello(const std::string& identity, const protocol::Hello& hello);
  protocol::Welcome welcome(uint32_t credits) const;  // what a joining peer is told
  void sweep(Clock::time_point now);
  void dispatch(const std::vector<JobAssignment>& jobs);
  std::vector<CompletedFrame> take_completed();
  void report_stall();
  // Bytes queued, or 0 when the peer is gone or its queue is full (it is then dropped).
  size_t send(const std::string& identity, const protocol::Message& message);
  size_t send(const std::string& identity, zmq::message_t&& payload);
  void log(const std::string& text) const;
  // Results and their verdicts (session_results.cpp).
  void on_result(const std::string& identity, std::span<const uint8_t> bytes);
  void use_result(const std::string& identity, Peer& peer, const protocol::TileResultView& view, size_t bytes);
  void on_bad_result(const std::string& identity, uint64_t job_id, const std::string& error);
  void on_bad_message(const std::string& identity, const std::string& error);
  void on_foreign_result(const std::string& identity, const protocol::TileResultHead& head);
  void on_stale_result(const std::string& identity, const protocol::TileResultHead& head, std::span<const uint8_t> bytes);
  void count_failures_against_workers(uint64_t job_id);
  void drop_peer(const std::string& identity, const std::string& why);
  void quarantine_peer(const std::string& identity, const std::string& why);
  void take_quarantined();
  void take_own_work();
  void render_own_jobs();
  void use_own_result(const MasterRenderer::TileAnswer& answer);
  void on_dispute(const HashDispute& dispute);
  void on_doubt(const HashDoubt& doubt);

  SessionSettings settings_;
  SceneSource scene_;
  PeerSocket socket_;
  Peers peers_;
  Scheduler scheduler_;
  FrameAssembly frames_;
  std::unique_ptr<OwnRenders> own_;  // the master's own hashes and tiles; null: workers vote
  JobFailures job_failures_;
  bool tile_sources_ = false;
  std::string last_failure_;
  Clock::time_point last_failure_at_{};
  std::vector<std::string> quarantined_names_;  // for the statistics (at most 1000)
  uint64_t quarantined_count_ = 0, own_tiles_ = 0, stale_messages_ = 0;
  const Clock::time_point began_ = Clock::now();
  uint64_t accepted_ = 0;
  uint64_t bad_messages_ = 0, declared_dead_ = 0;
  uint64_t nonfinite_pixels_ = 0, nonfinite_logged_ = 0, failures_logged_ = 0, doubts_logged_ = 0;
  std::optional<uint64_t> stall_reported_;  // the frame whose split was logged
  std::string fatal_;
  std::string user_id_;  // the CURVE key name of the message being handled
  double session_cpu_ = 0.0;
  uint64_t session_id_;
};

}  // namespace igi
