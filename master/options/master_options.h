#pragma once
// igi-master's options: the renderer's (scene, method, size...), declared
// once in render_options.h, plus the cluster's.
#include <optional>
#include <string>
#include <vector>

#include "options/camera_path.h"
#include "image/frame_buffer.h"
#include "options/render_options.h"
#include "session/session_settings.h"

namespace CLI {
class App;
}

namespace igi {

struct MasterOptions {
  RenderOptions render;           // scene, method, settings, size, -o, seed...
  int workers = 2;                // local igi-worker processes to start
  int worker_threads = 0;         // threads per local worker; 0: cores / workers
  std::string listen = "tcp://127.0.0.1:0";  // port 0: any free port
  // CURVE: required unless `listen` is local (protocol::is_local_endpoint).
  bool curve = false;             // --curve, or implied by --key
  std::string key_file;           // the master's NAME.key
  std::string authorized_keys;    // a folder of workers' .pub files, or a list of keys
  std::string viewer_listen;      // igi-view connects here (viewer_run.cpp); "": the window is here
  std::string viewer_keys;        // the viewers' .pub files, or a list of keys
  std::string viewer_codec = "h264";  // moving frames to the viewer: h264 (lossy) or zstd (lossless)
  double viewer_mbit = 20.0;      // h264's bit rate cap, Mbit/s
  int frames = 0;                 // headless: render this many frames; 0: window
  int min_workers = 0;            // headless: the first frame waits until this many workers joined...
  int min_workers_wait = 30;      // ... or this many seconds passed
  int first_frame = 0;            // headless: the index of the first (camera path, seed, file name)
  bool progressive = false;       // headless: accumulate frames (seed advances)
  CameraPath camera_path;         // headless: --camera-path, --orbit-step, --swing
  std::string stats;              // per-frame statistics as JSON Lines (frame_stats.h)
  bool no_write = false;          // headless benchmarks: render, count, write no images
  int credits = 2;                // jobs a worker holds at once
  int heartbeat_ms = 250;
  int timeout_ms = 1500;          // a silent worker is dead after this
  std::string pixels = "auto";    // pixel format on the wire: auto (float for float files, else half), float, half
  std::string pixel_codec = "raw";  // the pixel and surface blocks on the wire: raw, zstd or lz4 (lossless)
  int io_threads = 1;             // ZeroMQ I/O threads (receive and send off the session thread)
  int screenshot_after = 4;       // window: save --screenshot after this many accumulated frames
  bool panel = true;              // window: the panel and the frame rate shown at start (Tab toggles)
  bool help = false;              // window: the keys' help shown at start (F1 toggles; a test hook)
  std::string overlay = "off";    // window: tile overlay at start: off, tint or solid (F2 cycles)
  // Window: while the view changes, frames at a preview level that fits this
  // many ms (frame_budget.h); 0: every frame full. Negative: the default
  // (kWindowFrameBudgetMs in the window, off headless).
  double frame_budget_ms = -1.0;
  bool sharp_previews = true;     // window: previews with camera rays at every pixel, and refining after a stop (--previews)
  bool reproject = true;          // window: carry the accumulated image through camera moves (view_history.h)
  int history_frames = 16;        // window: a carried pixel keeps at most this many frames of history
  // Headless motion benchmark (motion_run.cpp): a scripted user.
  std::string motion;             // "", drag or walk
  std::string motion_out = "motion";  // its log, shown images and reference cameras
  double motion_seconds = 2.0, still_seconds = 4.0;
  bool motion_legacy = false;     // as before motion was handled: no budget, no cancel, no reprojection
  // Test hooks.
  int kill_worker_after = 0;      // SIGKILL local worker 0 after this many results (once all have joined)
  int force_duplicates = 0;       // hand this many jobs to two workers on purpose
  int stop_worker_after = 0;      // SIGSTOP local worker 0 after this many results (and never resume it)
  int send_hwm = 0;               // the master's ZMQ_SNDHWM per peer; 0: ZeroMQ's default (1000)
  // Window: after the first frame shown, these settings go through the panel's commit (as if edited there).
  std::optional<RenderSettings> test_panel_settings;
};

inline constexpr double kWindowFrameBudgetMs = 40.0;

// The pixel format of the session: --pixels, or for "auto" float when the
// output is a float file (.exr, .hdr, .pfm, .tif) and half otherwise (PNG, the window).
PixelFormat session_pixel_format(const MasterOptions& options);
// What the master's session reads of them (session/session_settings.h).
SessionSettings session_settings(const MasterOptions& options);

// Parses argv[1] on; throws cli::OptionError with a message naming the option and the value.
MasterOptions parse_master_options(const std::vector<std::string>& args);
std::string master_usage(const std::string& program);
// Declares igi-master's command line on `app` (the options reference reads it).
void declare_master_options(CLI::App& app, MasterOptions& options);

}  // namespace igi
