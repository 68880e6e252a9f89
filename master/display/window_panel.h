#pragma once
// Everything the master's window draws besides the image, and its keys
// (display/window_keys.h): the panel in a column left of the image (Tab:
// settings, cluster, frame-time graph, bookmarks), frame rate and passes at
// the column's foot, the keys' help in the middle (F1 or ?), the tile overlay
// over the image (F2); M meters the exposure, V cycles the view transforms;
// F5/F9 save and load the camera, F12 the accumulated image as EXR and PNG
// (PREFIX-NNNN.exr/.png).
// It draws with Dear ImGui; it never waits on the session: what it shows
// comes with each frame (FrameRecord, PeerView), copied by the session thread.
#include <cstdint>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "display/frame_graph.h"
#include "display/gui.h"
#include "display/panel_layout.h"
#include "display/settings_panel.h"
#include "display/tile_overlay.h"
#include "session/master_session.h"

struct GLFWwindow;

namespace igi {



struct PanelOptions {
  bool shown = true;  // the panel and the frame rate
  OverlayMode overlay = OverlayMode::Off;
  std::string bookmark = "camera.json";
  std::string shot_prefix = "igi-shot";
  bool help = false;  // the keys' help
  // While the view changes: "budget", then the levels' names (frame_budget.h), full first.
  std::vector<std::string> preview_levels;
  int preview = -1;  // -1: the frame budget picks the level; else the level index every frame takes
  int image_width = 640, image_height = 480;  // the image the window shows (the panel's width follows it)
};

// What the user asked for in this frame of the panel.
struct PanelActions {
  bool save_camera = false, load_camera = false, save_image = false;
  bool meter = false;  // M or the exposure's "auto": meter the image shown
};

class WindowPanel {
 public:
  WindowPanel(GLFWwindow* window, const RenderSettings& settings, const ToneMapping& tone, PanelOptions options);
  // A frame the window shows now: its record, the workers when it completed,
  // the frame rate (over the last second) and its level ("full", "preview 1/4").
  void frame_shown(const FrameRecord& record, std::vector<PeerView> peers, double fps, std::string level);
  // No frame came for this long (the read-out says so past a second).
  void set_waiting(double seconds) { waiting_ = seconds; }
  // Where the image goes in the window now (beside the panel's column while it is shown).
  Viewport image_viewport(float window_width, float window_height) const;
  // Builds the panels and draws them into the back buffer (beside and over the image): build() then render().
  // `taps`: the keys pressed since the last frame (InteractiveWindow::take_panel_taps),
  // so that a key tapped between two of the panel's frames still counts.
  PanelActions draw(int accumulated, const std::set<int>& taps = {});
  PanelActions build(int accumulated, const std::set<int>& taps = {});  // ImGui's lists only (CPU)
  void render() { gui_.render(); }      // the lists into the back buffer
  void set_overlay(OverlayMode mode) { options_.overlay = mode; }
  SettingsPanel& settings() { return settings_; }
  const PanelOptions& options() const { return options_; }
  // The outcome of F5, F9 or F12: on screen (top right) for a few seconds.
  void set_message(std::string message);
  bool wants_mouse() const { return gui_.wants_mouse(); }
  bool wants_keyboard() const { return gui_.wants_keyboard(); }

 private:
  PanelActions read_keys(const std::set<int>& taps);
  void draw_panel(PanelActions& actions);
  void draw_readout(int accumulated, float width);
  void draw_preview_choice();
  void draw_help();
  void draw_bookmarks(PanelActions& actions);
  void draw_message();
  Gui gui_;
  SettingsPanel settings_;
  PanelOptions options_;
  FrameGraph graph_;
  FrameRecord last_;
  std::vector<PeerView> peers_;
  std::string message_;
  double message_at_ = -1e9;  // ImGui time it was set: shown on screen for a while
  double fps_ = 0.0, waiting_ = 0.0;
  std::string level_;
  uint64_t frames_ = 0;  // shown
};

}  // namespace igi
