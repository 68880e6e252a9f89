#pragma once
// Which worker rendered which tile: each tile of the last shown frame is
// tinted (or, for a plain map, painted) in its worker's colour. Colours come
// from a fixed palette by worker number, so "worker-N" has one colour all run.
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "display/panel_layout.h"
#include "session/master_session.h"

namespace igi {

enum class OverlayMode { Off, Tint, Solid };

// "off", "tint", "solid"; nullopt for anything else.
std::optional<OverlayMode> parse_overlay(const std::string& name);
const char* overlay_name(OverlayMode mode);
OverlayMode next_overlay(OverlayMode mode);

inline constexpr size_t kPaletteSize = 8;
// 8-bit sRGB, distinct at a glance and from each other by at least 100 in some channel.
std::array<uint8_t, 3> worker_colour(uint32_t worker);

// Draws on ImGui's background list (under the panels, over the image), the
// image at `where` in the window.
void draw_tile_overlay(const std::vector<TileSource>& tiles, OverlayMode mode, const Viewport& where);

}  // namespace igi
