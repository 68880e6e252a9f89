#include "run/session_thread.h"

#include <cstdio>

namespace igi {

void session_loop(const MasterOptions& o, const Scene& scene, MasterSession& session, Handover& handover,
                  double budget_ms) {
  MotionPlanner planner(o, scene, budget_ms);
  try {
    while (!handover.stopped())
      for (MovedFrame& f : planner.turn(session, handover.view(), handover.waiting() < 2, 5))
        handover.deliver({std::move(f.frame), f.planned, level_name(f.level), f.weight, session.worker_count(),
                          session.peer_views()});
  } catch (const std::exception& e) {
    handover.stop(e.what());
  }
}

std::string waiting_line(double seconds) {
  char text[96];
  std::snprintf(text, sizeof text, "waiting for a frame (%.1f s)", seconds);
  return text;
}

std::string status_line(const Shown& shown, double accumulated, double fps, bool animated) {
  const CompletedFrame& f = shown.frame;
  char text[224];
  const double s = f.record.seconds;
  const int n = std::snprintf(text, sizeof text, "%.1f fps  %s  %.0f ms/frame  %.1f Mrays/s  %zu workers  ", fps,
                              shown.level.c_str(), 1e3 * s, s > 0 ? f.record.rays.total() * 1e-6 / s : 0.0,
                              shown.workers);
  if (animated) std::snprintf(text + n, sizeof text - size_t(n), "t = %.2f s", f.setup.pose.time);
  else std::snprintf(text + n, sizeof text - size_t(n), "%.1f frames accumulated", accumulated);
  return text;
}

}  // namespace igi
