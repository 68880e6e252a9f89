#include "display/panel_layout.h"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include <imgui.h>

namespace igi {

namespace {

constexpr float kMaxPanelWidth = 420.0f;
// The panel is this wide, or wider, for 13-pixel text, and narrower in
// proportion for smaller: its widest section, the cluster table, needs 196
// pixels in 13-pixel text and 184 in 12 (WindowPanel.TheClusterTableFitsThe-
// PanelAtEverySize prints them), so a 640-pixel window gets 12-pixel text.
constexpr float kWidthAt13Pixels = 230.0f;
constexpr int kSmallestFont = 8, kLargestFont = 13;
const char* const kPanelFontFile = "/usr/share/fonts/truetype/dejavu/DejaVuSansCondensed.ttf";

}  // namespace

PanelLayout panel_layout(float window_width) {
  PanelLayout layout;
  layout.width = std::min(window_width / 3.0f, kMaxPanelWidth);
  layout.font_pixels = std::clamp(std::floor(float(kLargestFont) * layout.width / kWidthAt13Pixels),
                                  float(kSmallestFont), float(kLargestFont));
  layout.start_folded = window_width < 480.0f;
  return layout;
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
