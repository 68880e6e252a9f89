#include "master_options.h"

#include <algorithm>
#include <cctype>
#include <sstream>
#include <stdexcept>

#include "protocol/curve.h"

namespace igi {

std::string master_usage(const std::string& program) {
  return "usage: " + program + " [cluster options] [render options]\n"
         "cluster options:\n"
         "  --workers N           local igi-worker processes to start (0: only remote ones) [2]\n"
         "  --worker-threads T    threads per local worker, 0 = cores / workers [0]\n"
         "  --listen ENDPOINT     where workers connect [tcp://127.0.0.1:0 = loopback, any free port];\n"
         "                        name another interface (tcp://0.0.0.0:5555) to open it to a network:\n"
         "                        that needs CURVE (--key and --authorized-keys)\n"
         "  --key FILE            the master's secret key (igi-keys new NAME writes NAME.key): turns on CURVE\n"
         "                        authentication and encryption; workers get NAME.pub (--master-key)\n"
         "  --authorized-keys P   workers allowed to connect: a folder of their .pub files, or a file\n"
         "                        with one Z85 public key per line (local workers are always allowed)\n"
         "  --curve               CURVE on a loopback endpoint too (needs --key)\n"
         "  --frames F            headless: render F frames and write them (-o); default: a window\n"
         "  --first-frame I       headless: start at frame I (camera path, seed and file names) [0]\n"
         "  --min-workers N       headless: hold the first frame until N workers have joined, at most\n"
         "                        --min-workers-wait S seconds [30], then start with those present [0]\n"
         "  --progressive         headless: accumulate frames, advancing the seed\n"
         "  --camera-path orbit   headless: turn the camera about the scene, one step a frame\n"
         "  --stats FILE.json     per-frame statistics\n"
         "  --no-write            headless: write no images (benchmarks)\n"
         "  --screenshot FILE     window: save it after --screenshot-after N accumulated frames [4], then exit\n"
         "  --camera FILE         start from this camera (JSON: position, forward, up, vfov_degrees); in the\n"
         "                        window also the bookmark file F5 saves and F9 loads [camera.json]\n"
         "  --panel on|off        window: the settings and cluster panel at start [on]\n"
         "  --overlay MODE        window: tint tiles by the worker that rendered them: off, tint, solid [off]\n"
         "window: drag with the left button to look, W/A/S/D/Q/E to move, R to reset, Esc to quit;\n"
         "  F1 panel, F2 tile overlay, F5/F9 save/load camera, F12 save the accumulated image (EXR and PNG);\n"
         "  while the camera and settings are still, frames accumulate (new seed and sub-pixel position each)\n"
         "  --credits K           jobs a worker holds at once [2]\n"
         "  --heartbeat-ms MS     [250]   --timeout-ms MS  silent worker declared dead [1500]\n"
         "  --pixels F            pixels on the wire: float, half (6 bytes a pixel, display frames) or auto:\n"
         "                        float when -o is a float file (.exr, .hdr, .pfm, .tif), else half [auto]\n"
         "  --io-threads N        ZeroMQ I/O threads [1]: more pay only past ~100,000 tiles a second\n"
         "render options (as igi-render):\n" + render_usage(program);
}

static int to_int(const std::string& option, const std::string& value) {
  try {
    size_t end = 0;
    int v = std::stoi(value, &end);
    if (end == value.size() && v >= 0) return v;
  } catch (const std::exception&) {
  }
  throw std::invalid_argument(option + ": expected a non-negative integer, got '" + value + "'");
}

static bool on_off(const std::string& option, const std::string& value) {
  if (value == "on") return true;
  if (value == "off") return false;
  throw std::invalid_argument(option + ": expected on or off, got '" + value + "'");
}

// The render options as given, then the edit's words (e.g. "--vpl-paths 2 --clamp 0").
static RenderSettings edited_settings(std::vector<std::string> render_args, const std::string& edit) {
  std::istringstream words(edit);
  for (std::string word; words >> word;) render_args.push_back(word);
  return parse_render_options(render_args).settings;
}

// Refuses what would expose workers' jobs and pixels, before anything is bound.
static void check_security(MasterOptions& o) {
  if (!protocol::is_local_endpoint(o.listen) && !o.curve)
    throw std::invalid_argument("--listen " + o.listen +
                                " can be reached from other machines, so CURVE authentication and encryption are "
                                "required: give --key MASTER.key and --authorized-keys DIR (make keys with "
                                "igi-keys new NAME), or listen on tcp://127.0.0.1");
  if (o.curve && o.key_file.empty())
    throw std::invalid_argument("CURVE needs the master's secret key: --key MASTER.key (igi-keys new MASTER)");
  if (o.curve && o.authorized_keys.empty() && (o.workers == 0 || !protocol::is_local_endpoint(o.listen)))
    throw std::invalid_argument("CURVE needs the workers' public keys: --authorized-keys DIR (their .pub files)");
  if (!o.authorized_keys.empty() && !o.curve)
    throw std::invalid_argument("--authorized-keys needs --key MASTER.key: without CURVE every peer is let in");
}

PixelFormat session_pixel_format(const MasterOptions& o) {
  if (o.pixels == "float") return PixelFormat::Float32;
  if (o.pixels == "half") return PixelFormat::Float16;
  if (o.frames == 0) return PixelFormat::Float16;  // the window
  std::string ext = o.render.output.substr(o.render.output.find_last_of('.') + 1);
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  const bool float_file = ext == "exr" || ext == "hdr" || ext == "pfm" || ext == "tif" || ext == "tiff";
  return float_file ? PixelFormat::Float32 : PixelFormat::Float16;
}

MasterOptions parse_master_options(const std::vector<std::string>& args) {
  MasterOptions o;
  std::vector<std::string> render_args;
  std::optional<std::string> panel_edit;
  for (size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    auto value = [&]() -> const std::string& {
      if (i + 1 >= args.size()) throw std::invalid_argument(a + ": missing value");
      return args[++i];
    };
    if (a == "--workers") o.workers = to_int(a, value());
    else if (a == "--worker-threads") o.worker_threads = to_int(a, value());
    else if (a == "--listen") o.listen = value();
    else if (a == "--key") o.key_file = value(), o.curve = true;
    else if (a == "--authorized-keys") o.authorized_keys = value();
    else if (a == "--curve") o.curve = true;
    else if (a == "--frames") o.frames = to_int(a, value());
    else if (a == "--first-frame") o.first_frame = to_int(a, value());
    else if (a == "--min-workers") o.min_workers = to_int(a, value());
    else if (a == "--min-workers-wait") o.min_workers_wait = to_int(a, value());
    else if (a == "--progressive") o.progressive = true;
    else if (a == "--camera-path") o.camera_path = value();
    else if (a == "--stats") o.stats = value();
    else if (a == "--no-write") o.no_write = true;
    else if (a == "--screenshot-after") o.screenshot_after = std::max(1, to_int(a, value()));
    else if (a == "--credits") o.credits = std::max(1, to_int(a, value()));
    else if (a == "--heartbeat-ms") o.heartbeat_ms = std::max(10, to_int(a, value()));
    else if (a == "--timeout-ms") o.timeout_ms = std::max(50, to_int(a, value()));
    else if (a == "--test-kill-worker-after") o.kill_worker_after = to_int(a, value());
    else if (a == "--test-force-duplicates") o.force_duplicates = to_int(a, value());
    else if (a == "--test-stop-worker-after") o.stop_worker_after = to_int(a, value());
    else if (a == "--test-send-hwm") o.send_hwm = to_int(a, value());
    else if (a == "--pixels") o.pixels = value();
    else if (a == "--io-threads") o.io_threads = std::clamp(to_int(a, value()), 1, 64);
    else if (a == "--camera") o.camera_file = value();
    else if (a == "--panel") o.panel = on_off(a, value());
    else if (a == "--overlay") o.overlay = value();
    else if (a == "--test-panel-edit") panel_edit = value();
    else render_args.push_back(a);
  }
  o.render = parse_render_options(render_args);
  if (panel_edit) o.test_panel_settings = edited_settings(render_args, *panel_edit);
  if (o.overlay != "off" && o.overlay != "tint" && o.overlay != "solid")
    throw std::invalid_argument("--overlay: expected off, tint or solid, got '" + o.overlay + "'");
  if (!o.render.help) check_security(o);
  if (o.pixels != "auto" && o.pixels != "float" && o.pixels != "half")
    throw std::invalid_argument("--pixels: expected auto, float or half, got '" + o.pixels + "'");
  if (o.camera_path != "" && o.camera_path != "orbit")
    throw std::invalid_argument("--camera-path: expected 'orbit', got '" + o.camera_path + "'");
  return o;
}

}  // namespace igi
