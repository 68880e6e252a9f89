#include "display/tile_overlay.h"

#include <imgui.h>

namespace igi {

std::optional<OverlayMode> parse_overlay(const std::string& name) {
  if (name == "off") return OverlayMode::Off;
  if (name == "tint") return OverlayMode::Tint;
  if (name == "solid") return OverlayMode::Solid;
  return std::nullopt;
}

const char* overlay_name(OverlayMode mode) {
  switch (mode) {
    case OverlayMode::Off: return "off";
    case OverlayMode::Tint: return "tint";
    case OverlayMode::Solid: return "solid";
  }
  return "?";
}

OverlayMode next_overlay(OverlayMode mode) {
  return mode == OverlayMode::Off ? OverlayMode::Tint : mode == OverlayMode::Tint ? OverlayMode::Solid : OverlayMode::Off;
}

std::array<uint8_t, 3> worker_colour(uint32_t worker) {
  static constexpr std::array<std::array<uint8_t, 3>, kPaletteSize> palette{{
      {230, 25, 75}, {60, 180, 75}, {0, 130, 200}, {255, 225, 25},
      {145, 30, 180}, {70, 240, 240}, {245, 130, 48}, {250, 190, 212},
  }};
  return palette[worker % kPaletteSize];
}

void draw_tile_overlay(const std::vector<TileSource>& tiles, OverlayMode mode, const Viewport& where) {
  if (mode == OverlayMode::Off) return;
  ImDrawList* list = ImGui::GetBackgroundDrawList();
  list->Flags &= ~ImDrawListFlags_AntiAliasedLines;  // plain one-pixel outlines: fewer, thinner triangles
  const int alpha = mode == OverlayMode::Solid ? 255 : 90;
  for (const TileSource& t : tiles) {
    const auto c = worker_colour(t.worker);
    auto at = [&](int x, int y) { return ImVec2(where.x + where.scale * float(x), where.y + where.scale * float(y)); };
    const ImVec2 a = at(t.tile.x, t.tile.y), b = at(t.tile.x + t.tile.w, t.tile.y + t.tile.h);
    list->AddRectFilled(a, b, IM_COL32(c[0], c[1], c[2], alpha));
    if (mode == OverlayMode::Tint) list->AddRect(a, b, IM_COL32(c[0], c[1], c[2], 200));
  }
}

}  // namespace igi
