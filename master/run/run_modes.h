#pragma once
// igi-master's ways to run a session: headless (a number of frames,
// written to files), the window, and a remote viewer's window. Each keeps the
// session's loop on one thread that does nothing else; files, the display and
// the viewer's port have threads of their own.
#include <atomic>

#include "cluster/local_workers.h"
#include "options/master_options.h"
#include "protocol/curve.h"
#include "session/master_session.h"
#include "scene/scene.h"

namespace igi {

// Returns the exit status: 0 when every frame was written.
int run_headless(const MasterOptions& options, const Scene& scene, MasterSession& session, LocalWorkers& workers,
                 const std::atomic<bool>& interrupted);
// --motion: the motion benchmark's scripted user (motion_run.cpp).
int run_motion(const MasterOptions& options, const Scene& scene, MasterSession& session, LocalWorkers& workers,
               const std::atomic<bool>& interrupted);
int run_interactive(const MasterOptions& options, const Scene& scene, MasterSession& session, LocalWorkers& workers,
                    std::atomic<bool>& interrupted);
// --viewer-listen: the window is igi-view's, on another machine (viewer_run.cpp); runs until interrupted.
// `keys`: the master's pair and the viewers it lets in.
int run_for_viewer(const MasterOptions& options, const Scene& scene, MasterSession& session, LocalWorkers& workers,
                   const protocol::CurveServerKeys& keys, const std::atomic<bool>& interrupted);

}  // namespace igi
