#pragma once
// Everything the master's window draws over the image, and its keys:
//   F1  panel on/off (settings, cluster, frame-time graph, bookmarks)
//   F2  tile overlay: off, tint, solid (who rendered which tile)
//   F5  save the camera to the bookmark file    F9  load it
//   F12 save the accumulated image as EXR and PNG (PREFIX-NNNN.exr/.png)
// It draws with Dear ImGui; it never waits on the session: what it shows
// comes with each frame (FrameRecord, PeerView), copied by the session thread.
#include <memory>
#include <string>
#include <vector>

#include "display/frame_graph.h"
#include "display/gui.h"
#include "display/settings_panel.h"
#include "display/tile_overlay.h"
#include "master_session.h"

struct GLFWwindow;

namespace igi {

struct PanelOptions {
  bool shown = true;
  OverlayMode overlay = OverlayMode::Off;
  std::string bookmark = "camera.json";
  std::string shot_prefix = "igi-shot";
};

// What the user asked for in this frame of the panel.
struct PanelActions {
  bool save_camera = false, load_camera = false, save_image = false;
};

class WindowPanel {
 public:
  WindowPanel(GLFWwindow* window, const RenderSettings& settings, float exposure, PanelOptions options);
  // A frame the window shows now: its record, the workers when it completed, its time.
  void frame_shown(const FrameRecord& record, std::vector<PeerView> peers);
  // Builds the panels and draws them into the back buffer (over the image): build() then render().
  PanelActions draw(int accumulated);
  PanelActions build(int accumulated);  // ImGui's lists only (CPU)
  void render() { gui_.render(); }      // the lists into the back buffer
  void set_overlay(OverlayMode mode) { options_.overlay = mode; }
  SettingsPanel& settings() { return settings_; }
  const PanelOptions& options() const { return options_; }
  void set_message(std::string message) { message_ = std::move(message); }
  bool wants_mouse() const { return gui_.wants_mouse(); }
  bool wants_keyboard() const { return gui_.wants_keyboard(); }

 private:
  PanelActions read_keys();
  void draw_bookmarks(PanelActions& actions);
  Gui gui_;
  SettingsPanel settings_;
  PanelOptions options_;
  FrameGraph graph_;
  FrameRecord last_;
  std::vector<PeerView> peers_;
  std::string message_;
};

}  // namespace igi
