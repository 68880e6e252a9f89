#pragma once
// The cluster at a glance: per worker its name (in its overlay colour),
// threads, tiles per second and busy share in the last shown frame, round
// trip and time since it was last heard; and the session's counts of tiles
// handed out again.
#include <vector>

#include "session/master_session.h"

namespace igi {

// A worker's share of a frame: tiles per second and the fraction of its
// threads' time spent rendering (busy seconds / (threads x frame seconds)).
struct WorkerLoad {
  double tiles_per_second = 0.0, busy_share = 0.0;
};
WorkerLoad worker_load(const PeerView& peer, const FrameRecord& frame);

// Inside an ImGui window. Returns the width the workers table needs for no
// column to be cut off (the panel's layout is sized so that it fits).
float draw_cluster_panel(const std::vector<PeerView>& peers, const FrameRecord& last_frame);

}  // namespace igi
