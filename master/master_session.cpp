#include "master_session.h"

#include <algorithm>
#include <cerrno>
#include <cstdio>

#include "build_info.h"
#include "protocol/codec.h"
#include "protocol/socket.h"
#include "render/frame_renderer.h"

namespace igi {

MasterSession::MasterSession(const MasterOptions& options, SceneSource scene, zmq::context_t& context,
                             const protocol::CurveServerKeys* curve)
    : options_(options),
      scene_(std::move(scene)),
      router_(context, zmq::socket_type::router),
      scheduler_(options.credits, 2),
      session_id_(uint64_t(Clock::now().time_since_epoch().count())) {
  protocol::configure(router_, protocol::kMaxWorkerMessageBytes);
  router_.set(zmq::sockopt::router_mandatory, 1);  // a send to a vanished peer fails instead of vanishing
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
  router_.bind(options.listen);
  endpoint_ = router_.get(zmq::sockopt::last_endpoint);
  scheduler_.force_duplicates(options.force_duplicates);
}

void MasterSession::log(const std::string& text) const {
  if (!options_.render.quiet) std::fprintf(stderr, "igi-master: %s\n", text.c_str());
}

void MasterSession::send(const std::string& identity, const protocol::Message& message) {
  const std::vector<uint8_t> bytes = protocol::encode(message);
  try {
    router_.send(zmq::buffer(identity), zmq::send_flags::sndmore);
    router_.send(zmq::buffer(bytes), zmq::send_flags::none);
  } catch (const zmq::error_t&) {
    return;  // the peer is gone; liveness will notice
  }
  auto it = peers_.find(identity);
  if (it == peers_.end()) return;
  it->second.last_sent = Clock::now();
  if (auto* r = std::get_if<protocol::TileJobMsg>(&message)) {
    auto f = frames_.find(r->frame_id);
    if (f != frames_.end()) f->second.record.workers[it->second.name].bytes_out += bytes.size();
  }
}

void MasterSession::add_frame(const FrameSetup& frame) {
  OpenFrame open;
  open.setup = frame;
  open.image = Image(frame.width, frame.height);
  open.record.frame_id = frame.frame_id;
  frames_[frame.frame_id] = std::move(open);
  const int border = tile_border(options_.render.settings);
  const int tile = options_.render.tile_size;
  scheduler_.add_frame(frame.frame_id, make_tiles(frame.width, frame.height, tile, tile, border));
}

std::vector<CompletedFrame> MasterSession::pump(int timeout_ms) {
  const auto end = Clock::now() + std::chrono::milliseconds(timeout_ms);
  std::vector<CompletedFrame> done;
  do {
    wait_for_traffic(1);
    serve_security();
    if (auto received = protocol::receive(router_, 0, true)) {
      if (received->message) handle(received->identity, *received->message, received->bytes);
      else on_bad_message(received->identity, received->error);
    }
    check_liveness();
    assign_jobs();
    send_heartbeats();
    for (CompletedFrame& f : take_completed()) done.push_back(std::move(f));
  } while (Clock::now() < end && done.empty());
  return done;
}

void MasterSession::wait_for_traffic(int timeout_ms) {
  std::vector<zmq::pollitem_t> items{{router_.handle(), 0, ZMQ_POLLIN, 0}};
  if (zap_) items.push_back({zap_->socket().handle(), 0, ZMQ_POLLIN, 0});
  try {
    zmq::poll(items, std::chrono::milliseconds(timeout_ms));
  } catch (const zmq::error_t& e) {
    if (e.num() != EINTR) throw;  // a signal: the caller's loop decides
  }
}

// Handshakes wait for these answers; a peer is only a peer once they pass.
void MasterSession::serve_security() {
  if (zap_)
    for (const protocol::ZapDecision& d : zap_->answer_waiting()) on_zap_decision(d);
  if (!monitor_) return;
  for (size_t n = monitor_->take_events().size(); n > 0; --n) {
    // A flood of these is an attack or a misconfigured farm: log the first few, count all.
    if (++failed_handshakes_ <= 5)
      log("a peer failed the CURVE handshake (it does not use CURVE, or has another master public key)");
  }
}

void MasterSession::on_zap_decision(const protocol::ZapDecision& d) {
  if (d.allowed) return log("CURVE key '" + d.name + "' from " + d.address + " accepted");
  ++refused_keys_;
  // Each key once, and a bounded set: a peer may try a new key per connection.
  if (refused_logged_.size() < 1000 && refused_logged_.insert(d.public_key).second)
    std::fprintf(stderr,
                 "igi-master: refused worker key %s from %s: not among --authorized-keys (%llu refused so far)\n",
                 d.public_key.empty() ? "(not CURVE)" : d.public_key.c_str(), d.address.c_str(),
                 static_cast<unsigned long long>(refused_keys_));
}

void MasterSession::handle(const std::string& identity, const protocol::Message& message, size_t bytes) {
  auto peer = peers_.find(identity);
  if (peer != peers_.end()) peer->second.last_heard = Clock::now();
  if (auto* hello = std::get_if<protocol::Hello>(&message)) return on_hello(identity, *hello);
  if (peer == peers_.end()) return on_bad_message(identity, "message from a peer that never said hello");
  if (auto* result = std::get_if<protocol::TileResult>(&message)) {
    auto f = frames_.find(result->frame_id);
    if (f != frames_.end()) f->second.record.workers[peer->second.name].bytes_in += bytes;
    on_result(identity, *const_cast<protocol::TileResult*>(result));
  } else if (auto* request = std::get_if<protocol::SceneRequest>(&message)) {
    if (request->scene_hash != scene_.hash || scene_.bytes.empty()) return drop_peer(identity, "asked for an unknown scene");
    log(peer->second.name + " has no copy of " + scene_.name + ": sending " + std::to_string(scene_.bytes.size()) + " bytes");
    send(identity, protocol::SceneData{scene_.hash, scene_.name, scene_.bytes});
  } else if (auto* bye = std::get_if<protocol::Bye>(&message)) {
    drop_peer(identity, "left: " + bye->reason);
  } else if (!std::holds_alternative<protocol::Heartbeat>(message)) {
    on_bad_message(identity, std::string("unexpected ") + protocol::message_name(protocol::type_of(message)));
  }
}

void MasterSession::on_hello(const std::string& identity, const protocol::Hello& hello) {
  if (hello.build_id != kBuildId) {
    const std::string reason = "build '" + hello.build_id + "' differs from the master's '" + kBuildId +
                               "': tiles would not match bit for bit";
    log("refused a worker: " + reason);
    peers_.erase(identity);
    return send(identity, protocol::Refuse{reason});
  }
  Peer& peer = peers_[identity];
  peer.name = "worker-" + std::to_string(next_peer_++);
  peer.last_heard = peer.last_sent = Clock::now();
  peer.frames_sent.clear();
  scheduler_.remove_worker(identity);  // a reconnect: its old jobs go back first
  // Enough jobs to keep every thread busy while results travel.
  const int credits = std::max<int>(options_.credits, 2 * int(std::min<uint32_t>(hello.threads, 32)));
  scheduler_.add_worker(identity, credits);
  log(peer.name + " joined (" + std::to_string(hello.threads) + " threads)");
  protocol::Welcome w;
  w.session = session_id_;
  w.scene_name = scene_.name;
  w.scene_hash = scene_.hash;
  w.scene_size = scene_.bytes.size();
  w.settings = options_.render.settings;
  w.credits = uint32_t(std::min(credits, 64));
  w.heartbeat_ms = uint32_t(options_.heartbeat_ms);
  send(identity, w);
}

void MasterSession::on_result(const std::string& identity, protocol::TileResult& result) {
  const Peer& peer = peers_.at(identity);
  const ResultVerdict verdict = scheduler_.on_result(identity, result.job_id, result.frame_state_hash);
  if (verdict == ResultVerdict::HashMismatch) {
    log(peer.name + " computed different VPL sets (hash " + std::to_string(result.frame_state_hash) +
        "): reported and given no more work");
    send(identity, protocol::Bye{"VPL-set hash differs from the other workers'"});
    peers_.erase(identity);
    return;
  }
  if (verdict != ResultVerdict::Accepted) return;
  auto f = frames_.find(result.frame_id);
  if (f == frames_.end()) return;
  OpenFrame& frame = f->second;
  const TileJob& t = result.tile;
  if (t.x + t.w > frame.image.width || t.y + t.h > frame.image.height) return on_bad_message(identity, "tile outside the image");
  for (int y = 0; y < t.h; ++y)
    std::copy_n(result.pixels.begin() + size_t(y) * t.w, t.w, frame.image.pixels.begin() + size_t(t.y + y) * frame.image.width + t.x);
  PeerStats& stats = frame.record.workers[peer.name];
  ++stats.tiles;
  stats.busy_seconds += result.render_seconds;
  frame.record.rays += result.rays;
  ++frame.record.tiles;
  ++accepted_;
  if (on_accepted) on_accepted(accepted_);
}

void MasterSession::on_bad_message(const std::string& identity, const std::string& error) {
  ++bad_messages_;
  log("dropped a bad message: " + error);
  // A peer that speaks another protocol version is told why, in our version.
  if (error.find("version") != std::string::npos) send(identity, protocol::Refuse{error});
}

void MasterSession::drop_peer(const std::string& identity, const std::string& why) {
  auto it = peers_.find(identity);
  if (it == peers_.end()) return;
  log(it->second.name + " " + why);
  scheduler_.remove_worker(identity);
  peers_.erase(it);
}

void MasterSession::check_liveness() {
  const auto now = Clock::now();
  std::vector<std::string> dead;
  for (const auto& [identity, peer] : peers_)
    if (now - peer.last_heard > std::chrono::milliseconds(options_.timeout_ms)) dead.push_back(identity);
  for (const std::string& identity : dead)
    drop_peer(identity, "silent for " + std::to_string(options_.timeout_ms) + " ms: declared dead, its jobs go to others");
}

void MasterSession::assign_jobs() {
  for (auto& [identity, peer] : peers_) {
    while (auto job = scheduler_.next_job(identity)) {
      auto f = frames_.find(job->frame_id);
      if (f == frames_.end()) continue;
      if (!f->second.started) f->second.started = Clock::now();
      if (peer.frames_sent.insert(job->frame_id).second) send(identity, protocol::FrameSetupMsg{f->second.setup});
      send(identity, protocol::TileJobMsg{job->frame_id, job->job_id, job->tile});
    }
  }
}

void MasterSession::send_heartbeats() {
  const auto now = Clock::now();
  for (auto& [identity, peer] : peers_)
    if (now - peer.last_sent > std::chrono::milliseconds(options_.heartbeat_ms)) send(identity, protocol::Heartbeat{});
}

std::vector<CompletedFrame> MasterSession::take_completed() {
  std::vector<CompletedFrame> done;
  for (uint64_t frame_id : scheduler_.take_completed_frames()) {
    OpenFrame& f = frames_.at(frame_id);
    const SchedulerStats& s = scheduler_.stats();
    f.record.seconds = f.started ? std::chrono::duration<double>(Clock::now() - *f.started).count() : 0.0;
    f.record.reissued = s.reissued;
    f.record.duplicated = s.duplicated;
    f.record.late_dropped = s.late_dropped;
    done.push_back(CompletedFrame{f.setup, std::move(f.image), f.record});
    frames_.erase(frame_id);
  }
  return done;
}

void MasterSession::close(const std::string& reason) {
  for (const auto& [identity, peer] : peers_) send(identity, protocol::Bye{reason});
  peers_.clear();
  if (refused_keys_ + failed_handshakes_ > 0)
    log("CURVE: refused " + std::to_string(refused_keys_) + " unknown worker keys; " +
        std::to_string(failed_handshakes_) + " failed handshakes");
}

}  // namespace igi
