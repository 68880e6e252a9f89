// igi-master: renders frames on igi-worker processes (local and remote) and
// writes them (--frames F) or shows them in a window.
#include <atomic>
#include <thread>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <map>
#include <optional>

#include "display/interactive_window.h"
#include "frame_plan.h"
#include "frame_stats.h"
#include "frame_writer.h"
#include "local_workers.h"
#include "master_options.h"
#include "master_session.h"
#include "protocol/curve.h"
#include "render/accumulator.h"
#include "scene/builtin_scenes.h"
#include "scene/load_scene.h"
#include "scene/scene_file.h"

namespace {

std::atomic<bool> g_interrupted{false};  // set by SIGINT/SIGTERM only

igi::SceneSource scene_source(const std::string& scene) {
  if (igi::is_builtin_scene(scene)) return {scene, 0, {}};
  auto bytes = igi::read_file_bytes(scene);
  if (!bytes) throw std::runtime_error(scene + ": cannot read the scene file");
  const uint64_t hash = igi::content_hash(*bytes);
  return {std::filesystem::path(scene).filename().string(), hash, std::move(*bytes)};
}

// Workers on this machine connect over loopback whatever interface we bound.
std::string local_endpoint(std::string endpoint) {
  for (const std::string any : {"0.0.0.0", "*"})
    if (auto at = endpoint.find(any); at != std::string::npos) endpoint.replace(at, any.size(), "127.0.0.1");
  return endpoint;
}

std::string frame_path(const std::string& output, int frame, int frames, int first) {
  if (frames <= 1 && first == 0) return output;
  std::filesystem::path p(output);
  char suffix[16];
  std::snprintf(suffix, sizeof suffix, "-%04d", frame);
  return (p.parent_path() / (p.stem().string() + suffix + p.extension().string())).string();
}

// --min-workers: a cluster's render starts when all of it is there, not with
// whichever worker dialled back first; a host that never comes costs at most
// --min-workers-wait seconds.
bool workers_gathered(const igi::MasterOptions& o, const igi::MasterSession& session,
                      std::chrono::steady_clock::time_point since) {
  const size_t joined = session.worker_count();
  if (joined >= size_t(o.min_workers)) return true;
  if (std::chrono::steady_clock::now() - since < std::chrono::seconds(o.min_workers_wait)) return false;
  std::fprintf(stderr, "igi-master: only %zu of %d workers joined in %d s: starting with them\n", joined,
               o.min_workers, o.min_workers_wait);
  return true;
}

int run_headless(const igi::MasterOptions& o, const igi::Scene& scene, igi::MasterSession& session,
                 igi::LocalWorkers& workers) {
  igi::Accumulator accumulator(o.render.width, o.render.height);
  std::vector<igi::FrameRecord> records;
  std::optional<igi::FrameWriter> writer(std::in_place, o.render.exposure);
  int next = 0, written = 0;
  auto idle_since = std::chrono::steady_clock::now();
  const auto wall_start = std::chrono::steady_clock::now();
  // The master's own cost: scheduling, messages, assembly, ZeroMQ's I/O thread;
  // image files are written on other threads (run with --no-write to leave them out).
  double session_cpu = 0.0;
  auto totals_now = [&] {
    igi::RunTotals t;
    t.bad_messages = session.bad_messages();
    t.refused_keys = session.refused_keys();
    t.failed_handshakes = session.failed_handshakes();
    t.master_cpu_seconds = session_cpu;
    t.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
    return t;
  };
  // The statistics so far, so a master that is killed leaves them: once a
  // second, and a second more per 1000 frames, so the rewrite stays ~300 bytes
  // a frame per second however long the run.
  auto last_flush = wall_start;
  bool gathered = o.min_workers == 0;
  while (written < o.frames && !g_interrupted) {
    const double cpu_before = igi::process_cpu_seconds();
    gathered = gathered || workers_gathered(o, session, wall_start);
    while (gathered && next < o.frames && session.can_add_frame())
      session.add_frame(igi::plan_frame(o.render, o.camera_path, scene, o.first_frame + next++, o.progressive));
    std::vector<igi::CompletedFrame> completed = session.pump(50);
    session_cpu += igi::process_cpu_seconds() - cpu_before;
    for (igi::CompletedFrame& f : completed) {
      igi::Image image = std::move(f.image);
      if (o.progressive) {
        accumulator.add(image, 1.0);
        image = accumulator.resolve();
      }
      if (!o.no_write)
        writer->write(std::move(image), frame_path(o.render.output, o.first_frame + written, o.frames, o.first_frame));
      if (!o.render.quiet)
        std::printf("frame %d: %.1f ms, %.1f Mrays/s, %zu workers\n", o.first_frame + written, 1e3 * f.record.seconds,
                    f.record.seconds > 0 ? f.record.rays.total() * 1e-6 / f.record.seconds : 0.0, session.worker_count());
      records.push_back(f.record);
      ++written;
    }
    if (!o.stats.empty() && std::chrono::steady_clock::now() - last_flush > std::chrono::seconds(1 + records.size() / 1000)) {
      igi::write_stats_json(o.stats, records, totals_now());
      last_flush = std::chrono::steady_clock::now();
    }
    if (session.worker_count() > 0) idle_since = std::chrono::steady_clock::now();
    if (std::chrono::steady_clock::now() - idle_since > std::chrono::seconds(60)) {
      std::fprintf(stderr, "igi-master: no worker for 60 s; start some with igi-worker --connect %s\n",
                   session.endpoint().c_str());
      break;
    }
  }
  igi::RunTotals totals = totals_now();
  totals.complete = true;
  session.close(written == o.frames ? "done" : "interrupted");
  workers.stop_all();
  const std::string write_error = writer->error();
  writer.reset();  // waits for the last images
  if (!o.stats.empty()) igi::write_stats_json(o.stats, records, totals);
  if (!write_error.empty()) throw std::runtime_error(write_error);
  return written == o.frames ? 0 : 1;
}

std::string status_line(const igi::CompletedFrame& f, size_t workers, int accumulated, double fps) {
  char text[160];
  const double s = f.record.seconds;
  std::snprintf(text, sizeof text, "%.1f fps  %.0f ms/frame  %.1f Mrays/s  %zu workers  %d frames accumulated", fps,
                1e3 * s, s > 0 ? f.record.rays.total() * 1e-6 / s : 0.0, workers, accumulated);
  return text;
}

// The window: frames follow the camera; while it is still they accumulate.
int run_interactive(const igi::MasterOptions& o, const igi::Scene& scene, igi::MasterSession& session,
                    igi::LocalWorkers& workers) {
  igi::InteractiveWindow window(o.render.width, o.render.height, "igi-master: " + o.render.scene);
  igi::CameraController controller(scene.camera_or_auto(), 0.25f * scene.bounds().diagonal());
  igi::Accumulator accumulator(o.render.width, o.render.height);
  std::map<uint64_t, uint64_t> generation_of_frame;
  uint64_t generation = controller.generation();
  int pass = 0, next_id = 0;
  auto last_frame = std::chrono::steady_clock::now();
  while (window.poll(controller) && !g_interrupted) {
    if (controller.generation() != generation) {  // the camera moved: start over
      generation = controller.generation();
      accumulator.reset();
      pass = 0;
    }
    if (session.can_add_frame()) {
      igi::FrameSetup f = igi::plan_frame(o.render, o.camera_path, scene, pass, true);  // pass p: seed + p, a new jitter
      f.frame_id = uint64_t(next_id++);
      f.camera = controller.camera();
      generation_of_frame[f.frame_id] = generation;
      session.add_frame(f);
      ++pass;
    }
    for (igi::CompletedFrame& f : session.pump(2)) {
      if (generation_of_frame[f.setup.frame_id] != generation) continue;  // rendered for an old camera
      accumulator.add(f.image, 1.0);
      const auto now = std::chrono::steady_clock::now();
      const double fps = 1.0 / std::max(1e-6, std::chrono::duration<double>(now - last_frame).count());
      last_frame = now;
      window.show(accumulator.resolve(), o.render.exposure);
      window.set_status(status_line(f, session.worker_count(), int(accumulator.weight()), fps));
      if (!o.render.screenshot.empty() && accumulator.weight() >= o.screenshot_after) {
        window.screenshot(o.render.screenshot);
        g_interrupted = true;
      }
      window.present();
    }
  }
  session.close("window closed");
  workers.stop_all();
  return 0;
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

int run(const igi::MasterOptions& o) {
  const std::optional<CurveSetup> curve = curve_setup(o);  // bad key files stop us before anything is bound
  igi::Scene scene = igi::load_scene(o.render.scene);  // validates it, and gives the camera
  zmq::context_t context;
  igi::MasterSession session(o, scene_source(o.render.scene), context, curve ? &curve->server : nullptr);
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
  if (o.kill_worker_after > 0)
    session.on_accepted = [&](uint64_t n) { if (n == uint64_t(o.kill_worker_after)) workers.kill_one(0, SIGKILL); };
  if (o.frames > 0) return run_headless(o, scene, session, workers);
  return run_interactive(o, scene, session, workers);
}

}  // namespace

int main(int argc, char** argv) {
  std::signal(SIGINT, [](int) { g_interrupted = true; });
  std::signal(SIGTERM, [](int) { g_interrupted = true; });
  try {
    igi::MasterOptions o = igi::parse_master_options({argv + 1, argv + argc});
    if (o.render.help) { std::cout << igi::master_usage(argv[0]); return 0; }
    return run(o);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "igi-master: %s\n", e.what());
    return 1;
  }
}
