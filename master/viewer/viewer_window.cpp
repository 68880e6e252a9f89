#include "viewer/viewer_window.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <memory>
#include <stdexcept>
#include <optional>

#include "display/interactive_window.h"
#include "display/view_changes.h"
#include "display/window_panel.h"
#include "view/camera_bookmark.h"
#include "view/frame_rate.h"
#include "viewer/video_codec.h"
#include "viewer/viewer_client.h"

namespace igi {
namespace {

using Clock = std::chrono::steady_clock;

uint64_t now_us() {
  return uint64_t(std::chrono::duration_cast<std::chrono::microseconds>(Clock::now().time_since_epoch()).count());
}

protocol::CurveClientKeys client_keys(const ViewerOptions& o) {
  return {protocol::read_public_key_file(o.master_key), protocol::read_secret_key_file(o.key_file)};
}

PanelOptions panel_options(const ViewerOptions& o, const display::Welcome& w, const InteractiveWindow& window) {
  PanelOptions p;
  p.image_width = w.width;
  p.image_height = w.height;
  p.shown = o.panel && panel_opens(float(window.width()), float(window.height()), w.width, w.height,
                                   panel_layout(w.width).width);
  p.bookmark = o.bookmark;
  p.preview_levels = w.preview_levels;
  return p;
}

// What the window shows and what it measured.
struct Screen {
  InteractiveWindow& window;
  WindowPanel& panel;
  ViewerFigures& figures;
  bool metering;
  float accumulated = 0.0f;
  uint64_t last_stamp = 0;
  Clock::time_point first{};
  FrameRate rate;
  VideoDecoder video;
  std::FILE* log = nullptr;  // --frame-log

  // "1765148400123 h264 5120 307200 48.2": wall clock, codec, bytes, pixels, input to frame.
  void log_frame(const display::Frame& f, double delay_ms) {
    if (!log) return;
    const auto wall = std::chrono::duration_cast<std::chrono::milliseconds>(
        std::chrono::system_clock::now().time_since_epoch());
    std::fprintf(log, "%lld %s %zu %d ", static_cast<long long>(wall.count()),
                 f.codec == display::FrameCodec::H264 ? "h264" : "zstd", f.pixels.size(), f.width * f.height);
    if (delay_ms >= 0.0) std::fprintf(log, "%.1f\n", delay_ms);
    else std::fprintf(log, "-\n");
  }

  // Every frame's pixels: H.264 frames are decoded in order even when not shown.
  std::vector<uint8_t> unpack(const display::Frame& f) {
    std::string error;
    std::optional<std::vector<uint8_t>> rgb = f.codec == display::FrameCodec::H264
                                                  ? video.decode(f.pixels, f.width, f.height, error)
                                                  : display::unpack_pixels(f, error);
    if (!rgb) throw ViewerError("the master sent a frame that does not unpack: " + error);
    return std::move(*rgb);
  }

  // A frame of the current settings: up, with its status and the opening meter's exposure.
  void show(const display::Frame& f, const std::vector<uint8_t>& rgb) {
    window.upload_srgb8(rgb, f.width, f.height);
    if (metering && f.metered > 0.0f) panel.settings().set_exposure(f.metered);
    if (f.full) metering = false;
    accumulated = f.accumulated;
    const auto now = Clock::now();
    if (figures.frames++ == 0) first = now;
    figures.seconds = std::chrono::duration<double>(now - first).count();
    figures.bytes += double(f.pixels.size());
    figures.pixels += double(f.width) * f.height;
    double delay_ms = -1.0;
    if (f.stamp_us != 0 && f.stamp_us != last_stamp) {  // the first frame that shows this input
      delay_ms = std::max(0.0, double(now_us()) - double(f.stamp_us)) * 1e-3;
      figures.delays_ms.push_back(delay_ms);
      last_stamp = f.stamp_us;
    }
    log_frame(f, delay_ms);
    rate.shown(now);
    char fps[48];
    std::snprintf(fps, sizeof fps, "  |  shown %.1f fps", rate.fps(now));
    window.set_status(f.status + fps);
    FrameRecord record;  // what the panel's read-out and graph show; the cluster's figures stay on the master
    record.seconds = f.seconds;
    panel.frame_shown(record, {}, rate.fps(now), f.level);
  }
};

// F5 and F9 here, M and F12 on the master.
void act(const PanelActions& a, WindowPanel& panel, CameraController& controller, float speed, ViewerClient& client) {
  try {
    if (a.meter) client.send(display::Request{display::RequestKind::Meter});
    if (a.save_image) client.send(display::Request{display::RequestKind::SaveImage});
    if (a.save_camera) {
      write_camera_file(panel.options().bookmark, controller.camera());
      panel.set_message("camera saved to " + panel.options().bookmark);
    }
    if (a.load_camera) {
      controller = CameraController(read_camera_file(panel.options().bookmark), speed);
      controller.hold();
      panel.set_message("camera loaded from " + panel.options().bookmark);
    }
  } catch (const std::exception& e) {
    panel.set_message(e.what());
  }
}

// F12's answer: the master's float image, kept here as PREFIX-NNNN.exr, and as
// .png at this window's exposure and view transform. Says what it saved.
std::string keep_shot(const display::Reply& r, WindowPanel& panel, int& shots) {
  char name[64];
  std::snprintf(name, sizeof name, "%s-%04d", panel.options().shot_prefix.c_str(), shots++);
  const std::string exr = std::string(name) + ".exr";
  try {
    std::ofstream out(exr, std::ios::binary);
    out.write(reinterpret_cast<const char*>(r.exr.data()), std::streamsize(r.exr.size()));
    if (!out.flush()) throw std::runtime_error("cannot write " + exr);
    out.close();
    write_image(read_image(exr), std::string(name) + ".png", panel.settings().tone());
  } catch (const std::exception& e) {
    return std::string("not kept here: ") + e.what();
  }
  return std::string("kept here as ") + name + ".exr and .png";
}

}  // namespace

std::string ViewerFigures::summary() const {
  std::vector<double> d = delays_ms;
  std::sort(d.begin(), d.end());
  const double median = d.empty() ? 0.0 : d[d.size() / 2];
  char text[256];
  std::snprintf(text, sizeof text,
                "%d frames in %.1f s (%.1f a second), %.3f bytes a pixel, input to frame median %.0f ms over %zu inputs",
                frames, seconds, seconds > 0 ? (frames - 1) / seconds : 0.0, pixels > 0 ? bytes / pixels : 0.0,
                median, d.size());
  return text;
}

ViewerFigures run_viewer(const ViewerOptions& o, const std::atomic<bool>& interrupted) {
  ViewerClient client(o.connect, client_keys(o));
  const display::Welcome w = client.join(std::chrono::seconds(o.wait_seconds));
  InteractiveWindow window(w.width, w.height, panel_layout(w.width).width, o.panel, "igi-view: " + w.scene);
  WindowPanel panel(window.handle(), w.settings, w.tone, panel_options(o, w, window));
  CameraController controller(w.camera, w.speed);
  ViewChanges changes(controller);
  ViewerFigures figures;
  Screen screen{window, panel, figures, w.metering, 0.0f, 0, {}, {}, {}, nullptr};
  std::unique_ptr<std::FILE, int (*)(std::FILE*)> log(nullptr, std::fclose);
  if (!o.frame_log.empty()) {
    log.reset(std::fopen(o.frame_log.c_str(), "w"));
    if (!log) throw std::runtime_error("--frame-log " + o.frame_log + ": cannot write it");
    screen.log = log.get();
  }
  auto view = [&] {
    return display::View{controller.camera(), panel.settings().settings(), changes.camera_generation(),
                         changes.settings_generation(), controller.light_offset(), panel.options().preview,
                         panel.settings().tone(), screen.metering, now_us()};
  };
  display::View sent = view();
  client.send(sent);
  auto last_draw = Clock::now();
  bool shot = false;
  int shots = 0;
  while (!shot && window.poll(controller) && !interrupted) {
    const ViewChanges::Change change = changes.take(panel, controller, sent.preview);
    const ToneMapping tone = panel.settings().tone();
    if (change != ViewChanges::Change::None || tone.exposure != sent.tone.exposure || tone.view != sent.tone.view ||
        screen.metering != sent.metering)
      client.send(sent = view());
    bool fresh = false;
    for (auto wait = std::chrono::milliseconds(5); auto m = client.receive(wait); wait = std::chrono::milliseconds(0)) {
      if (auto* f = std::get_if<display::Frame>(&*m)) {
        client.send(display::Ack{f->sequence});
        const std::vector<uint8_t> rgb = screen.unpack(*f);
        if (f->settings_generation != changes.settings_generation()) continue;  // rendered with old settings
        screen.show(*f, rgb);
        fresh = true;
      } else if (auto* r = std::get_if<display::Reply>(&*m)) {
        if (r->exposure > 0.0f) panel.settings().set_exposure(r->exposure);
        const std::string text = r->exr.empty() ? r->text : r->text + "; " + keep_shot(*r, panel, shots);
        if (!o.quiet) std::fprintf(stderr, "igi-view: %s\n", text.c_str());
        panel.set_message(text);
      }
    }
    const auto now = Clock::now();
    if (!fresh && now - last_draw < std::chrono::milliseconds(50)) continue;  // redraw for the panel at 20 Hz
    last_draw = now;
    if (!fresh && screen.figures.frames > 0) panel.set_waiting(screen.rate.waiting(now));
    window.draw(panel.image_viewport(float(window.width()), float(window.height())), panel.settings().tone());
    const PanelActions actions = panel.draw(int(screen.accumulated), window.take_panel_taps());
    window.set_input_captured(panel.wants_mouse(), panel.wants_keyboard());
    act(actions, panel, controller, w.speed, client);
    if (actions.load_camera) changes.forget_camera(controller);
    if (fresh && !o.screenshot.empty() && screen.accumulated >= float(o.screenshot_after)) {
      window.screenshot(o.screenshot);
      shot = true;
    }
    window.present();
  }
  if (!o.exit_screenshot.empty()) {  // the last frame shown, drawn again (the back buffer after a swap is undefined)
    window.draw(panel.image_viewport(float(window.width()), float(window.height())), panel.settings().tone());
    window.screenshot(o.exit_screenshot);
  }
  client.close("the viewer's window closed");
  return figures;
}

}  // namespace igi
