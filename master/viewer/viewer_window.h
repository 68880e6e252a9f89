#pragma once
// igi-view's window: igi-master's window code (display/: the window, its
// panel, the camera controls, ViewChanges) on the viewer's machine. What the
// user does goes to the master as a View (stamped with the time of the input)
// or a Request (M meters; F12 saves the master's float image there and sends
// it, kept here as EXR and PNG); F5 and F9 keep the camera
// file here. What it shows are the master's display frames, as they come.
#include <atomic>
#include <string>
#include <vector>

#include "viewer/viewer_options.h"

namespace igi {

// What a session of the viewer measured, printed at its end.
struct ViewerFigures {
  int frames = 0;              // shown
  double seconds = 0.0;        // from the first frame shown to the last
  double bytes = 0.0, pixels = 0.0;  // of the frames shown, as sent
  std::vector<double> delays_ms;     // input to the first frame that shows it, per input
  std::string summary() const;
};

// Runs until the window closes or `interrupted`; throws ViewerError (viewer_client.h) when the link fails.
ViewerFigures run_viewer(const ViewerOptions& options, const std::atomic<bool>& interrupted);

}  // namespace igi
