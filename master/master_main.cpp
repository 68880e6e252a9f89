// igi-master: renders frames on igi-worker processes (local and remote) and
// writes them (--frames F) or shows them in a window.
#include <atomic>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <thread>

#include "cli/option_checks.h"
#include "cluster/local_workers.h"
#include "options/master_options.h"
#include "session/master_session.h"
#include "protocol/curve.h"
#include "run/run_modes.h"
#include "scene/animation.h"
#include "scene/builtin_scenes.h"
#include "scene/load_scene.h"
#include "view/camera_bookmark.h"

namespace {

std::atomic<bool> g_interrupted{false};  // set by SIGINT/SIGTERM only

// Workers on this machine connect over loopback whatever interface we bound.
std::string local_endpoint(std::string endpoint) {
  for (const std::string any : {"0.0.0.0", "*"})
    if (auto at = endpoint.find(any); at != std::string::npos) endpoint.replace(at, any.size(), "127.0.0.1");
  return endpoint;
}

// CURVE for the session: the master's keys, the workers it lets in, and a key
// pair made now for its local workers (trusted, never written to a file).
struct CurveSetup {
  igi::protocol::CurveServerKeys server;
  igi::protocol::CurveClientKeys local_workers;
};

std::optional<CurveSetup> curve_setup(const igi::MasterOptions& o) {
  if (!o.curve) return std::nullopt;
  CurveSetup c;
  c.server.own = igi::protocol::read_secret_key_file(o.key_file);
  if (!o.authorized_keys.empty()) c.server.authorized = igi::protocol::read_authorized_keys(o.authorized_keys);
  if (c.server.authorized.empty() && o.workers == 0)
    throw std::runtime_error(o.authorized_keys + ": no public keys: no worker could join");
  c.local_workers = {c.server.own.public_key, igi::protocol::make_curve_keypair()};
  c.server.authorized[c.local_workers.own.public_key] = "local worker";
  return c;
}

// --viewer-listen's keys: the master's own and the viewers' (read here, so that bad key files stop us first).
std::optional<igi::protocol::CurveServerKeys> viewer_keys(const igi::MasterOptions& o) {
  if (o.viewer_listen.empty()) return std::nullopt;
  igi::protocol::CurveServerKeys keys;
  keys.own = igi::protocol::read_secret_key_file(o.key_file);
  keys.authorized = igi::protocol::read_authorized_keys(o.viewer_keys);
  if (keys.authorized.empty()) throw std::runtime_error(o.viewer_keys + ": no public keys: no viewer could join");
  return keys;
}

// Test hooks: a signal to local worker 0 after so many accepted results, once
// every local worker has joined (so that it hits one that holds jobs).
void arm_test_hooks(const igi::MasterOptions& o, igi::MasterSession& session, igi::LocalWorkers& workers) {
  if (o.kill_worker_after <= 0 && o.stop_worker_after <= 0) return;
  auto fired = std::make_shared<std::pair<bool, bool>>(false, false);  // killed, stopped
  session.on_accepted = [&o, &session, &workers, fired](uint64_t n) {
    if (session.worker_count() < size_t(o.workers)) return;
    if (o.kill_worker_after > 0 && n >= uint64_t(o.kill_worker_after) && !fired->first) {
      fired->first = true;
      workers.kill_one(0, SIGKILL);
    }
    if (o.stop_worker_after > 0 && n >= uint64_t(o.stop_worker_after) && !fired->second) {
      fired->second = true;
      workers.kill_one(0, SIGSTOP);
    }
  };
}

int run(igi::MasterOptions o) {
  const std::optional<CurveSetup> curve = curve_setup(o);  // bad key files stop us before anything is bound
  const std::optional<igi::protocol::CurveServerKeys> viewers = viewer_keys(o);
  igi::SceneMessages messages;
  igi::Scene scene = igi::load_scene(o.render.scene, igi::scene_options(o.render), &messages);  // validates it, and gives the camera
  for (const std::string& w : messages.warnings) std::fprintf(stderr, "igi-master: warning: %s\n", w.c_str());
  if (!o.render.quiet)
    for (const std::string& n : messages.notices) std::fprintf(stderr, "igi-master: %s\n", n.c_str());
  if (auto note = igi::choose_caustics(o.render, scene)) std::fprintf(stderr, "igi-master: %s\n", note->c_str());
  igi::Scene as_workers_load_it = scene;                 // the master's own VPL sets judge each worker's
  if (!o.render.camera_file.empty()) igi::place_camera(scene, igi::read_camera_file(o.render.camera_file));  // before anything starts
  zmq::context_t context(o.io_threads);
  igi::SceneSource source = igi::make_scene_source(o.render.scene, o.render.ignored_extensions);
  source.environment = scene.environment;
  source.light_units = o.render.light_units;
  if (scene.environment_map)  // --environment FILE's, or the glTF scene's extras'
    igi::add_environment_map(source, scene.environment_map->source(), scene.environment_map->rotation());
  igi::MasterSession session(igi::session_settings(o), std::move(source), context, curve ? &curve->server : nullptr);
  session.judge_by(std::move(as_workers_load_it));
  if (curve)
    std::fprintf(stderr, "igi-master: listening on %s (CURVE; master public key %s; %zu authorised worker keys)\n",
                 session.endpoint().c_str(), curve->server.own.public_key.c_str(), curve->server.authorized.size() - 1);
  else
    std::fprintf(stderr, "igi-master: listening on %s\n", session.endpoint().c_str());
  igi::LocalWorkers workers;
  const int threads = o.worker_threads > 0 ? o.worker_threads
                                           : std::max(1, int(std::thread::hardware_concurrency()) / std::max(1, o.workers));
  std::vector<std::string> extra;
  if (!igi::is_builtin_scene(o.render.scene))
    extra = {"--scene-dir", std::filesystem::absolute(o.render.scene).parent_path().string()};
  workers.start(o.workers, local_endpoint(session.endpoint()), threads, extra, curve ? &curve->local_workers : nullptr);
  arm_test_hooks(o, session, workers);
  if (!o.motion.empty()) return igi::run_motion(o, scene, session, workers, g_interrupted);
  if (o.frames > 0) return igi::run_headless(o, scene, session, workers, g_interrupted);
  if (viewers) return igi::run_for_viewer(o, scene, session, workers, *viewers, g_interrupted);
  return igi::run_interactive(o, scene, session, workers, g_interrupted);
}

}  // namespace

int main(int argc, char** argv) {
  std::signal(SIGINT, [](int) { g_interrupted = true; });
  std::signal(SIGTERM, [](int) { g_interrupted = true; });
  return igi::cli::run_program("igi-master", 1, 1, [&] {
    igi::MasterOptions o = igi::parse_master_options({argv + 1, argv + argc});
    if (o.render.help) { std::cout << igi::master_usage(argv[0]); return 0; }
    return run(o);
  });
}
