#include "worker_session.h"

#include <cstdio>
#include <cstring>
#include <thread>

#include "build_id.h"
#include "protocol/codec.h"
#include "protocol/socket.h"
#include "render/frame_renderer.h"
#include "scene/accel.h"
#include "scene/libraries.h"
#include "scene/load_scene.h"
#include "scene/scene_file.h"

namespace igi {
namespace {

constexpr int kLogFirst = 5;  // non-finite pixels are logged this often, then only counted
constexpr double kFirstBackoff = 0.25, kMaxBackoff = 32.0;

// The scene as a worker holds it: the file (or built-in name) and the sky it stands under.
std::string scene_key(const protocol::Welcome& w) {
  uint32_t sky[3];
  std::memcpy(sky, &w.environment[0], sizeof sky);
  uint32_t rotation;
  std::memcpy(&rotation, &w.environment_rotation, sizeof rotation);
  return w.scene_name + "#" + hash_hex(w.scene_hash) + "#" + std::to_string(sky[0]) + "," + std::to_string(sky[1]) +
         "," + std::to_string(sky[2]) + "#" + w.environment_map + "#" + hash_hex(w.environment_map_hash) + "#" +
         std::to_string(rotation) + "#" + light_units_name(w.light_units);
}

}  // namespace

struct WorkerSession::Loaded {
  std::unique_ptr<SceneState> scene;  // with its BVH and lights, posed frame by frame
  std::unique_ptr<RenderPool> pool;   // made for each connection
};

WorkerSession::WorkerSession(WorkerOptions options)
    : options_(std::move(options)), cache_(std::make_shared<SceneCache>(options_.cache_dir, options_.search_dirs)) {
  if (options_.threads <= 0) options_.threads = default_thread_count();
  if (options_.build_id.empty()) options_.build_id = igi::build_id();
}

WorkerSession::~WorkerSession() {
  if (loading_.valid()) loading_.wait();
}

void WorkerSession::log(const std::string& text) const {
  if (!options_.quiet) std::fprintf(stderr, "igi-worker: %s\n", text.c_str());
}

void WorkerSession::announce(const std::string& text) const {
  std::fprintf(stderr, "igi-worker: %s\n", text.c_str());  // even when quiet: it is why we exit
}

// Never blocks: with the master's queue full (it stopped reading) the message
// is dropped; the master reissues a lost result, and silence ends the connection.
void WorkerSession::send(zmq::socket_t& socket, const protocol::Message& message) {
  if (protocol::try_send(socket, message)) last_sent_ = Clock::now();
}

WorkerExit WorkerSession::run() {
  zmq::context_t context;
  auto last_contact = Clock::now();
  double backoff = kFirstBackoff;
  for (;;) {
    const Outcome outcome = serve(context);
    if (outcome == Outcome::Bye) return WorkerExit::Bye;
    if (outcome == Outcome::Refused) return WorkerExit::Refused;
    if (outcome == Outcome::Quarantined) return WorkerExit::Quarantined;
    if (outcome == Outcome::SceneFailed) return WorkerExit::SceneFailed;
    if (outcome == Outcome::RenderFailed) return WorkerExit::RenderFailed;
    if (welcome_) last_contact = Clock::now(), backoff = kFirstBackoff;  // it was alive until just now
    welcome_.reset();
    const double silent = std::chrono::duration<double>(Clock::now() - last_contact).count();
    if (silent + backoff > options_.give_up_seconds) {
      if (failed_handshakes_ == 0) log("no master for " + std::to_string(int(silent)) + " s: giving up");
      else announce("no master for " + std::to_string(int(silent)) + " s: giving up; " + handshake_hint());
      return WorkerExit::GaveUp;
    }
    if (failed_handshakes_ > 0) log(handshake_hint());
    char text[64];
    std::snprintf(text, sizeof text, "master lost; reconnecting in %.2g s", backoff);
    log(text);
    std::this_thread::sleep_for(std::chrono::duration<double>(backoff));
    backoff = std::min(std::max(2.0 * backoff, 1.0), kMaxBackoff);
  }
}

WorkerSession::Outcome WorkerSession::serve(zmq::context_t& context) {
  zmq::socket_t socket(context, zmq::socket_type::dealer);
  protocol::configure(socket);
  if (options_.curve) protocol::make_curve_client(socket, *options_.curve);
  protocol::SocketMonitor monitor(context, socket,
                                  ZMQ_EVENT_HANDSHAKE_SUCCEEDED | ZMQ_EVENT_HANDSHAKE_FAILED_NO_DETAIL |
                                      ZMQ_EVENT_HANDSHAKE_FAILED_PROTOCOL | ZMQ_EVENT_HANDSHAKE_FAILED_AUTH |
                                      ZMQ_EVENT_DISCONNECTED);
  protocol::connect(socket, options_.endpoint);
  const protocol::Hello hello{options_.build_id, "native", uint32_t(options_.threads), runtime_libraries()};
  send(socket, hello);
  auto last_heard = Clock::now();
  for (;;) {
    wait_for_work(socket);
    // The connection's events are taken before the messages are read: a master
    // that says Bye and exits is seen to disconnect, but its Bye, queued before
    // the disconnect, must still be read (the worker would otherwise reconnect
    // to a master that is gone, and retry until --give-up).
    const auto connection = check_connection(monitor);
    while (auto received = protocol::receive(socket, 0, false)) {
      last_heard = Clock::now();
      if (!received->message) {
        log("dropped a bad message: " + received->error);
      } else if (auto outcome = handle(*received->message)) {
        return *outcome;
      }
    }
    if (connection) return *connection;
    if (auto outcome = poll_loading(socket)) return *outcome;
    if (auto outcome = check_failure(socket)) return *outcome;
    send_results(socket);
    const auto heartbeat = std::chrono::milliseconds(welcome_ ? welcome_->heartbeat_ms : 500);
    // Until welcomed, the Hello again instead: a master accepting many
    // connections at once can lose the first one's with its connection, and
    // answers a repeat on a connection it knows with the same Welcome.
    if (Clock::now() - last_sent_ > heartbeat) {
      if (welcome_) send(socket, protocol::Heartbeat{});
      else send(socket, hello);
    }
    // Longer than the master waits for us: it declares us dead (and reissues our jobs) first.
    const auto patience = welcome_ ? std::chrono::milliseconds(welcome_->timeout_ms) + 2 * heartbeat
                                   : 4 * heartbeat + std::chrono::seconds(2);
    if (Clock::now() - last_heard > patience) return Outcome::MasterLost;
  }
}

void WorkerSession::send_results(zmq::socket_t& socket) {
  if (!loaded_ || !loaded_->pool) return;
  for (protocol::TileResult& r : loaded_->pool->take_results()) {
    if (r.nonfinite_pixels > 0) {
      nonfinite_pixels_ += r.nonfinite_pixels;
      if (++nonfinite_logged_ <= kLogFirst)
        log("frame " + std::to_string(r.frame_id) + ": " + std::to_string(r.nonfinite_pixels) +
            " non-finite pixels sent as black (" + std::to_string(nonfinite_pixels_) + " so far)");
    }
    r.pixel_codec = welcome_->pixel_codec;
    send(socket, r);
  }
}

WorkerSession::Outcome WorkerSession::refused(const std::string& why) const {
  announce(why);
  return Outcome::Refused;
}

std::string WorkerSession::handshake_hint() const {
  char last[96];
  std::snprintf(last, sizeof last, " (the last: zmq event 0x%x, value %u)", unsigned(last_failure_.event),
                unsigned(last_failure_.value));
  std::string hint = std::to_string(failed_handshakes_) + " handshakes with the master at " + options_.endpoint +
                     " failed" + last;
  if (options_.curve) return hint + ": is --master-key the public key of that master's --key?";
  hint += ": is it an igi-master?";
  // A master that requires CURVE names the mismatch in its greeting, but when
  // it reads our whole greeting in one go (a loaded machine) zmq closes the
  // connection before that greeting is sent: the handshake just breaks off.
  if (last_failure_.event == ZMQ_EVENT_HANDSHAKE_FAILED_NO_DETAIL)
    hint += " If it requires CURVE (it then closes the connection during the handshake, as here), give --master-key "
            "MASTER.pub and --key WORKER.key";
  return hint;
}

// A refused handshake never becomes a message: zmq would retry it for ever.
// A connection that closes after a Welcome means the master process ended.
std::optional<WorkerSession::Outcome> WorkerSession::check_connection(protocol::SocketMonitor& monitor) {
  const std::string& master = options_.endpoint;
  for (const protocol::SocketEvent& e : monitor.take_events()) {
    if (e.event == ZMQ_EVENT_HANDSHAKE_SUCCEEDED) {
      failed_handshakes_ = 0;
    } else if (e.event == ZMQ_EVENT_DISCONNECTED) {
      if (welcome_) return Outcome::MasterLost;
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
      last_failure_ = e;
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

std::optional<WorkerSession::Outcome> WorkerSession::handle(protocol::Message& m) {
  if (auto* w = std::get_if<protocol::Welcome>(&m)) {
    on_welcome(*w);
  } else if (auto* r = std::get_if<protocol::Refuse>(&m)) {
    announce("refused by master: " + r->reason);
    return Outcome::Refused;
  } else if (auto* bye = std::get_if<protocol::Bye>(&m)) {
    if (bye->kind == protocol::ByeKind::Quarantined) {
      announce(bye->reason + ": exiting with status 5");
      return Outcome::Quarantined;
    }
    log("master said bye: " + bye->reason);
    return Outcome::Bye;
  } else if (auto* data = std::get_if<protocol::SceneData>(&m)) {
    if (!welcome_ || (data->scene_hash != welcome_->scene_hash &&
                      (welcome_->environment_map.empty() || data->scene_hash != welcome_->environment_map_hash)))
      return std::nullopt;  // not what we asked for
    auto bytes = std::make_shared<protocol::SceneData>(std::move(*data));
    start_loading([cache = cache_, bytes, welcome = *welcome_, fail = options_.fail_scene_load] {
      try {
        cache->store(*bytes);  // checks the hash; writes only inside the cache folder
      } catch (const std::exception& e) {
        return LoadResult{nullptr, 0, e.what(), true};
      }
      return find_and_load(*cache, welcome, fail);  // the other file may still be missing
    });
  } else if (std::holds_alternative<protocol::FrameSetupMsg>(m) || std::holds_alternative<protocol::TileJobMsg>(m)) {
    if (!welcome_) return std::nullopt;  // not ours to render yet
    if (loaded_ && loaded_->pool) feed_pool(m);
    else waiting_.push_back(std::move(m));
  } else if (auto* cancel = std::get_if<protocol::CancelFrame>(&m)) {
    if (loaded_ && loaded_->pool) loaded_->pool->cancel_frame(cancel->frame_id);
    std::erase_if(waiting_, [&](const protocol::Message& w) { return frame_of(w) == cancel->frame_id; });
  }
  return std::nullopt;
}

// The frame a waiting frame setup or job belongs to.
std::optional<uint64_t> WorkerSession::frame_of(const protocol::Message& m) {
  if (auto* f = std::get_if<protocol::FrameSetupMsg>(&m)) return f->frame.frame_id;
  if (auto* j = std::get_if<protocol::TileJobMsg>(&m)) return j->frame_id;
  return std::nullopt;
}

// The scene, its BVH and lights, built on the loading thread.
WorkerSession::LoadResult WorkerSession::find_and_load(const SceneCache& cache, const protocol::Welcome& w, bool fail) {
  std::string scene = w.scene_name;  // built in
  if (w.scene_hash != 0) {
    const std::optional<std::string> path = cache.find(w.scene_name, w.scene_hash);
    if (!path) return {nullptr, w.scene_hash, {}, false};
    scene = *path;
  }
  SkyChoice sky;
  sky.radiance = w.environment;  // the master's sky, whatever the file says
  if (!w.environment_map.empty()) {
    const std::optional<std::string> map = cache.find(w.environment_map, w.environment_map_hash);
    if (!map) return {nullptr, w.environment_map_hash, {}, false};
    sky.map = *map;
    sky.rotation = w.environment_rotation;
  }
  // No --ignore-extension: the master leaves ignored extensions out of the file it sends (scene/gltf_pack.h).
  return load(scene, {sky, w.light_units, false}, fail);
}

WorkerSession::LoadResult WorkerSession::load(const std::string& scene, const SceneOptions& options, bool fail) {
  try {
    if (fail) throw std::runtime_error("--test-fail-scene-load");
    auto loaded = std::make_shared<Loaded>();
    loaded->scene = std::make_unique<SceneState>(load_scene(scene, options));
    return {loaded, 0, {}, false};
  } catch (const std::exception& e) {
    return {nullptr, 0, e.what(), false};
  }
}

// Same scene as the one loaded (a master restart, a reconnect): keep it, BVH
// and all. Otherwise find it by content hash on the loading thread (reading
// and hashing a large file takes seconds); the master sends the bytes if not found.
void WorkerSession::on_welcome(const protocol::Welcome& welcome) {
  if (welcome_ && welcome_->session == welcome.session) return;  // the answer to a repeated Hello
  welcome_ = welcome;
  waiting_.clear();
  const std::string key = scene_key(welcome);
  if (loaded_ && loaded_key_ == key) {
    log("welcomed again: keeping scene " + loaded_->scene->scene().name + " and its BVH (no reload)");
    return start_pool();
  }
  if (loading_.valid() && loading_key_ == key) return;  // on its way
  loaded_.reset();
  loaded_key_.clear();
  loading_key_ = key;
  start_loading([cache = cache_, welcome, fail = options_.fail_scene_load] {
    return find_and_load(*cache, welcome, fail);
  });
}

// A previous load still running is waited for first (a new master with
// another scene while the old one loads: rare, and bounded by one load).
void WorkerSession::start_loading(std::function<LoadResult()> work) {
  if (loading_.valid()) loading_.wait();
  loading_ = std::async(std::launch::async, std::move(work));
}

std::optional<WorkerSession::Outcome> WorkerSession::poll_loading(zmq::socket_t& socket) {
  if (!loading_.valid() || loading_.wait_for(std::chrono::seconds(0)) != std::future_status::ready) return std::nullopt;
  LoadResult result = loading_.get();
  const bool current = welcome_ && scene_key(*welcome_) == loading_key_;
  if (result.refused) return refused(result.error);
  if (!result.error.empty()) {
    const std::string why = "cannot load the scene " + (welcome_ ? welcome_->scene_name : loading_key_) + ": " + result.error;
    announce(why + ": exiting with status 6");
    send(socket, protocol::Bye{why, protocol::ByeKind::Failed});
    socket.set(zmq::sockopt::linger, 500);  // the Bye leaves before the process does
    return Outcome::SceneFailed;
  }
  if (result.need_hash != 0) {
    if (!current) return std::nullopt;
    const bool map = result.need_hash != welcome_->scene_hash;
    log((map ? "environment map " + welcome_->environment_map : "scene " + welcome_->scene_name) +
        " not found locally: asking the master for it");
    send(socket, protocol::SceneRequest{result.need_hash});
    return std::nullopt;
  }
  loaded_ = result.loaded;
  loaded_key_ = loading_key_;
  ++loads_;
  log("scene " + loaded_->scene->scene().name + " ready: " + std::to_string(loaded_->scene->scene().triangles.size()) +
      " triangles (scene loads by this worker: " + std::to_string(loads_) + ")");
  if (current) start_pool();
  return std::nullopt;
}

// A fresh pool for this connection (frames carry their settings); jobs that came early go in now.
void WorkerSession::start_pool() {
  loaded_->pool.reset();
  loaded_->pool = std::make_unique<RenderPool>(*loaded_->scene, welcome_->pixel_format, options_.threads,
                                               options_.memory_bytes);
  for (protocol::Message& m : waiting_) feed_pool(m);
  waiting_.clear();
}

void WorkerSession::feed_pool(protocol::Message& m) {
  try {
    if (auto* f = std::get_if<protocol::FrameSetupMsg>(&m)) loaded_->pool->add_frame(f->frame, f->settings);
    else loaded_->pool->add_job(std::get<protocol::TileJobMsg>(m));
  } catch (const std::exception& e) {
    if (failure_.empty()) failure_ = e.what();
  }
}

// A frame this worker cannot render: the master is told why (it gives the
// jobs to others and logs the reason), and the worker exits rather than
// render some frames and fail others.
std::optional<WorkerSession::Outcome> WorkerSession::check_failure(zmq::socket_t& socket) {
  std::string why = failure_;
  if (why.empty() && loaded_ && loaded_->pool) why = loaded_->pool->failure();
  if (why.empty()) return std::nullopt;
  why = "cannot render here: " + why;
  announce(why + ": exiting with status 7");
  send(socket, protocol::Bye{why, protocol::ByeKind::Failed});
  socket.set(zmq::sockopt::linger, 500);  // the Bye leaves before the process does
  return Outcome::RenderFailed;
}

}  // namespace igi
