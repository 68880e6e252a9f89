#include "display/panel_layout.h"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include <imgui.h>

namespace igi {

namespace {

constexpr float kMinPanelWidth = 220.0f, kMaxPanelWidth = 420.0f;
// The panel is this wide, or wider, for 13-pixel text, and narrower in
// proportion for smaller: its widest section, the cluster table, needs 196
// pixels in 13-pixel text and 184 in 12 (WindowPanel.TheClusterTableFitsThe-
// PanelAtEverySize prints them), so a 640-pixel image gets 12-pixel text.
constexpr float kWidthAt13Pixels = 230.0f;
constexpr int kSmallestFont = 8, kLargestFont = 13;
const char* const kPanelFontFile = "/usr/share/fonts/truetype/dejavu/DejaVuSansCondensed.ttf";

}  // namespace

PanelLayout panel_layout(int image_width) {
  PanelLayout layout;
  layout.width = std::clamp(float(image_width) / 3.0f, kMinPanelWidth, kMaxPanelWidth);
  layout.font_pixels = std::clamp(std::floor(float(kLargestFont) * layout.width / kWidthAt13Pixels),
                                  float(kSmallestFont), float(kLargestFont));
  return layout;
}

Viewport image_viewport(float window_width, float window_height, int image_width, int image_height,
                        float panel_width) {
  const float room_x = std::max(window_width - panel_width, 0.0f), room_y = window_height;
  Viewport v;
  v.scale = std::min({1.0f, room_x / float(image_width), room_y / float(image_height)});
  v.width = std::round(v.scale * float(image_width));
  v.height = std::round(v.scale * float(image_height));
  v.x = panel_width + std::floor(0.5f * (room_x - v.width));
  v.y = std::floor(0.5f * (room_y - v.height));
  return v;
}

int window_width(int image_width, float panel_width, bool panel_shown, int screen_width) {
  const int wide = image_width + int(std::ceil(panel_width));
  return panel_shown && wide <= screen_width ? wide : image_width;
}

bool panel_opens(float window_width, float window_height, int image_width, int image_height, float panel_width) {
  return image_viewport(window_width, window_height, image_width, image_height, panel_width).scale >= 0.5f;
}

void load_panel_fonts() {
  ImGuiIO& io = ImGui::GetIO();
  if (io.Fonts->Fonts.empty()) io.Fonts->AddFontDefault();  // the read-out's and the help's
  if (!std::filesystem::exists(kPanelFontFile)) return;
  for (int pixels = kSmallestFont; pixels <= kLargestFont; ++pixels)
    io.Fonts->AddFontFromFileTTF(kPanelFontFile, float(pixels));
}

PanelFont panel_font(float pixels) {
  const ImVector<ImFont*>& fonts = ImGui::GetIO().Fonts->Fonts;
  const int index = 1 + int(pixels) - kSmallestFont;  // after the default font
  if (fonts.Size == 1 + kLargestFont - kSmallestFont + 1 && index >= 1 && index < fonts.Size) return {fonts[index], 1.0f};
  return {nullptr, pixels / float(kLargestFont)};  // ImGui's own 13-pixel font, scaled
}

}  // namespace igi
