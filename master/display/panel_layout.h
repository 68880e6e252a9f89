#pragma once
// How the window's panel and image share the window: the panel's column,
// its text size and fonts, where the image goes. Apart from the panel itself
// (window_panel.h) so that tests measure the layout with ImGui alone, without
// a window or OpenGL.
struct ImFont;

namespace igi {

// The panel's column, left of the image and never over it, for an image
// this wide: a third of it, 220 to 420 pixels, its text in the font size
// that fits its widest section (the cluster table) in that width, 13 pixels
// down to 8.
struct PanelLayout {
  float width = 0.0f;
  float font_pixels = 13.0f;
};
PanelLayout panel_layout(int image_width);

// A rectangle of the window in pixels, (0, 0) top left.
struct Viewport {
  float x = 0.0f, y = 0.0f, width = 0.0f, height = 0.0f;
  float scale = 1.0f;  // window pixels per image pixel
};
// Where the image shows in a window: right of the panel's column (`panel_width`,
// 0 while it is hidden), whole, its aspect kept, at its own size or smaller
// where the rest of the window is smaller, centred.
Viewport image_viewport(float window_width, float window_height, int image_width, int image_height,
                        float panel_width);
// The window's width: the image's, plus the panel's column when it opens at
// the start and the screen (its work area) has room beside the image.
int window_width(int image_width, float panel_width, bool panel_shown, int screen_width);
// Whether the panel opens at the start, when asked: not where the image
// beside it would show at under half its size (a small window that the
// screen could not widen; Tab still opens it).
bool panel_opens(float window_width, float window_height, int image_width, int image_height, float panel_width);
// The read-out's strip at the bottom of the panel's column: two lines.
inline constexpr float kReadoutHeight = 40.0f;

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
