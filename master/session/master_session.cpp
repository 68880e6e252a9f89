#include "session/master_session.h"

#include <algorithm>
#include <cstdio>
#include <ctime>
#include <utility>

#include "build_id.h"
#include "scene/libraries.h"
#include "trust/reports.h"

namespace igi {
namespace {

constexpr int kBatch = 512;  // messages received per wake-up before timers run again

double thread_cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}

// Two jobs for a newcomer until it answers, then one more per result up to
// its threads' worth: a peer that claims 32 threads and never answers holds two.
// A verdict against the master's own hash waits two timeouts after the latest
// join: a worker that starts as late as a timeout still joins and votes.
SchedulerConfig scheduler_config(const SessionSettings& settings) {
  SchedulerConfig c;
  c.credits = settings.credits;
  c.frames_in_flight = 2;
  c.first_credits = 2;
  c.failures_need_standing = true;
  c.vote_wait_seconds = 2e-3 * settings.timeout_ms;
  return c;
}

}  // namespace

MasterSession::MasterSession(const SessionSettings& settings, SceneSource scene, zmq::context_t& context,
                             const protocol::CurveServerKeys* curve)
    : settings_(settings),
      scene_(std::move(scene)),
      socket_(context, settings.listen, settings.send_hwm, curve, settings.quiet),
      peers_(settings.heartbeat_ms, settings.timeout_ms, settings.quiet),
      scheduler_(scheduler_config(settings)),
      frames_(settings.pixel_format, settings.tile_size),
      session_id_(uint64_t(Clock::now().time_since_epoch().count())) {
  scheduler_.force_duplicates(settings.force_duplicates);
}

void MasterSession::log(const std::string& text) const {
  if (!settings_.quiet) std::fprintf(stderr, "igi-master: %s\n", text.c_str());
}

size_t MasterSession::send(const std::string& identity, zmq::message_t&& payload) {
  const size_t bytes = socket_.send(identity, std::move(payload));
  if (Peer* peer = peers_.find(identity); peer && bytes > 0) peer->last_sent = Clock::now();
  return bytes;
}

size_t MasterSession::send(const std::string& identity, const protocol::Message& message) {
  std::vector<uint8_t> bytes = protocol::encode(message);
  return send(identity, zmq::message_t(bytes.data(), bytes.size()));
}

// ---- Frames.

void MasterSession::judge_by(Scene scene) {
  scheduler_.judge_by_reference();
  own_ = std::make_unique<OwnRenders>(std::move(scene), settings_.quiet);
}

void MasterSession::expect_frame(const FrameSetup& frame) {
  if (own_ && !frames_.find(frame.frame_id)) own_->expect(frame, settings_.settings);
}

void MasterSession::add_frame(const FrameSetup& frame) {
  std::optional<std::optional<uint64_t>> hash;
  if (!own_ || !own_->take_expected(frame.frame_id, hash)) return add_frame(frame, settings_.settings);
  open_frame(frame, settings_.settings);  // its hash is on its way, or here
  if (hash) scheduler_.set_reference(frame.frame_id, *hash);
}

void MasterSession::add_frame(const FrameSetup& frame, const RenderSettings& settings) {
  open_frame(frame, settings);
  if (own_) own_->request(frame, settings);
}

void MasterSession::open_frame(const FrameSetup& frame, const RenderSettings& settings) {
  scheduler_.add_frame(frame.frame_id, frames_.open(frame, settings));
}

void MasterSession::cancel_frame(uint64_t frame_id) {
  if (!frames_.cancel(frame_id)) return;
  scheduler_.cancel_frame(frame_id);
  for (auto& [identity, peer] : peers_.all())
    if (peer.frames_sent.erase(frame_id)) send(identity, protocol::CancelFrame{frame_id});
}

// ---- The loop.

std::vector<CompletedFrame> MasterSession::pump(int timeout_ms) {
  const double cpu_start = thread_cpu_seconds();
  const auto end = Clock::now() + std::chrono::milliseconds(std::max(timeout_ms, 0));
  std::vector<CompletedFrame> done;
  for (;;) {
    step(Clock::now(), done);
    if (!fatal_.empty()) {
      session_cpu_ += thread_cpu_seconds() - cpu_start;
      throw SessionError(fatal_);
    }
    if (!done.empty() || Clock::now() >= end) break;
    Clock::time_point until = std::min(end, peers_.next_sweep());
    if (auto late = scheduler_.next_straggler_time(Clock::now())) until = std::min(until, *late);
    if (auto verdict = scheduler_.next_verdict_time()) until = std::min(until, std::max(*verdict, Clock::now()));
    socket_.wait(until, own_ ? own_->fd() : -1);
    socket_.serve_security();
    socket_.receive(kBatch, [this](const std::string& identity, zmq::message_t& payload, size_t parts) {
      on_message(identity, payload, parts);
    });
  }
  session_cpu_ += thread_cpu_seconds() - cpu_start;
  return done;
}

// Everything but receiving: timers, jobs for free credit, completed frames.
void MasterSession::step(Clock::time_point now, std::vector<CompletedFrame>& done) {
  if (now >= peers_.next_sweep()) sweep(now);
  take_own_work();
  dispatch(scheduler_.assign(now));
  render_own_jobs();
  for (const HashDispute& d : scheduler_.take_disputes()) on_dispute(d);
  for (const HashDoubt& d : scheduler_.take_doubts()) on_doubt(d);
  for (const WorkerId& id : scheduler_.take_benched()) {
    const Peer* peer = peers_.find(id);
    if (!peer) continue;
    char late[32];
    std::snprintf(late, sizeof late, "%.0f ms", 1e3 * scheduler_.straggler_seconds());
    peers_.log_join_or_leave(peer->name + " held a job past " + late + " without answering it while another "
                             "worker did (it heartbeats, so it is not dead): its jobs go to others, and it gets "
                             "none until it answers");
  }
  take_quarantined();
  for (const std::string& identity : socket_.take_congested())
    if (peers_.known(identity)) {
      ++declared_dead_;
      drop_peer(identity, "stopped reading (its queue is full): declared dead, its jobs go to others");
    }
  for (const std::string& identity : socket_.take_vanished())
    drop_peer(identity, "lost its connection: its jobs go to others");
  for (CompletedFrame& f : take_completed()) done.push_back(std::move(f));
  report_stall();
}

// Liveness and heartbeats, a few times per heartbeat interval.
void MasterSession::sweep(Clock::time_point now) {
  const Peers::Sweep sweep = peers_.sweep(now);
  for (const std::string& identity : sweep.heartbeat) send(identity, protocol::Heartbeat{});
  declared_dead_ += sweep.dead.size();
  for (const auto& [identity, patience] : sweep.dead) drop_peer(identity, peers_.why_dead(patience));
}

void MasterSession::dispatch(const std::vector<JobAssignment>& jobs) {
  for (const JobAssignment& job : jobs) {
    Peer* peer = peers_.find(job.worker);
    FrameAssembly::OpenFrame* f = frames_.find(job.frame_id);
    if (!peer || !f) continue;
    if (!f->started) f->started = Clock::now();
    size_t bytes = 0;
    if (peer->frames_sent.insert(job.frame_id).second)
      bytes += send(job.worker, protocol::FrameSetupMsg{f->setup, f->settings});
    bytes += send(job.worker, protocol::TileJobMsg{job.frame_id, job.job_id, job.tile});
    if (settings_.detailed_stats) {
      f->record.workers[peer->name].bytes_out += bytes;
      std::map<uint64_t, Clock::time_point>& sent = peer->sent;
      if (sent.size() > 1024) sent.clear();  // results that never came (reissued elsewhere): forget them
      sent[job.job_id] = Clock::now();
    }
  }
}

std::vector<CompletedFrame> MasterSession::take_completed() {
  std::vector<CompletedFrame> done;
  for (uint64_t frame_id : scheduler_.take_completed_frames()) {
    CompletedFrame f = frames_.complete(frame_id, began_);
    const SchedulerStats& s = scheduler_.stats();
    f.record.reissued = s.reissued;
    f.record.duplicated = s.duplicated;
    f.record.late_dropped = s.late_dropped;
    f.record.verified = s.verified;
    f.record.failed_results = s.failed_results;
    f.record.quarantined = quarantined_count_;
    f.record.own_tiles = own_tiles_;
    done.push_back(std::move(f));
    for (auto& [identity, peer] : peers_.all()) peer.frames_sent.erase(frame_id);
  }
  return done;
}

// Two workers disagree on a frame's VPL sets and no third breaks the tie: said once per frame.
void MasterSession::report_stall() {
  std::optional<HashSplit> split = scheduler_.stalled_split();
  if (!split || stall_reported_ == split->frame_id) return;
  stall_reported_ = split->frame_id;
  std::fprintf(stderr, "igi-master: %s\n", stall().c_str());
}

std::string MasterSession::stall() const {
  std::optional<HashSplit> split = scheduler_.stalled_split();
  if (!split) return {};
  std::vector<std::string> names;
  for (const auto& [hash, voters] : split->voters)
    for (const WorkerId& v : voters) {
      const Peer* peer = peers_.find(v);
      names.push_back(peer ? peer->name : "a departed worker");
    }
  return split_report(*split, names);
}

void MasterSession::close(const std::string& reason) {
  peers_.flush_log();
  for (const auto& [identity, peer] : peers_.all()) send(identity, protocol::Bye{reason});
  peers_.clear();
  // The goodbyes must leave before the process does (linger 0 would drop them
  // when the context ends): up to a second, then they are abandoned.
  socket_.linger(1000);
  if (socket_.refused_keys() + socket_.failed_handshakes() > 0)
    log("CURVE: refused " + std::to_string(socket_.refused_keys()) + " unknown worker keys; " +
        std::to_string(socket_.failed_handshakes()) + " failed handshakes");
}

// ---- Messages.

// [identity, payload]; anything else is a bad message.
void MasterSession::on_message(const std::string& identity, zmq::message_t& payload, size_t parts) {
  user_id_.clear();
  if (socket_.curve() && parts == 1 && !peers_.known(identity))  // a Hello, or a stranger's: which key sent it
    user_id_ = PeerSocket::user_id(payload);
  if (parts != 1)
    return on_bad_message(identity, std::to_string(parts) + " frames, expected 1 message frame after the identity");
  on_frame(identity, {payload.data<uint8_t>(), payload.size()});
}

void MasterSession::on_frame(const std::string& identity, std::span<const uint8_t> payload) {
  if (peers_.quarantined(identity)) return;  // told to leave; its last messages do not matter
  const bool dropped = peers_.dropped(identity);
  if (protocol::is_tile_result(payload)) {
    if (dropped) return void(++stale_messages_);  // its jobs went to others when it was dropped
    return on_result(identity, payload);
  }
  protocol::DecodeResult decoded = protocol::decode(payload);
  if (dropped && !(decoded.message && std::holds_alternative<protocol::Hello>(*decoded.message)))
    return void(++stale_messages_);  // until it says hello again
  if (!decoded.message) return on_bad_message(identity, decoded.error);
  handle(identity, *decoded.message);
}

void MasterSession::handle(const std::string& identity, const protocol::Message& message) {
  Peer* peer = peers_.find(identity);
  if (peer) Peers::heard(*peer, Clock::now());
  if (auto* hello = std::get_if<protocol::Hello>(&message)) return on_hello(identity, *hello);
  if (!peer) return on_bad_message(identity, "message from a peer that never said hello");
  if (auto* request = std::get_if<protocol::SceneRequest>(&message)) {
    on_scene_request(identity, *peer, *request);
  } else if (auto* bye = std::get_if<protocol::Bye>(&message)) {
    if (bye->kind == protocol::ByeKind::Failed) {
      last_failure_ = peer->name + " failed: " + bye->reason;
      last_failure_at_ = Clock::now();
    }
    drop_peer(identity, bye->kind == protocol::ByeKind::Failed ? "failed: " + bye->reason : "left: " + bye->reason);
  } else if (!std::holds_alternative<protocol::Heartbeat>(message)) {
    on_bad_message(identity, std::string("unexpected ") + protocol::message_name(protocol::type_of(message)));
  }
}

void MasterSession::on_scene_request(const std::string& identity, const Peer& peer,
                                     const protocol::SceneRequest& request) {
  if (request.scene_hash == scene_.map_hash && scene_.map_message) {
    log(peer.name + " has no copy of " + scene_.map_name + ": sending " + std::to_string(scene_.map_size) + " bytes");
    send(identity, shared_frame(scene_.map_message));
    return;
  }
  if (request.scene_hash != scene_.hash || !scene_.message) return drop_peer(identity, "asked for an unknown scene");
  log(peer.name + " has no copy of " + scene_.name + ": sending " + std::to_string(scene_.size) + " bytes");
  send(identity, shared_frame(scene_.message));
}

void MasterSession::on_hello(const std::string& identity, const protocol::Hello& hello) {
  if (hello.build_id != igi::build_id()) {
    const std::string reason = "build '" + hello.build_id + "' differs from the master's '" + igi::build_id() +
                               "': tiles would not match bit for bit";
    log("refused a worker: " + reason);
    scheduler_.remove_worker(identity);
    peers_.erase(identity);
    send(identity, protocol::Refuse{reason});
    return;
  }
  if (const Peer* known = peers_.find(identity); known && known->threads == hello.threads) {
    // The same connection asking again: a worker repeats its Hello until it is
    // welcomed, so its first Welcome is late or was lost. Nothing to reset.
    send(identity, welcome(known->credits));
    return;
  }
  Peer& peer = peers_.join(identity, hello.threads, hello.libraries, user_id_);
  scheduler_.remove_worker(identity);  // another Hello on this connection (other threads): its old jobs go back first
  // Enough jobs to keep every thread busy while results travel.
  const int wanted = std::max<int>(settings_.credits, 2 * int(std::min<uint32_t>(hello.threads, 32)));
  peer.credits = uint32_t(std::min<int>(wanted, protocol::kMaxCredits));  // --credits is within it already
  scheduler_.add_worker(identity, int(peer.credits), user_id_, Clock::now());
  const bool other_libraries = !hello.libraries.empty() && hello.libraries != runtime_libraries();
  peers_.log_join_or_leave(peer.name + " joined (" + std::to_string(hello.threads) + " threads" +
                           (other_libraries ? "; it runs " + hello.libraries + ", the master " +
                                                  runtime_libraries() + ": their VPL sets may differ"
                                            : "") +
                           ")");
  send(identity, welcome(peer.credits));
}

protocol::Welcome MasterSession::welcome(uint32_t credits) const {
  protocol::Welcome w;
  w.session = session_id_;
  w.scene_name = scene_.name;
  w.scene_hash = scene_.hash;
  w.scene_size = scene_.size;
  w.environment = scene_.environment;
  w.settings = settings_.settings;
  w.credits = credits;
  w.heartbeat_ms = uint32_t(settings_.heartbeat_ms);
  w.timeout_ms = uint32_t(settings_.timeout_ms);
  w.pixel_format = settings_.pixel_format;
  w.pixel_codec = settings_.pixel_codec == "zstd"  ? protocol::PixelCodec::Zstd
                  : settings_.pixel_codec == "lz4" ? protocol::PixelCodec::Lz4
                                                   : protocol::PixelCodec::Raw;
  w.environment_map = scene_.map_name;
  w.environment_map_hash = scene_.map_hash;
  w.environment_map_size = scene_.map_size;
  w.environment_rotation = scene_.map_rotation;
  w.light_units = scene_.light_units;
  return w;
}

}  // namespace igi
