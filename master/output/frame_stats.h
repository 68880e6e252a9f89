#pragma once
// Per-frame statistics of a master run (--stats FILE), as JSON Lines: one
// object a line, appended as the run goes on.
//   {"frame": N, "seconds": ..., "completed_at": ..., "tiles": ..., ..., "workers": {...}}   one per frame, in order
// ("seconds": the frame's own latency; "completed_at": since the session began,
// so the steady rate of overlapping frames is a difference of two of these)
//   {"complete": false, "outcome": "running", "bad_messages": ..., ...}  the run's totals so far
// A totals line follows the frames now and then, so a master that is killed
// leaves its figures; the last line of a run that ended is its totals with
// "complete": true and how it ended: "outcome" "done" (every frame written),
// "interrupted" or "failed". A reader takes the frame lines in order and the last totals.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "session/master_session.h"

namespace igi {

struct RunTotals {
  uint64_t bad_messages = 0;       // frames that did not decode, dropped
  uint64_t refused_keys = 0;       // CURVE: worker keys the ZAP handler refused
  uint64_t failed_handshakes = 0;  // CURVE: peers without CURVE or the right master key
  uint64_t nonfinite_pixels = 0;   // pixels workers rendered NaN or infinite and sent as black
  uint64_t declared_dead = 0;      // workers silent past --timeout-ms (or not reading), their jobs given to others
  double unlistened_seconds = 0.0; // time the session was not listening (stalled), not counted as workers' silence
  std::vector<std::string> quarantined;  // "worker-N: why"
  uint64_t own_tiles = 0;          // jobs no worker's result passed for, rendered by the master
  uint64_t benched = 0;            // hoarders given no more jobs until they answered
  uint64_t doubted = 0;            // frames in doubt: the master rendered what its workers contested
  bool follows_workers = false;    // the master's VPL sets lost to its authenticated workers' (CURVE)
  double master_cpu_seconds = 0.0;   // process CPU (every thread) during the session loop
  double session_cpu_seconds = 0.0;  // the session thread's own CPU
  uint64_t hash_frames = 0;          // frames whose VPL-set hash the master computed itself (master_renderer.h)
  double hash_seconds = 0.0;         // its thread's time on them (off the session thread; ahead of headless frames)
  double peak_rss_mib = 0.0;         // the master's peak memory (its own copy of the scene and BVH included)
  double wall_seconds = 0.0;
  std::string pixel_format;        // on the wire: float, half or rgb9e5
  std::string pixel_codec;         // and packed: raw, zstd or lz4
  int io_threads = 0;
  bool complete = false;           // false while the run goes on
  std::string outcome = "running"; // then: done, interrupted or failed
};

// The session's counts for the statistics file: CPU since `cpu_start`
// (process_cpu_seconds() when the run began) and the run's wall time.
RunTotals run_totals(const MasterSession& session, int io_threads, double cpu_start, double wall_seconds);

// A frame's line, and the totals' line (`tiles`: of every frame so far).
nlohmann::ordered_json frame_json(const FrameRecord& frame);
nlohmann::ordered_json totals_json(const RunTotals& totals, uint64_t tiles);
// CPU time this process has used (user + system), all threads.
double process_cpu_seconds();

}  // namespace igi
