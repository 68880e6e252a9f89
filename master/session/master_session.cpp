#include "session/master_session.h"

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <utility>

#include "build_id.h"
#include "protocol/pixels.h"
#include "protocol/socket.h"
#include "render/frame_renderer.h"
#include "scene/builtin_scenes.h"
#include "scene/gltf_pack.h"
#include "scene/libraries.h"
#include "scene/scene_file.h"

namespace igi {
namespace {

constexpr int kBatch = 512;              // messages received per wake-up before timers run again
constexpr int kMaxFailedResults = 3;     // a peer whose results fail validation this often is quarantined
constexpr size_t kMaxQuarantinedNames = 1000;
constexpr uint64_t kLogFirst = 5;        // repeated conditions are logged this often, then counted
constexpr int kPeerLinesPerMinute = 100;  // joins and departures logged one by one
constexpr size_t kRememberDropped = 4096;  // dropped peers whose later messages are ignored
constexpr size_t kMaxExpected = 8;         // frames whose hashes are computed before they are added

double thread_cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}

std::string describe(const TileJob& t) {
  char text[96];
  std::snprintf(text, sizeof text, "(%d, %d, %d x %d, border %d)", t.x, t.y, t.w, t.h, t.border);
  return text;
}

// The encoded bytes handed to ZeroMQ without a copy; zmq drops the reference when sent.
zmq::message_t shared_frame(const std::shared_ptr<const std::vector<uint8_t>>& bytes) {
  auto* keep = new std::shared_ptr<const std::vector<uint8_t>>(bytes);
  auto release = [](void*, void* hint) { delete static_cast<std::shared_ptr<const std::vector<uint8_t>>*>(hint); };
  return zmq::message_t(const_cast<uint8_t*>(bytes->data()), bytes->size(), release, keep);
}

// Two jobs for a newcomer until it answers, then one more per result up to
// its threads' worth: a peer that claims 32 threads and never answers holds two.
SchedulerConfig session_scheduler_config(const MasterOptions& options) {
  SchedulerConfig c;
  c.credits = options.credits;
  c.frames_in_flight = 2;
  c.first_credits = 2;
  c.failures_need_standing = true;
  return c;
}

}  // namespace

SceneSource make_scene_source(const std::string& scene) {
  if (is_builtin_scene(scene)) {
    SceneSource builtin;
    builtin.name = scene;
    return builtin;
  }
  SceneFile file = scene_file_for_workers(scene);  // a .gltf with files beside it: packed into one .glb
  if (file.packed)
    std::fprintf(stderr, "igi-master: %s goes to workers as %s, its buffers and images packed in\n", scene.c_str(),
                 file.name.c_str());
  SceneSource source;
  source.name = file.name;
  source.hash = content_hash(file.bytes);
  source.size = file.bytes.size();
  protocol::SceneData data{source.hash, source.name, std::move(file.bytes)};
  source.message = std::make_shared<const std::vector<uint8_t>>(protocol::encode(data));
  return source;
}

void add_environment_map(SceneSource& source, const std::string& path, float rotation) {
  std::optional<std::vector<uint8_t>> bytes = read_file_bytes(path);
  if (!bytes) throw std::runtime_error("cannot read the environment map " + path);
  source.map_name = std::filesystem::path(path).filename().string();
  source.map_hash = content_hash(*bytes);
  source.map_size = bytes->size();
  source.map_rotation = rotation;
  protocol::SceneData data{source.map_hash, source.map_name, std::move(*bytes)};
  source.map_message = std::make_shared<const std::vector<uint8_t>>(protocol::encode(data));
}

MasterSession::MasterSession(const MasterOptions& options, SceneSource scene, zmq::context_t& context,
                             const protocol::CurveServerKeys* curve)
    : options_(options),
      scene_(std::move(scene)),
      pixel_format_(session_pixel_format(options)),
      detailed_stats_(!options.stats.empty()),
      router_(context, zmq::socket_type::router),
      scheduler_(session_scheduler_config(options)),
      session_id_(uint64_t(Clock::now().time_since_epoch().count())) {
  protocol::configure(router_, protocol::kMaxWorkerMessageBytes);
  router_.set(zmq::sockopt::router_mandatory, 1);  // a send to a vanished peer fails instead of vanishing
  if (options.send_hwm > 0) router_.set(zmq::sockopt::sndhwm, options.send_hwm);
  // A peer that has not finished the ZMTP handshake in 5 s (a port scanner,
  // non-ZMTP bytes) is disconnected, rather than holding a descriptor for
  // libzmq's default 30 s.
  router_.set(zmq::sockopt::handshake_ivl, 5000);
  if (curve) {
    zap_ = std::make_unique<protocol::ZapHandler>(context, curve->authorized);
    protocol::make_curve_server(router_, curve->own);
    monitor_ = std::make_unique<protocol::SocketMonitor>(
        context, router_, ZMQ_EVENT_HANDSHAKE_FAILED_PROTOCOL | ZMQ_EVENT_HANDSHAKE_FAILED_NO_DETAIL);
  }
  protocol::bind(router_, options.listen);
  endpoint_ = router_.get(zmq::sockopt::last_endpoint);
  scheduler_.force_duplicates(options.force_duplicates);
  next_sweep_ = last_sweep_ = Clock::now();
}

void MasterSession::log(const std::string& text) const {
  if (!options_.render.quiet) std::fprintf(stderr, "igi-master: %s\n", text.c_str());
}

void MasterSession::log_peer(const std::string& text) {
  const Clock::time_point now = Clock::now();
  if (now - peer_log_minute_ >= std::chrono::minutes(1)) {
    if (peer_lines_held_ > 0)
      log(std::to_string(peer_lines_held_) + " more joins and departures in the last minute, not logged one by one");
    peer_log_minute_ = now;
    peer_lines_ = 0;
    peer_lines_held_ = 0;
  }
  if (peer_lines_++ < kPeerLinesPerMinute) log(text);
  else ++peer_lines_held_;
}

void MasterSession::forget_peer(const std::string& identity) {
  if (!dropped_ids_.insert(identity).second) return;
  dropped_order_.push_back(identity);
  if (dropped_order_.size() > kRememberDropped) {
    dropped_ids_.erase(dropped_order_.front());
    dropped_order_.pop_front();
  }
}

// ---- Sending: never blocks.

size_t MasterSession::send_frame(const std::string& identity, zmq::message_t&& payload) {
  const size_t bytes = payload.size();
  try {
    if (!router_.send(zmq::buffer(identity), zmq::send_flags::sndmore | zmq::send_flags::dontwait)) {
      congested_.push_back(identity);  // its queue is full: it stopped reading
      return 0;
    }
    router_.send(payload, zmq::send_flags::dontwait);  // the rest of a message is never refused
  } catch (const zmq::error_t& e) {
    // ROUTER_MANDATORY: its connection has closed (it exited, or its TCP
    // connection was re-established under a new routing id, as a loaded
    // machine's can be while it joins). Its jobs go back now, not after the timeout.
    if (e.num() == EHOSTUNREACH) vanished_.push_back(identity);
    return 0;
  }
  auto it = peers_.find(identity);
  if (it != peers_.end()) it->second.last_sent = Clock::now();
  return bytes;
}

size_t MasterSession::send(const std::string& identity, const protocol::Message& message) {
  std::vector<uint8_t> bytes = protocol::encode(message);
  zmq::message_t payload(bytes.data(), bytes.size());
  return send_frame(identity, std::move(payload));
}

// ---- The loop.

void MasterSession::judge_by(Scene scene) {
  scheduler_.judge_by_reference();
  referee_ = std::make_unique<MasterRenderer>(std::move(scene));
}

void MasterSession::expect_frame(const FrameSetup& frame) {
  if (!referee_ || follows_workers_ || expected_.count(frame.frame_id) || frames_.count(frame.frame_id)) return;
  if (expected_.size() >= kMaxExpected) return;  // frames expected far ahead wait for their turn
  expected_[frame.frame_id];
  referee_->request(frame, options_.render.settings);
}

void MasterSession::add_frame(const FrameSetup& frame) {
  auto expected = expected_.find(frame.frame_id);
  if (expected == expected_.end()) return add_frame(frame, options_.render.settings);
  std::optional<MasterRenderer::Answer> answer = std::move(expected->second);
  expected_.erase(expected);
  add_frame(frame, options_.render.settings, false);  // its hash is on its way, or here
  if (answer) scheduler_.set_reference(answer->frame_id, answer->hash);
}

void MasterSession::add_frame(const FrameSetup& frame, const RenderSettings& settings) {
  add_frame(frame, settings, true);
}

void MasterSession::add_frame(const FrameSetup& frame, const RenderSettings& settings, bool request_hash) {
  OpenFrame open;
  open.setup = frame;
  open.settings = settings;
  open.pixels = pool_.acquire(frame.width, frame.height, pixel_format_);
  open.record.frame_id = frame.frame_id;
  if (frame.want_surfaces) open.surfaces.resize(size_t(frame.width) * size_t(frame.height));
  frames_[frame.frame_id] = std::move(open);
  const int border = tile_border(settings);
  if (tiles_.empty() || tiles_cut_ != std::tuple{frame.width, frame.height, border}) {  // cut once per size and border
    const int tile = options_.render.tile_size;
    tiles_ = make_tiles(frame.width, frame.height, tile, tile, border);
    tiles_cut_ = {frame.width, frame.height, border};
  }
  scheduler_.add_frame(frame.frame_id, tiles_);
  if (referee_ && !follows_workers_ && request_hash) referee_->request(frame, settings);
}

void MasterSession::cancel_frame(uint64_t frame_id) {
  if (!frames_.erase(frame_id)) return;
  scheduler_.cancel_frame(frame_id);
  for (auto& [identity, peer] : peers_)
    if (peer.frames_sent.erase(frame_id)) send(identity, protocol::CancelFrame{frame_id});
}

std::vector<uint64_t> MasterSession::open_frames() const {
  std::vector<uint64_t> ids;
  for (const auto& entry : frames_) ids.push_back(entry.first);
  return ids;
}

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
    Clock::time_point until = std::min(end, next_sweep_);
    if (auto late = scheduler_.next_straggler_time(Clock::now())) until = std::min(until, *late);
    wait_for_traffic(until);
    serve_security();
    receive_batch();
  }
  session_cpu_ += thread_cpu_seconds() - cpu_start;
  return done;
}

// Everything but receiving: timers, jobs for free credit, completed frames.
void MasterSession::step(Clock::time_point now, std::vector<CompletedFrame>& done) {
  if (now >= next_sweep_) sweep(now);
  take_references();
  dispatch(scheduler_.assign(now));
  render_own_jobs();
  for (const HashDispute& d : scheduler_.take_disputes()) on_dispute(d);
  for (const WorkerId& id : scheduler_.take_benched()) {
    auto peer = peers_.find(id);
    if (peer == peers_.end()) continue;
    char late[32];
    std::snprintf(late, sizeof late, "%.0f ms", 1e3 * scheduler_.straggler_seconds());
    log_peer(peer->second.name + " held a job past " + late + " without answering it while another worker did "
             "(it heartbeats, so it is not dead): its jobs go to others, and it gets none until it answers");
  }
  take_quarantined();
  for (const std::string& identity : std::exchange(congested_, {}))
    if (peers_.count(identity)) {
      ++declared_dead_;
      drop_peer(identity, "stopped reading (its queue is full): declared dead, its jobs go to others");
    }
  for (const std::string& identity : std::exchange(vanished_, {}))
    drop_peer(identity, "lost its connection: its jobs go to others");
  for (CompletedFrame& f : take_completed()) done.push_back(std::move(f));
  report_stall();
}

void MasterSession::wait_for_traffic(Clock::time_point until) {
  const auto wait = std::chrono::duration_cast<std::chrono::milliseconds>(until - Clock::now());
  std::vector<zmq::pollitem_t> items{{router_.handle(), 0, ZMQ_POLLIN, 0}};
  if (zap_) items.push_back({zap_->socket().handle(), 0, ZMQ_POLLIN, 0});
  if (referee_) items.push_back({nullptr, referee_->fd(), ZMQ_POLLIN, 0});
  try {
    // Round up: a wake a millisecond early would only poll again.
    zmq::poll(items, std::chrono::milliseconds(std::max<int64_t>(0, wait.count() + 1)));
  } catch (const zmq::error_t& e) {
    if (e.num() != EINTR) throw;  // a signal: the caller's loop decides
  }
}

// Every message waiting, up to a batch: [identity, payload]; anything else is a bad message.
void MasterSession::receive_batch() {
  for (int n = 0; n < kBatch; ++n) {
    zmq::message_t identity, payload;
    if (!router_.recv(identity, zmq::recv_flags::dontwait)) return;
    size_t parts = 1;
    bool more = identity.more();
    while (more) {
      zmq::message_t part;
      if (!router_.recv(part, zmq::recv_flags::dontwait)) break;  // parts of a message arrive together
      more = part.more();
      if (parts++ == 1) payload = std::move(part);
    }
    const std::string id = identity.to_string();
    user_id_.clear();
    if (zap_ && parts == 2 && !peers_.count(id))  // a Hello, or a stranger's message: which key sent it
      if (const char* user = zmq_msg_gets(payload.handle(), "User-Id")) user_id_ = user;
    if (parts != 2) {
      on_bad_message(id, std::to_string(parts - 1) + " frames, expected 1 message frame after the identity");
      continue;
    }
    on_frame(id, {payload.data<uint8_t>(), payload.size()});
  }
}

void MasterSession::on_frame(const std::string& identity, std::span<const uint8_t> payload) {
  if (quarantined_ids_.count(identity)) return;  // told to leave; its last messages do not matter
  const bool dropped = !peers_.count(identity) && dropped_ids_.count(identity);
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

// ---- Security.

// Handshakes wait for these answers; a peer is only a peer once they pass.
void MasterSession::serve_security() {
  if (zap_)
    for (const protocol::ZapDecision& d : zap_->answer_waiting()) on_zap_decision(d);
  if (!monitor_) return;
  for (size_t n = monitor_->take_events().size(); n > 0; --n) {
    // A flood of these is an attack or a misconfigured farm: log the first few, count all.
    if (++failed_handshakes_ <= kLogFirst)
      log("a peer failed the CURVE handshake (it does not use CURVE, or has another master public key)");
  }
}

void MasterSession::on_zap_decision(const protocol::ZapDecision& d) {
  if (d.allowed) return log("CURVE key '" + d.name + "' from " + d.address + " accepted");
  if (d.quarantined) {
    ++refused_keys_;
    if (++quarantined_keys_logged_ <= kLogFirst || quarantined_keys_logged_ % 1000 == 0)
      std::fprintf(stderr, "igi-master: refused CURVE key '%s' from %s: it was quarantined in this session\n",
                   d.name.c_str(), d.address.c_str());
    return;
  }
  ++refused_keys_;
  // Each key once, and a bounded set: a peer may try a new key per connection.
  if (refused_logged_.size() < 1000 && refused_logged_.insert(d.public_key).second)
    std::fprintf(stderr,
                 "igi-master: refused worker key %s from %s: not among --authorized-keys (%llu refused so far)\n",
                 d.public_key.empty() ? "(not CURVE)" : d.public_key.c_str(), d.address.c_str(),
                 static_cast<unsigned long long>(refused_keys_));
}

// ---- Messages.

void MasterSession::handle(const std::string& identity, const protocol::Message& message) {
  auto peer = peers_.find(identity);
  if (peer != peers_.end()) heard(peer->second, Clock::now());
  if (auto* hello = std::get_if<protocol::Hello>(&message)) return on_hello(identity, *hello);
  if (peer == peers_.end()) return on_bad_message(identity, "message from a peer that never said hello");
  if (auto* request = std::get_if<protocol::SceneRequest>(&message)) {
    if (request->scene_hash == scene_.map_hash && scene_.map_message) {
      log(peer->second.name + " has no copy of " + scene_.map_name + ": sending " + std::to_string(scene_.map_size) +
          " bytes");
      send_frame(identity, shared_frame(scene_.map_message));
      return;
    }
    if (request->scene_hash != scene_.hash || !scene_.message) return drop_peer(identity, "asked for an unknown scene");
    log(peer->second.name + " has no copy of " + scene_.name + ": sending " + std::to_string(scene_.size) + " bytes");
    send_frame(identity, shared_frame(scene_.message));
  } else if (auto* bye = std::get_if<protocol::Bye>(&message)) {
    if (bye->kind == protocol::ByeKind::Failed) {
      last_failure_ = peer->second.name + " failed: " + bye->reason;
      last_failure_at_ = Clock::now();
    }
    drop_peer(identity, bye->kind == protocol::ByeKind::Failed ? "failed: " + bye->reason : "left: " + bye->reason);
  } else if (!std::holds_alternative<protocol::Heartbeat>(message)) {
    on_bad_message(identity, std::string("unexpected ") + protocol::message_name(protocol::type_of(message)));
  }
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
  auto known = peers_.find(identity);
  if (known != peers_.end() && known->second.threads == hello.threads) {
    // The same connection asking again: a worker repeats its Hello until it is
    // welcomed, so its first Welcome is late or was lost. Nothing to reset.
    send(identity, welcome(known->second.credits));
    return;
  }
  Peer& peer = peers_[identity];
  peer.number = uint32_t(next_peer_);
  peer.threads = hello.threads;
  peer.sent.clear();
  peer.round_trip_ms = 0.0;
  peer.name = "worker-" + std::to_string(next_peer_++);
  peer.last_heard = peer.last_sent = Clock::now();
  peer.gap_count = 0;
  peer.frames_sent.clear();
  peer.failed_results = 0;
  peer.libraries = hello.libraries;
  peer.key_name = user_id_;
  scheduler_.remove_worker(identity);  // another Hello on this connection (other threads): its old jobs go back first
  // Enough jobs to keep every thread busy while results travel.
  const int wanted = std::max<int>(options_.credits, 2 * int(std::min<uint32_t>(hello.threads, 32)));
  peer.credits = uint32_t(std::min<int>(wanted, protocol::kMaxCredits));  // --credits is within it already
  scheduler_.add_worker(identity, int(peer.credits));
  const bool other_libraries = !hello.libraries.empty() && hello.libraries != runtime_libraries();
  log_peer(peer.name + " joined (" + std::to_string(hello.threads) + " threads" +
           (other_libraries ? "; it runs " + hello.libraries + ", the master " + runtime_libraries() +
                                  ": their VPL sets may differ"
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
  w.settings = options_.render.settings;
  w.credits = credits;
  w.heartbeat_ms = uint32_t(options_.heartbeat_ms);
  w.timeout_ms = uint32_t(options_.timeout_ms);
  w.pixel_format = pixel_format_;
  w.pixel_codec = options_.pixel_codec == "zstd"  ? protocol::PixelCodec::Zstd
                  : options_.pixel_codec == "lz4" ? protocol::PixelCodec::Lz4
                                                  : protocol::PixelCodec::Raw;
  w.environment_map = scene_.map_name;
  w.environment_map_hash = scene_.map_hash;
  w.environment_map_size = scene_.map_size;
  w.environment_rotation = scene_.map_rotation;
  w.light_units = scene_.light_units;
  return w;
}

void MasterSession::on_result(const std::string& identity, std::span<const uint8_t> bytes) {
  auto peer = peers_.find(identity);
  if (peer == peers_.end()) return on_bad_message(identity, "message from a peer that never said hello");
  heard(peer->second, Clock::now());
  scheduler_.heard_result(identity);  // a benched worker works again
  std::string error;
  std::optional<protocol::TileResultView> view = protocol::decode_tile_result(bytes, error);
  if (!view) {
    const std::optional<uint64_t> job_id = protocol::tile_result_job_id(bytes);
    if (job_id && scheduler_.holds(identity, *job_id)) return on_bad_result(identity, *job_id, error);
    return on_bad_message(identity, error);
  }
  const protocol::TileResult& r = view->fields;
  if (detailed_stats_) note_round_trip(peer->second, r.job_id);
  switch (scheduler_.check_result(identity, r.job_id, r.frame_id, r.tile)) {
    case ResultCheck::Unknown:
      return scheduler_.drop_result(identity, r.job_id);  // from before a reconnect, or a frame long done
    case ResultCheck::WrongTile:
      return on_bad_result(identity, r.job_id,
                           "frame " + std::to_string(r.frame_id) + ", tile " + describe(r.tile) +
                               " is not what job " + std::to_string(r.job_id) + " asked for");
    case ResultCheck::NotNeeded:
      scheduler_.on_result(identity, r.job_id, r.frame_state_hash, Clock::now());  // its hash still votes
      return;
    case ResultCheck::Wanted:
      return use_result(identity, peer->second, *view, bytes.size());
  }
}

// Smoothed over about ten results: what the cluster panel shows.
void MasterSession::note_round_trip(Peer& peer, uint64_t job_id) {
  auto sent = peer.sent.find(job_id);
  if (sent == peer.sent.end()) return;
  const double ms = std::chrono::duration<double, std::milli>(Clock::now() - sent->second).count();
  peer.round_trip_ms = peer.round_trip_ms > 0.0 ? 0.9 * peer.round_trip_ms + 0.1 * ms : ms;
  peer.sent.erase(sent);
}

std::vector<PeerView> MasterSession::peer_views() const {
  std::vector<PeerView> views;
  const auto now = Clock::now();
  for (const auto& [identity, p] : peers_)
    views.push_back({p.name, p.number, p.threads, std::chrono::duration<double>(now - p.last_heard).count(),
                     p.round_trip_ms});
  std::sort(views.begin(), views.end(), [](const PeerView& a, const PeerView& b) { return a.number < b.number; });
  return views;
}

// The job's first result: its pixels go straight into the frame, then the
// scheduler decides whether they count (or are held for the frame's hash).
void MasterSession::use_result(const std::string& identity, Peer& peer, const protocol::TileResultView& view,
                               size_t bytes) {
  const protocol::TileResult& r = view.fields;
  OpenFrame& frame = frames_.at(r.frame_id);  // the scheduler knows the job, so its frame is open
  if (r.pixel_format != pixel_format_)
    return on_bad_result(identity, r.job_id, std::string("pixels as ") + pixel_format_name(r.pixel_format) +
                                                 ", the session asked for " + pixel_format_name(pixel_format_));
  FrameBuffer& pixels = *frame.pixels;
  const std::string error = protocol::copy_tile_pixels(view, pixels.pixel(r.tile.x, r.tile.y), pixels.row_bytes());
  if (!error.empty()) return on_bad_result(identity, r.job_id, error);
  if (!frame.surfaces.empty()) {
    if (view.surface_bytes.empty()) return on_bad_result(identity, r.job_id, "no pixel surfaces, which its frame asked for");
    protocol::copy_tile_surfaces(view, &frame.surfaces[size_t(r.tile.y) * size_t(pixels.width) + size_t(r.tile.x)],
                                 size_t(pixels.width));
  }
  const ResultVerdict verdict = scheduler_.on_result(identity, r.job_id, r.frame_state_hash, Clock::now());
  if (verdict == ResultVerdict::Accepted || verdict == ResultVerdict::Held) count_failures_against_workers(r.job_id);
  ++frame.record.tiles;
  frame.record.rays += r.rays;
  if (r.nonfinite_pixels > 0) {
    nonfinite_pixels_ += r.nonfinite_pixels;
    frame.record.nonfinite_pixels += r.nonfinite_pixels;
    if (++nonfinite_logged_ <= kLogFirst)
      log(peer.name + " rendered " + std::to_string(r.nonfinite_pixels) + " non-finite pixels in frame " +
          std::to_string(r.frame_id) + ", tile " + describe(r.tile) + ", and sent them as black");
  }
  if (detailed_stats_) {
    PeerStats& stats = frame.record.workers[peer.name];
    ++stats.tiles;
    stats.busy_seconds += r.render_seconds;
    stats.bytes_in += bytes;
  }
  if (tile_sources_) frame.record.tile_sources.push_back({r.tile, peer.number});
  ++accepted_;
  if (on_accepted) on_accepted(accepted_);
}

// The job goes to another worker, or to the master's own renderer when every
// worker that could take it failed it (render_own_jobs()).
void MasterSession::on_bad_result(const std::string& identity, uint64_t job_id, const std::string& error) {
  Peer& peer = peers_.at(identity);
  if (++failures_logged_ <= kLogFirst)
    log(peer.name + " sent a result for job " + std::to_string(job_id) + " that fails validation (" + error +
        "): the job goes to another worker");
  if (job_failures_.size() >= 4096) job_failures_.clear();  // jobs long done or cancelled
  JobFailures& failures = job_failures_[job_id];
  failures.workers.push_back(identity);
  failures.text += (failures.text.empty() ? "" : ", ") + peer.name + " (" + error + ")";
  scheduler_.on_bad_result(identity, job_id);
  if (scheduler_.answered(job_id)) count_failures_against_workers(job_id);  // a straggler copy passed first
}

// Another worker's result for the job passed: each worker that failed it
// was at fault, and one with three such results is quarantined.
void MasterSession::count_failures_against_workers(uint64_t job_id) {
  auto failed = job_failures_.find(job_id);
  if (failed == job_failures_.end()) return;
  const std::vector<std::string> workers = std::move(failed->second.workers);
  job_failures_.erase(failed);
  for (const std::string& identity : workers) {
    auto peer = peers_.find(identity);
    if (peer != peers_.end() && ++peer->second.failed_results >= kMaxFailedResults)
      quarantine_peer(identity, std::to_string(peer->second.failed_results) +
                                    " of its results failed validation where another worker's passed");
  }
}

// Jobs whose results failed on every worker that could take them: the master
// renders each as a worker would. Only when it cannot is the run over.
void MasterSession::render_own_jobs() {
  for (const JobAssignment& job : scheduler_.take_own_jobs()) {
    auto f = frames_.find(job.frame_id);
    if (f == frames_.end()) continue;
    auto failed = job_failures_.find(job.job_id);
    const std::string what = "job " + std::to_string(job.job_id) + " (frame " + std::to_string(job.frame_id) +
                             ", tile " + describe(job.tile) + ") failed validation on " +
                             (failed != job_failures_.end() ? failed->second.text : std::string("its workers"));
    if (failed != job_failures_.end()) job_failures_.erase(failed);
    if (!referee_ || follows_workers_) {  // a master whose VPL sets lost to its workers' would render another tile
      if (fatal_.empty())
        fatal_ = what + ", no other worker may take it and the master cannot render it" +
                 (follows_workers_ ? " as they would (its VPL sets differ from theirs)" : "") +
                 ": its frame can never complete";
      return;
    }
    if (++own_logged_ <= kLogFirst || own_logged_ % 100 == 0)  // always said, never a flood
      std::fprintf(stderr, "igi-master: %s: the master renders it itself (%llu so far)\n", what.c_str(),
                   static_cast<unsigned long long>(own_logged_));
    own_failures_[job.job_id] = what;
    referee_->request_tile(f->second.setup, f->second.settings, job.job_id, job.tile, pixel_format_);
  }
}

// The master's own tile goes through the checks a worker's does; it counts
// whatever its frame's vote (the master is the judge).
void MasterSession::use_own_result(const MasterRenderer::TileAnswer& answer) {
  auto failed = own_failures_.find(answer.job_id);
  const std::string what = failed != own_failures_.end() ? failed->second : "job " + std::to_string(answer.job_id);
  if (failed != own_failures_.end()) own_failures_.erase(failed);
  std::string error = answer.error;
  std::optional<protocol::TileResultView> view;
  if (error.empty()) view = protocol::decode_tile_result(answer.result, error);
  auto frame = view ? frames_.find(view->fields.frame_id) : frames_.end();
  if (view && frame == frames_.end()) return;  // the view moved on meanwhile
  if (view) {
    FrameBuffer& pixels = *frame->second.pixels;
    const TileJob& t = view->fields.tile;
    error = protocol::copy_tile_pixels(*view, pixels.pixel(t.x, t.y), pixels.row_bytes());
    if (error.empty() && !frame->second.surfaces.empty())
      protocol::copy_tile_surfaces(
          *view, &frame->second.surfaces[size_t(t.y) * size_t(pixels.width) + size_t(t.x)], size_t(pixels.width));
  }
  if (!error.empty()) {
    if (fatal_.empty()) fatal_ = what + ", and the master could not render it either (" + error + ")";
    return;
  }
  if (!scheduler_.on_own_result(answer.job_id)) return;
  ++own_tiles_;
  ++frame->second.record.tiles;
  frame->second.record.rays += view->fields.rays;
  if (view->fields.nonfinite_pixels > 0) {
    nonfinite_pixels_ += view->fields.nonfinite_pixels;
    frame->second.record.nonfinite_pixels += view->fields.nonfinite_pixels;
  }
}

void MasterSession::on_bad_message(const std::string& identity, const std::string& error) {
  ++bad_messages_;
  if (bad_messages_ <= 100 || bad_messages_ % 1000 == 0)
    log("dropped a bad message (" + std::to_string(bad_messages_) + " so far): " + error);
  // A peer that speaks another protocol version is told why, in our version.
  if (error.find("version") != std::string::npos) send(identity, protocol::Refuse{error});
  // A worker of this build never sends what does not decode: one that keeps doing so is broken.
  auto peer = peers_.find(identity);
  if (peer != peers_.end() && ++peer->second.failed_results >= kMaxFailedResults)
    quarantine_peer(identity, std::to_string(peer->second.failed_results) + " of its messages failed to decode");
}

// ---- Peers.

void MasterSession::drop_peer(const std::string& identity, const std::string& why) {
  auto it = peers_.find(identity);
  if (it == peers_.end()) return;
  log_peer(it->second.name + " " + why);
  scheduler_.remove_worker(identity);
  peers_.erase(it);
  forget_peer(identity);
}

// Told why, so it exits with its own status; its later messages are ignored.
void MasterSession::quarantine_peer(const std::string& identity, const std::string& why) {
  auto it = peers_.find(identity);
  if (it == peers_.end()) return;
  const std::string name = it->second.name;
  const std::string key = it->second.key_name;
  std::fprintf(stderr, "igi-master: %s quarantined: %s; it gets no more work%s\n", name.c_str(), why.c_str(),
               key.empty() ? "" : (", and its CURVE key '" + key + "' is refused from now on").c_str());
  send(identity, protocol::Bye{"quarantined by the master: " + why, protocol::ByeKind::Quarantined});
  scheduler_.remove_worker(identity);
  peers_.erase(it);
  if (zap_ && !key.empty()) zap_->quarantine(key);  // by key: a reconnection is a new connection, not a new worker
  quarantined_ids_.insert(identity);
  ++quarantined_count_;
  if (quarantined_names_.size() < kMaxQuarantinedNames) quarantined_names_.push_back(name + ": " + why);
}

void MasterSession::take_quarantined() {
  const char* why = referee_ ? "its VPL-set hash differs from the master's own for the frame "
                               "(another build, CPU, a fault, or a peer that does not render)"
                             : "its VPL-set hash differs from the one most of its frame's workers reported "
                               "(another build, CPU or a fault)";
  for (const WorkerId& id : scheduler_.take_quarantined()) quarantine_peer(id, why);
}

// The master's own hashes, as they are computed. One it could not compute
// (the scene does not fit here, say) is left to a vote among the workers.
void MasterSession::take_references() {
  if (!referee_) return;
  for (MasterRenderer::Answer& a : referee_->take()) {
    ++reference_frames_;
    reference_seconds_ += a.seconds;
    if (auto expected = expected_.find(a.frame_id); expected != expected_.end()) {
      expected->second = std::move(a);  // the frame is not added yet: add_frame() takes it
      continue;
    }
    if (!a.hash && ++referee_errors_ <= kLogFirst)
      log("frame " + std::to_string(a.frame_id) + ": the master cannot compute its VPL-set hash (" + a.error +
          "): its workers vote on it");
    scheduler_.set_reference(a.frame_id, a.hash);
  }
  for (const MasterRenderer::TileAnswer& a : referee_->take_tiles()) use_own_result(a);
}

// Every worker agrees on a frame's VPL sets and the master's own differ: the
// master is likelier wrong than they (a maths library 1 ulp off, which no
// version names, is enough). Authenticated workers are followed; anonymous
// ones could be two fakes, so the run ends at once, saying why.
void MasterSession::on_dispute(const HashDispute& d) {
  std::string names, libraries;
  for (const WorkerId& id : d.workers) {
    auto peer = peers_.find(id);
    const std::string name = peer != peers_.end() ? peer->second.name : "a departed worker";
    names += (names.empty() ? "" : ", ") + name;
    if (peer != peers_.end() && !peer->second.libraries.empty() && peer->second.libraries != runtime_libraries())
      libraries += "; " + name + " runs " + peer->second.libraries;
  }
  const std::string what =
      "frame " + std::to_string(d.frame_id) + ": the master's VPL-set hash " + hash_hex(d.callers_hash) +
      " differs from the one all its workers agree on (" + names + ": " + hash_hex(d.workers_hash) +
      "). The master is the odd one out: likely its maths library or CPU (the master runs " + runtime_libraries() +
      (libraries.empty() ? ", as they do: a library that differs under one version, LD_PRELOAD, another libm"
                           " dispatch for this CPU" : libraries) + ")";
  if (!zap_) {
    if (fatal_.empty())
      fatal_ = what + ". Without CURVE keys two agreeing workers could be two fakes, so the master cannot follow "
                      "them: run it where the workers' libraries are, or authenticate the workers (--authorized-keys)";
    return;
  }
  std::fprintf(stderr, "igi-master: %s. The workers are authenticated by their CURVE keys: the master follows their "
                       "agreement from now on (votes among them decide each frame)\n", what.c_str());
  follows_workers_ = true;
  scheduler_.follow_workers();
}

void MasterSession::heard(Peer& peer, Clock::time_point now) {
  peer.gaps[peer.gap_count++ % peer.gaps.size()] = std::chrono::duration<float>(now - peer.last_heard).count();
  peer.last_heard = now;
}

// How long a peer may be silent before it is declared dead: --timeout-ms, or
// four times the longest of its last 16 silences, at most four timeouts. A
// worker on a loaded machine whose messages come ever later gets longer; one
// that answers steadily, none (its silences stay near a heartbeat).
MasterSession::Clock::duration MasterSession::patience(const Peer& peer) const {
  const auto timeout = std::chrono::milliseconds(options_.timeout_ms);
  const size_t n = std::min<size_t>(peer.gap_count, peer.gaps.size());
  const float longest = n ? *std::max_element(peer.gaps.begin(), peer.gaps.begin() + long(n)) : 0.0f;
  const auto learned = std::chrono::duration_cast<Clock::duration>(std::chrono::duration<float>(4.0f * longest));
  return std::clamp<Clock::duration>(learned, timeout, 4 * timeout);
}

// Liveness and heartbeats, a few times per heartbeat interval: O(peers), not per message.
void MasterSession::sweep(Clock::time_point now) {
  const auto heartbeat = std::chrono::milliseconds(options_.heartbeat_ms);
  const auto interval = std::clamp(heartbeat / 4, std::chrono::milliseconds(5), std::chrono::milliseconds(100));
  // A master that was not listening (its process stopped, or descheduled on
  // a loaded machine, or a caller that did not pump) has its peers' messages
  // still queued: that time is not their silence.
  if (const auto away = now - last_sweep_; away > 2 * interval + heartbeat) {
    const auto stall = away - interval;
    for (auto& [identity, peer] : peers_) peer.last_heard += stall;
    unlistened_seconds_ += std::chrono::duration<double>(stall).count();
  }
  last_sweep_ = now;
  std::vector<std::pair<std::string, Clock::duration>> dead;
  for (auto& [identity, peer] : peers_) {
    if (const auto wait = patience(peer); now - peer.last_heard > wait) dead.emplace_back(identity, wait);
    else if (now - peer.last_sent > heartbeat) send(identity, protocol::Heartbeat{});
  }
  declared_dead_ += dead.size();
  for (const auto& [identity, wait] : dead) {
    const long ms = long(std::chrono::duration_cast<std::chrono::milliseconds>(wait).count());
    drop_peer(identity, "silent for " + std::to_string(ms) + " ms" +
                            (ms > options_.timeout_ms ? " (four times its longest recent silence; --timeout-ms " +
                                                            std::to_string(options_.timeout_ms) + ")"
                                                      : "") +
                            ": declared dead, its jobs go to others (a worker on a loaded machine can be this slow "
                            "to answer: --timeout-ms gives it longer)");
  }
  next_sweep_ = now + interval;
}

void MasterSession::dispatch(const std::vector<JobAssignment>& jobs) {
  for (const JobAssignment& job : jobs) {
    auto peer = peers_.find(job.worker);
    auto f = frames_.find(job.frame_id);
    if (peer == peers_.end() || f == frames_.end()) continue;
    if (!f->second.started) f->second.started = Clock::now();
    size_t bytes = 0;
    if (peer->second.frames_sent.insert(job.frame_id).second)
      bytes += send(job.worker, protocol::FrameSetupMsg{f->second.setup, f->second.settings});
    bytes += send(job.worker, protocol::TileJobMsg{job.frame_id, job.job_id, job.tile});
    if (detailed_stats_) {
      f->second.record.workers[peer->second.name].bytes_out += bytes;
      std::map<uint64_t, Clock::time_point>& sent = peer->second.sent;
      if (sent.size() > 1024) sent.clear();  // results that never came (reissued elsewhere): forget them
      sent[job.job_id] = Clock::now();
    }
  }
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
  std::string text = "frame " + std::to_string(split->frame_id) + " waits: its workers disagree on the VPL sets (";
  bool first = true;
  for (const auto& [hash, voters] : split->voters) {
    for (const WorkerId& v : voters) {
      auto peer = peers_.find(v);
      text += (first ? "" : ", ") + (peer != peers_.end() ? peer->second.name : std::string("a departed worker")) +
              ": hash " + hash_hex(hash);
      first = false;
    }
  }
  return text + ") and no other worker breaks the tie; start another worker of this build";
}

std::vector<CompletedFrame> MasterSession::take_completed() {
  std::vector<CompletedFrame> done;
  for (uint64_t frame_id : scheduler_.take_completed_frames()) {
    OpenFrame& f = frames_.at(frame_id);
    const SchedulerStats& s = scheduler_.stats();
    f.record.seconds = f.started ? std::chrono::duration<double>(Clock::now() - *f.started).count() : 0.0;
    f.record.completed_at = std::chrono::duration<double>(Clock::now() - began_).count();
    f.record.reissued = s.reissued;
    f.record.duplicated = s.duplicated;
    f.record.late_dropped = s.late_dropped;
    f.record.verified = s.verified;
    f.record.failed_results = s.failed_results;
    f.record.quarantined = quarantined_count_;
    f.record.own_tiles = own_tiles_;
    done.push_back(CompletedFrame{f.setup, std::move(f.pixels), std::move(f.record), std::move(f.surfaces)});
    frames_.erase(frame_id);
    for (auto& [identity, peer] : peers_) peer.frames_sent.erase(frame_id);
  }
  return done;
}

void MasterSession::close(const std::string& reason) {
  if (peer_lines_held_ > 0)
    log(std::to_string(peer_lines_held_) + " more joins and departures in the last minute, not logged one by one");
  peer_lines_held_ = 0;
  for (const auto& [identity, peer] : peers_) send(identity, protocol::Bye{reason});
  peers_.clear();
  // The goodbyes must leave before the process does (linger 0 would drop them
  // when the context ends): up to a second, then they are abandoned.
  router_.set(zmq::sockopt::linger, 1000);
  if (refused_keys_ + failed_handshakes_ > 0)
    log("CURVE: refused " + std::to_string(refused_keys_) + " unknown worker keys; " +
        std::to_string(failed_handshakes_) + " failed handshakes");
}

}  // namespace igi
