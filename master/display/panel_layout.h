#pragma once
// How the window's panel fits the window: its width, its text size, its
// fonts. Apart from the panel itself (window_panel.h) so that tests measure
// the layout with ImGui alone, without a window or OpenGL.
struct ImFont;

namespace igi {

// The panel for a window this wide: a third of it (at most 420 pixels), its
// text in the font size that fits its widest section (the cluster table) in
// that width, 13 pixels down to 8; in a window under 480 pixels it opens
// folded to its title bar.
struct PanelLayout {
  float width = 0.0f;
  float font_pixels = 13.0f;
  bool start_folded = false;
};
PanelLayout panel_layout(float window_width);

// Loads the panel's fonts into the current ImGui context (DejaVu Sans
// Condensed at 8 to 13 pixels, when the system has it; else ImGui's own,
// scaled): call before its first frame. Returns the font for `pixels`, and
// its scale, once loaded.
void load_panel_fonts();
struct PanelFont {
  ImFont* font = nullptr;  // null: ImGui's default font
  float scale = 1.0f;      // SetWindowFontScale
};
PanelFont panel_font(float pixels);

}  // namespace igi
