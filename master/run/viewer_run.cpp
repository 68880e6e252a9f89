// --viewer-listen: the window is on another machine (igi-view). The session
// runs on its own thread as for the window (session_thread.h); this thread
// owns the viewer port (viewer/viewer_port.h): it turns the viewer's View into
// the view the session follows, accumulates the frames as the window does
// (view_history.h), and sends the viewer the newest image tone-mapped at its
// exposure and view transform, 8-bit, whenever the viewer has acknowledged
// enough frames: one that falls behind gets fewer frames, never a queue.
// While the view moves (the planner's "moving") they go as H.264 within
// --viewer-mbit (video_codec.h); once it is still, lossless (zstd), at most
// kStillFramesPerSecond a second. With no viewer connected
// the frames still accumulate, so a viewer that joins (again) sees the image
// as far as it has come.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <map>
#include <memory>
#include <optional>
#include <thread>

#include "image/exposure_check.h"
#include "output/frame_stats.h"
#include "output/stats_writer.h"
#include "render/view_history.h"
#include "run/run_modes.h"
#include "run/session_thread.h"
#include "scene/animation.h"
#include "view/frame_budget.h"
#include "view/frame_rate.h"
#include "viewer/video_codec.h"
#include "viewer/viewer_port.h"

namespace igi {
namespace {

using Clock = std::chrono::steady_clock;

// A still view's lossless frames (about 1 byte a pixel each): enough for the
// image to settle on the viewer, few enough to leave a slow link room.
constexpr double kStillFramesPerSecond = 4.0;
constexpr double kVideoFramesPerSecond = 25.0;  // what the H.264 rate control plans a frame's bits for
// The share of the measured link (link_meter.h) the moving frames may take:
// the measure is a lower bound, and Acks and still frames share the link.
constexpr double kLinkShare = 0.7;

display::Welcome welcome_for(const MasterOptions& o, const Scene& scene) {
  display::Welcome w;
  w.scene = o.render.scene;
  w.width = o.render.width;
  w.height = o.render.height;
  w.settings = o.render.settings;
  w.camera = scene_camera(scene, o.render.time);
  w.speed = 0.25f * scene.bounds().diagonal();
  w.metering = !o.render.exposure_given || o.render.exposure.metered;
  w.tone = {w.metering ? 1.0f : o.render.exposure.factor, o.render.view};
  const FrameBudget budget(o.render.width, o.render.height, 0.0, o.sharp_previews);
  for (const PreviewLevel& level : budget.levels()) w.preview_levels.push_back(level_name(level));
  return w;
}

// The viewer's view as the session follows it. The master counts its own
// generations (a viewer that joins again starts its counts over): new
// settings or moved lights start the image over, a moved camera carries it,
// and a viewer that joins where the last one left keeps the image.
class ViewerState {
 public:
  explicit ViewerState(const display::Welcome& w) {
    view_.camera = w.camera;
    view_.settings = w.settings;
    tone_ = w.tone;
    metering_ = w.metering;
  }
  // A viewer joined: its counts start at 0 with the Welcome's settings and
  // camera, which are the view's now (ViewerServer::take_view keeps them so).
  // Its stamps are of its own clock: frames of a camera it did not move echo none.
  void joined() {
    viewer_settings_ = viewer_camera_ = 0;
    stamps_.clear();
  }
  // True when the image starts over.
  bool take(const display::View& v) {
    const bool restart = v.settings_generation != viewer_settings_ || v.light_offset != view_.light_offset;
    const bool moved = !restart && v.camera_generation != viewer_camera_;
    if (restart) ++view_.settings_generation;
    if (moved) ++view_.camera_generation;
    // The input a camera shows: the View that moved it (a View of a new exposure alone is no input to echo).
    if (moved) stamps_[view_.camera_generation] = v.stamp_us;
    viewer_settings_ = v.settings_generation;
    viewer_camera_ = v.camera_generation;
    view_.camera = v.camera;
    view_.settings = v.settings;
    view_.light_offset = v.light_offset;
    view_.preview = v.preview;
    tone_ = v.tone;
    metering_ = v.metering;
    while (stamps_.size() > 256) stamps_.erase(stamps_.begin());
    return restart;
  }
  uint64_t stamp_of(uint64_t camera_generation) const {
    auto it = stamps_.find(camera_generation);
    return it == stamps_.end() ? 0 : it->second;
  }
  const MovingView& view() const { return view_; }
  uint64_t viewer_settings() const { return viewer_settings_; }
  ToneMapping tone_;
  bool metering_ = false;

 private:
  MovingView view_;
  uint64_t viewer_settings_ = 0, viewer_camera_ = 0;
  std::map<uint64_t, uint64_t> stamps_;  // camera generation -> the viewer's stamp of the View that made it
};

// The newest image, as the viewer will see it, and what it says about itself.
struct Latest {
  bool fresh = false;  // not sent yet
  bool full = false;
  bool moving = false;  // the camera changed just before it (motion_planner.h's kStillAfter)
  uint64_t stamp = 0;
  float seconds = 0.0f;
  std::string level, status;
};

struct ViewerServer {
  ViewerServer(const MasterOptions& o, ViewerPort& port, Handover& handover, const display::Welcome& welcome,
               std::optional<StatsWriter>& stats)
      : o(o), port(port), handover(handover), welcome(welcome), state(welcome),
        history(o.render.width, o.render.height, o.history_frames), stats(stats) {}

  const MasterOptions& o;
  ViewerPort& port;
  Handover& handover;
  display::Welcome welcome;
  ViewerState state;
  ViewHistory history;
  std::optional<StatsWriter>& stats;
  Latest latest;
  FrameRate rate;
  int shots = 0;
  std::unique_ptr<VideoEncoder> video;  // one stream per viewer connection; null: zstd only
  Clock::time_point last_lossless{};

  void start_stream() {
    video.reset();
    if (o.viewer_codec == "h264" && o.render.width % 2 == 0 && o.render.height % 2 == 0)
      video = std::make_unique<VideoEncoder>(o.render.width, o.render.height, o.viewer_mbit, kVideoFramesPerSecond);
  }

  void take_view(const ViewerPort::Incoming& in) {
    if (in.joined) {
      state.joined();
      start_stream();
    }
    if (!in.view) return;
    if (state.take(*in.view)) history.reset();
    handover.publish(state.view());
    welcome.camera = in.view->camera;  // a viewer that joins next starts where this one is
    welcome.settings = in.view->settings;
    welcome.tone = in.view->tone;
    welcome.metering = false;
    port.set_welcome(welcome);
    latest.fresh = history.weight() > 0.0;  // at the new exposure
  }

  void take_frames() {
    for (Shown& shown : handover.take(std::chrono::milliseconds(0))) {
      if (shown.planned.settings_generation != state.view().settings_generation) continue;  // old settings
      history.add(shown.frame.pixels->to_image(), shown.frame.surfaces, shown.frame.setup.camera, shown.weight,
                  shown.frame.surface_offset);
      shown.frame.pixels.reset();  // back to the pool
      const auto now = Clock::now();
      rate.shown(now);
      latest = {true, shown.planned.level == 0, shown.planned.moving, state.stamp_of(shown.planned.camera_generation),
                float(shown.frame.record.seconds), shown.level, status_line(shown, history.weight(), rate.fps(now), false)};
      if (stats) stats->add(shown.frame.record);
    }
  }

  void send_latest() {
    if (!latest.fresh || !port.can_send_frame() || history.weight() <= 0.0) return;
    const bool lossless = !latest.moving || !video;
    const auto now = Clock::now();
    if (lossless && video && now - last_lossless < std::chrono::duration<double>(1.0 / kStillFramesPerSecond)) return;
    const Image image = history.resolve();
    display::Frame f;
    if (state.metering_) {  // the opening meter, as the window's: until a full frame
      f.metered = state.tone_.exposure = metered_exposure(image);
      if (latest.full) state.metering_ = false;
    }
    const std::vector<unsigned char> rgb = to_srgb8(image, state.tone_);
    f.stamp_us = latest.stamp;
    f.settings_generation = state.viewer_settings();
    f.width = image.width;
    f.height = image.height;
    f.full = latest.full;
    f.accumulated = float(history.weight());
    f.seconds = latest.seconds;
    f.level = latest.level;
    f.status = latest.status;
    f.codec = lossless ? display::FrameCodec::Zstd : display::FrameCodec::H264;
    if (!lossless) follow_link();
    f.pixels = lossless ? display::pack_pixels(rgb) : video->encode(rgb);
    if (lossless) last_lossless = now;
    port.send_frame(std::move(f));
    latest.fresh = false;
  }

  // The H.264 bit rate: a share of the link measured, within --viewer-mbit; changed when 10 % off.
  void follow_link() {
    const double budget = o.viewer_mbit > 0.0 ? port.link().budget(o.viewer_mbit, kLinkShare) : 0.0;
    const double was = video->bit_rate();
    if (std::abs(budget - was) > 0.1 * was) {
      video->set_bit_rate(budget);
      if (!o.render.quiet && std::abs(budget - was) > 0.3 * was)  // the big steps on the terminal
        std::fprintf(stderr, "igi-master: viewer link measured %.1f Mbit/s: moving frames at %.1f Mbit/s\n",
                     port.link().mbit(), budget);
    }
  }

  display::Reply answer(const display::Request& r) {
    if (history.weight() <= 0.0) return {"no image yet", 0.0f, {}};
    const Image image = history.resolve();
    char text[160];
    if (r.kind == display::RequestKind::Meter) {
      const float exposure = metered_exposure(image);
      std::snprintf(text, sizeof text, "exposure metered: %+.2f EV", std::log2(exposure));
      return {text, exposure, {}};
    }
    char name[48];
    std::snprintf(name, sizeof name, "igi-shot-%04d", shots++);
    std::vector<uint8_t> exr;
    try {
      write_image(image, std::string(name) + ".exr");
      write_image(image, std::string(name) + ".png", state.tone_);
      std::ifstream in(std::string(name) + ".exr", std::ios::binary);  // the file as written, for the viewer
      exr.assign(std::istreambuf_iterator<char>(in), {});
    } catch (const std::exception& e) {
      return {std::string("the master could not save the image: ") + e.what(), 0.0f, {}};
    }
    std::snprintf(text, sizeof text, "saved %s.exr and .png on the master (%.1f frames accumulated)", name,
                  history.weight());
    return {text, 0.0f, std::move(exr)};
  }

  void turn(const std::atomic<bool>& interrupted) {
    while (!interrupted && !handover.stopped()) {
      const ViewerPort::Incoming in = port.poll(std::chrono::milliseconds(5));
      take_view(in);
      for (const display::Request& r : in.requests) {
        const display::Reply reply = answer(r);
        if (!o.render.quiet) std::fprintf(stderr, "igi-master: %s\n", reply.text.c_str());
        port.reply(reply);
      }
      take_frames();
      send_latest();
    }
  }
};

void print_how_to_connect(const MasterOptions& o, const ViewerPort& port, const std::string& master_public_key) {
  std::string port_number = port.endpoint().substr(port.endpoint().find_last_of(':') + 1);
  std::fprintf(stderr,
               "igi-master: viewer port %s (CURVE; master public key %s)\n"
               "igi-master: from another machine: ssh -N -L %s:127.0.0.1:%s THIS_HOST, then\n"
               "igi-master:   igi-view --connect tcp://127.0.0.1:%s --key VIEWER.key --master-key %s\n",
               port.endpoint().c_str(), master_public_key.c_str(), port_number.c_str(), port_number.c_str(),
               port_number.c_str(), (o.key_file.substr(0, o.key_file.find_last_of('.')) + ".pub").c_str());
}

}  // namespace

int run_for_viewer(const MasterOptions& o, const Scene& scene, MasterSession& session, LocalWorkers& workers,
                   const protocol::CurveServerKeys& keys, const std::atomic<bool>& interrupted) {  if (o.viewer_codec == "h264" && !have_h264_encoder())
    throw std::runtime_error("--viewer-codec h264: this build's libavcodec has no H.264 encoder (libx264); "
                             "--viewer-codec zstd sends every frame lossless");
  const display::Welcome welcome = welcome_for(o, scene);
  ViewerPort port(o.viewer_listen, keys, welcome, o.render.quiet);
  print_how_to_connect(o, port, keys.own.public_key);
  std::optional<StatsWriter> stats;  // the frames the viewer's image took in
  if (!o.stats.empty()) stats.emplace(o.stats);
  const auto wall_start = Clock::now();
  const double cpu_start = process_cpu_seconds();
  Handover handover;
  ViewerServer server(o, port, handover, welcome, stats);
  handover.publish(server.state.view());
  const double budget_ms = o.frame_budget_ms >= 0.0 ? o.frame_budget_ms : kWindowFrameBudgetMs;
  std::thread session_thread([&] { session_loop(o, scene, session, handover, budget_ms); });
  server.turn(interrupted);
  handover.stop();
  session_thread.join();
  port.close(handover.error().empty() ? "the master was stopped" : "the master failed: " + handover.error(), 500);
  session.close("stopped");
  workers.stop_all();
  if (stats) {
    RunTotals t = run_totals(session, o.io_threads, cpu_start,
                             std::chrono::duration<double>(Clock::now() - wall_start).count());
    t.complete = true;
    t.outcome = "done";
    stats->write_final(t);
  }
  if (const std::string error = handover.error(); !error.empty()) throw std::runtime_error(error);
  return 0;
}

}  // namespace igi
