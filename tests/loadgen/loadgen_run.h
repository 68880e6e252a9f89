#pragma once
// One load-generator run: an igi-master (the real program) with no workers
// of its own, and simulated workers over real ZeroMQ sockets; the master's
// throughput, CPU per tile, frame latency and memory measured from outside.
//
// CPU comes from /proc (every thread of the master: its session thread and
// ZeroMQ's I/O threads) over a window that starts after the warm-up frames;
// so does RSS, sampled every 20 ms. Frame latency is what the master prints
// per frame (first job out to last result in). Every sample is written to
// DIR/samples.csv.
#include <cstdint>
#include <string>
#include <vector>

#include "sim_worker.h"

namespace igi::loadgen {

struct LoadgenOptions {
  std::string master_binary;
  std::string dir = "loadgen-run";   // master log, stats, frames
  int workers = 8;
  int width = 640, height = 480, tile = 32;
  std::string pixels = "half";       // the master's --pixels
  std::string pixel_codec = "raw";   // the master's --pixel-codec
  std::string picture;               // the tiles' pixels: this image's (at least the frame's size); else a gradient
  // Where the master listens and the workers connect (empty: loopback, a free
  // port); off loopback the master needs CURVE (master_args --key,
  // --authorized-keys) and the workers these key files.
  std::string endpoint;
  std::string worker_key, master_public_key;
  int frames = 300;
  int warmup_frames = 10;
  // Paces the workers: tile time = busy lanes / (fps x tiles per frame), where the busy lanes are
  // workers x threads, at most two frames' tiles (the master keeps two frames open).
  double fps = 30.0;
  double tile_ms = -1.0;             // >= 0: this render time instead (0: answer at once, flat out)
  int threads = 1;                   // per simulated worker
  int pools = 2;                     // driver threads
  int io_threads = 1;                // the master's
  int heartbeat_ms = 250, timeout_ms = 1500;
  bool write_frames = false;         // the master writes EXR frames into dir (float pixels) for checking
  bool stats = false;                // the master writes stats.json (JSON Lines, grows with frames)
  std::vector<std::string> master_args;  // more, e.g. {"--credits", "4"}
  std::vector<std::string> master_env;   // NAME=VALUE for the master's environment (LD_PRELOAD=...)
  double deadline_seconds = 120.0;
  bool sample_memory = true;
};

struct LoadgenReport {
  int exit_code = -1;                // the master's
  std::string master_log;            // its last lines
  int frames_done = 0;
  int tiles_per_frame = 0;
  double tile_seconds = 0.0;         // the simulated render time used
  // Over the measured window (after the warm-up frames):
  double wall_seconds = 0.0, fps = 0.0, tiles_per_second = 0.0;
  double master_cpu_seconds = 0.0, session_cpu_seconds = 0.0;
  double cpu_us_per_tile = 0.0, session_us_per_tile = 0.0;
  double cores = 0.0;                // master CPU seconds per wall second
  double latency_median_ms = 0.0, latency_p95_ms = 0.0;
  // Memory: median RSS over the first and second halves of the frames after warm-up, and the peak.
  double rss_first_mib = 0.0, rss_second_mib = 0.0, rss_peak_mib = 0.0;
  // The scheduler's totals, from the master's last log line (-1: not found).
  long duplicated = -1, reissued = -1, verified = -1;
  std::vector<SimOutcome> workers;
  int quarantined_workers() const;
  int welcomed_workers() const;
};

// One simulated worker per behaviour.
LoadgenReport run_loadgen(const LoadgenOptions& options, const std::vector<SimBehaviour>& behaviours);

// The simulated tiles' pixels (the picture's, or the gradient).
TileCache make_tile_cache(const LoadgenOptions& options);

// Checks every `every`-th frame the master wrote (write_frames) pixel by pixel
// against the simulated tiles as the master gets them (sent_pixel); returns
// what is wrong (empty: all exact).
std::vector<std::string> check_written_frames(const LoadgenOptions& options, int every);

// Tiles per frame of a size, as the master cuts it.
int tiles_per_frame(int width, int height, int tile);
// The simulated render time that paces `workers` to `fps`.
double paced_tile_seconds(const LoadgenOptions& options);

}  // namespace igi::loadgen
