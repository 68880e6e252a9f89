#pragma once
// The settings panel: the method and its settings, as RenderSettings, and
// how the window shows the image (exposure in stops, the view transform). Its
// widgets are the settings' rows (core/settings_table.h): each offers its
// row's range, the range check_settings() accepts, so a VPL count below 1 or
// a clamp below 0 cannot be entered, and no value is rewritten: one the panel
// cannot show stays as it was typed on the command line. Settings that fit
// each field but not each other (anti-aliasing samples above the paths per
// set...) are shown as an error and not sent. A valid change is what the
// window sends with the next frame (protocol FrameSetup); no worker reconnects.
#include <optional>
#include <string>
#include <utility>

#include "core/settings.h"
#include "image/view_transform.h"

namespace igi {

// The method combo's choice: `settings` with method `m`, less what only ir and
// igi take (caustics, on by default in scenes with glass, and bidirectional
// IR), so picking pt or lightcuts is never held back by an option it refuses.
RenderSettings with_method(RenderSettings settings, MethodKind m);
// What is wrong with the set as a whole (the command line's and the wire's checks), or nothing.
std::optional<std::string> panel_settings_error(const RenderSettings& settings);

class SettingsPanel {
 public:
  SettingsPanel(const RenderSettings& settings, const ToneMapping& tone);
  // Draws the widgets in three sections, quality (open), filter and lighting
  // (closed), inside an ImGui window the caller opened: each row the method
  // reads, as its row says; each widget's tooltip names its command-line
  // option, in the command line's units.
  void draw();
  // The working copy, as edited, becomes the committed settings when valid (the
  // widgets call this; so does the test hook). True when the committed set changed.
  bool commit(const RenderSettings& edited);
  // Settings changed since the last call: the caller starts a new view with them.
  bool take_change();
  const RenderSettings& settings() const { return committed_; }
  // How the window shows the image: the display's own, never sent (the workers' colours stay linear).
  const ToneMapping& tone() const { return tone_; }
  void set_exposure(float factor) { tone_.exposure = factor; }  // the meter's
  void next_view();  // standard, neutral, agx, standard ...
  // The "auto" button was pressed since the last call: the caller meters the image shown.
  bool take_meter_request() { return std::exchange(meter_requested_, false); }
  const std::string& error() const { return error_; }

 private:
  void draw_tone();
  RenderSettings committed_, editing_;
  ToneMapping tone_;
  bool meter_requested_ = false;
  std::string error_;
  bool changed_ = false;
};

}  // namespace igi
