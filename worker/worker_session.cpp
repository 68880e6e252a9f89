#include "worker_session.h"

#include <cstdio>
#include <thread>

#include "build_info.h"
#include "protocol/codec.h"
#include "protocol/socket.h"
#include "render/frame_renderer.h"
#include "scene/accel.h"
#include "scene/load_scene.h"

namespace igi {

struct WorkerSession::Loaded {
  Scene scene;
  std::unique_ptr<Accel> accel;
  std::unique_ptr<LightSet> lights;
  std::unique_ptr<RenderPool> pool;
};

WorkerSession::WorkerSession(WorkerOptions options)
    : options_(std::move(options)), cache_(options_.cache_dir, options_.search_dirs) {
  if (options_.threads <= 0) options_.threads = default_thread_count();
  if (options_.build_id.empty()) options_.build_id = kBuildId;
}

WorkerSession::~WorkerSession() {
  if (loading_.valid()) loading_.wait();
}

void WorkerSession::log(const std::string& text) const {
  if (!options_.quiet) std::fprintf(stderr, "igi-worker: %s\n", text.c_str());
}

void WorkerSession::send(zmq::socket_t& socket, const protocol::Message& message) {
  protocol::send(socket, message);
  last_sent_ = Clock::now();
}

WorkerExit WorkerSession::run() {
  zmq::context_t context;
  auto last_contact = Clock::now();
  double backoff = 1.0;
  for (;;) {
    Outcome outcome = serve(context);
    if (outcome == Outcome::Bye) return WorkerExit::Bye;
    if (outcome == Outcome::Refused) return WorkerExit::Refused;
    if (welcome_) last_contact = Clock::now(), backoff = 1.0;  // it was alive until just now
    welcome_.reset();
    double silent = std::chrono::duration<double>(Clock::now() - last_contact).count();
    if (silent + backoff > options_.give_up_seconds) {
      if (failed_handshakes_ == 0) log("no master for " + std::to_string(int(silent)) + " s: giving up");
      else announce("no master for " + std::to_string(int(silent)) + " s: giving up; " + handshake_hint());
      return WorkerExit::GaveUp;
    }
    if (failed_handshakes_ > 0) log(handshake_hint());
    log("master lost; reconnecting in " + std::to_string(int(backoff)) + " s");
    std::this_thread::sleep_for(std::chrono::duration<double>(backoff));
    backoff = std::min(backoff * 2.0, 32.0);
  }
}

WorkerSession::Outcome WorkerSession::serve(zmq::context_t& context) {
  zmq::socket_t socket(context, zmq::socket_type::dealer);
  protocol::configure(socket);
  if (options_.curve) protocol::make_curve_client(socket, *options_.curve);
  protocol::SocketMonitor monitor(context, socket,
                                  ZMQ_EVENT_HANDSHAKE_SUCCEEDED | ZMQ_EVENT_HANDSHAKE_FAILED_NO_DETAIL |
                                      ZMQ_EVENT_HANDSHAKE_FAILED_PROTOCOL | ZMQ_EVENT_HANDSHAKE_FAILED_AUTH);
  socket.connect(options_.endpoint);
  send(socket, protocol::Hello{options_.build_id, "native", uint32_t(options_.threads)});
  auto last_heard = Clock::now();
  for (;;) {
    wait_for_work(socket);
    if (auto outcome = check_handshakes(monitor)) return *outcome;
    while (auto received = protocol::receive(socket, 0, false)) {
      last_heard = Clock::now();
      if (!received->message) {
        log("dropped a bad message: " + received->error);
      } else if (auto outcome = handle(socket, *received->message)) {
        return *outcome;
      }
    }
    poll_loading();
    if (loaded_ && loaded_->pool)
      for (protocol::TileResult& r : loaded_->pool->take_results()) send(socket, r);
    const auto heartbeat = std::chrono::milliseconds(welcome_ ? welcome_->heartbeat_ms : 500);
    if (Clock::now() - last_sent_ > heartbeat) send(socket, protocol::Heartbeat{});
    if (Clock::now() - last_heard > 4 * heartbeat + std::chrono::seconds(welcome_ ? 0 : 2))
      return Outcome::MasterLost;
  }
}

void WorkerSession::announce(const std::string& text) const {
  std::fprintf(stderr, "igi-worker: %s\n", text.c_str());  // even when quiet: it is why we exit
}

WorkerSession::Outcome WorkerSession::refused(const std::string& why) const {
  announce(why);
  return Outcome::Refused;
}

std::string WorkerSession::handshake_hint() const {
  return std::to_string(failed_handshakes_) + " handshakes with the master at " + options_.endpoint + " failed" +
         (options_.curve ? ": is --master-key the public key of that master's --key?" : ": is it an igi-master?");
}

// A refused handshake never becomes a message: zmq would retry it for ever.
std::optional<WorkerSession::Outcome> WorkerSession::check_handshakes(protocol::SocketMonitor& monitor) {
  const std::string& master = options_.endpoint;
  for (const protocol::SocketEvent& e : monitor.take_events()) {
    if (e.event == ZMQ_EVENT_HANDSHAKE_SUCCEEDED) {
      failed_handshakes_ = 0;
    } else if (e.event == ZMQ_EVENT_HANDSHAKE_FAILED_AUTH) {
      const std::string key = options_.curve ? options_.curve->own.public_key : "none: no --key";
      return refused("the master at " + master + " refused this worker's key (public key " + key + ", ZAP status " +
                     std::to_string(e.value) + "): its operator must add this worker's NAME.pub to the master's "
                     "--authorized-keys");
    } else if (e.event == ZMQ_EVENT_HANDSHAKE_FAILED_PROTOCOL &&
               e.value == ZMQ_PROTOCOL_ERROR_ZMTP_MECHANISM_MISMATCH) {
      return refused(options_.curve ? "the master at " + master + " does not use CURVE (no --key): connect without "
                                          "--master-key and --key, or start the master with CURVE"
                                    : "the master at " + master + " requires CURVE: give --master-key MASTER.pub and "
                                          "--key WORKER.key (make keys with igi-keys new NAME)");
    } else {
      ++failed_handshakes_;  // a wrong --master-key, or a relay whose master is down: retried until --give-up
    }
  }
  return std::nullopt;
}

// Sleeps until a message arrives, a result is ready, or a few ms pass (heartbeats, loading).
void WorkerSession::wait_for_work(zmq::socket_t& socket) {
  std::vector<zmq::pollitem_t> items{{socket.handle(), 0, ZMQ_POLLIN, 0}};
  if (loaded_ && loaded_->pool) items.push_back({nullptr, loaded_->pool->results_fd(), ZMQ_POLLIN, 0});
  zmq::poll(items, std::chrono::milliseconds(5));
}

std::optional<WorkerSession::Outcome> WorkerSession::handle(zmq::socket_t& socket, const protocol::Message& m) {
  if (auto* w = std::get_if<protocol::Welcome>(&m)) {
    on_welcome(socket, *w);
  } else if (auto* r = std::get_if<protocol::Refuse>(&m)) {
    log("refused by master: " + r->reason);
    return Outcome::Refused;
  } else if (auto* bye = std::get_if<protocol::Bye>(&m)) {
    log("master said bye: " + bye->reason);
    return Outcome::Bye;
  } else if (auto* data = std::get_if<protocol::SceneData>(&m)) {
    try {
      start_loading(cache_.store(*data));
    } catch (const std::exception& e) {
      log(e.what());
      return Outcome::Refused;
    }
  } else if (std::holds_alternative<protocol::FrameSetupMsg>(m) || std::holds_alternative<protocol::TileJobMsg>(m)) {
    if (!welcome_) return std::nullopt;  // not ours to render yet
    if (loaded_ && loaded_->pool) {
      if (auto* f = std::get_if<protocol::FrameSetupMsg>(&m)) loaded_->pool->add_frame(f->frame);
      else loaded_->pool->add_job(std::get<protocol::TileJobMsg>(m));
    } else {
      waiting_.push_back(m);
    }
  }
  return std::nullopt;
}

void WorkerSession::on_welcome(zmq::socket_t& socket, const protocol::Welcome& welcome) {
  const bool same_scene = welcome_ && loaded_ && welcome_->scene_hash == welcome.scene_hash &&
                          welcome_->scene_name == welcome.scene_name;
  welcome_ = welcome;
  waiting_.clear();
  if (same_scene) {  // a reconnect to the same session: keep the BVH, fresh pool
    loaded_->pool = std::make_unique<RenderPool>(SceneContext{loaded_->scene, *loaded_->accel, *loaded_->lights},
                                                 welcome.settings, options_.threads);
    return;
  }
  loaded_.reset();
  if (welcome.scene_hash == 0) return start_loading(welcome.scene_name);  // built-in
  if (auto path = cache_.find(welcome.scene_name, welcome.scene_hash)) return start_loading(*path);
  log("scene " + welcome.scene_name + " not found locally: asking the master for it");
  send(socket, protocol::SceneRequest{welcome.scene_hash});
}

// Loads and builds on another thread; the socket loop keeps heartbeating.
void WorkerSession::start_loading(const std::string& scene) {
  const RenderSettings settings = welcome_->settings;
  const int threads = options_.threads;
  loading_ = std::async(std::launch::async, [scene, settings, threads] {
    auto loaded = std::make_shared<Loaded>();
    loaded->scene = load_scene(scene);
    loaded->accel = std::make_unique<Accel>(loaded->scene);
    loaded->lights = std::make_unique<LightSet>(loaded->scene);
    loaded->pool = std::make_unique<RenderPool>(SceneContext{loaded->scene, *loaded->accel, *loaded->lights},
                                                settings, threads);
    return loaded;
  });
}

void WorkerSession::poll_loading() {
  if (!loading_.valid() || loading_.wait_for(std::chrono::seconds(0)) != std::future_status::ready) return;
  try {
    loaded_ = loading_.get();
    log("scene " + loaded_->scene.name + " ready: " + std::to_string(loaded_->scene.triangles.size()) + " triangles");
  } catch (const std::exception& e) {
    log(std::string("cannot load the scene: ") + e.what());
    return;
  }
  for (const protocol::Message& m : waiting_) {
    if (auto* f = std::get_if<protocol::FrameSetupMsg>(&m)) loaded_->pool->add_frame(f->frame);
    else loaded_->pool->add_job(std::get<protocol::TileJobMsg>(m));
  }
  waiting_.clear();
}

}  // namespace igi
