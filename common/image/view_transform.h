#pragma once
// What a screen shows of a linear image (Rec.709 primaries, radiance or any
// scale of it): the image times an exposure, through a view transform to
// display-linear RGB in [0, 1], then the sRGB curve. One function for every
// 8-bit output: the PNG writer, the window (whose shader looks it up in a
// table sampled from it, view_table()) and a remote viewer's encoder. Float
// files (EXR, HDR) take none of it: they stay linear.
//
//   standard  each channel clipped at 1 (Blender's "Standard"): every 8-bit
//             output before views, byte for byte.
//   neutral   Khronos PBR Neutral (Khronos Group 2024, KhronosGroup/ToneMapping,
//             PBR_Neutral/README.md): a base colour in [0.08, 0.8] under unit
//             white light shows as itself less the 0.04 that an ior-1.5
//             surface reflects; brighter colours compress towards white
//             without a hue shift.
//   agx       AgX (Troy Sobotka's, as Blender has shown it by default since
//             4.0, after EaryChow/AgX_LUT_Gen's AgXBaseRec2020.py): Rec.2020
//             primaries pulled in (inset), a log2 encoding from 10 stops under
//             to 6.5 over middle grey, a sigmoid through middle grey that rolls
//             highlights off to white at 16.3 (6.5 stops over), primaries pushed
//             out again (outset). Left out, as in Allen Pestaluky's port for
//             Godot (allenwp/AgX-GLSL-Shaders): Blender's 40 % hue mix and its
//             guard rails for negative input.
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace igi {

enum class ViewTransform : uint8_t { Standard, Neutral, Agx };
inline constexpr std::array<ViewTransform, 3> kViewTransforms{ViewTransform::Standard, ViewTransform::Neutral,
                                                              ViewTransform::Agx};
const char* view_name(ViewTransform view);  // "standard", "neutral", "agx"
std::optional<ViewTransform> parse_view(const std::string& name);

// How an 8-bit output shows a linear image. Plain data: a viewer can hold it
// and send it, and whoever holds the linear image applies it.
struct ToneMapping {
  float exposure = 1.0f;  // a factor (2^EV) the image is multiplied by first
  ViewTransform view = ViewTransform::Standard;
};

// Display-linear RGB in [0, 1] of an exposed linear colour (negative channels
// count as 0).
glm::vec3 view_transform(glm::vec3 exposed, ViewTransform view);
// The three bytes of 8-bit sRGB an output shows for a linear colour.
std::array<uint8_t, 3> tone_map_srgb8(glm::vec3 linear, const ToneMapping& tone);

// AgX's sigmoid on its log2 encoding x (0 = 10 stops under middle grey, 1 =
// 6.5 over): values for a display of gamma 2.4 (Blender's
// AgX_Default_Contrast.spi1d holds it at 4096 points). Exposed for its test.
float agx_sigmoid(float x);

// The window's table: a view sampled at kViewTableSize^3 exposed colours,
// each channel spaced evenly in log2 from kViewTableLog2Min to
// kViewTableLog2Max (1.0 is a node: a quarter stop apart), red fastest;
// entries are sRGB-encoded (what the screen gets), so a shader interpolates
// them in log2 of the exposed colour and writes the result. A channel under
// 2^kViewTableLog2Min reads at the lowest node, whose entry is the view's
// value at 0 (black stays black); over 2^kViewTableLog2Max, at the highest.
inline constexpr int kViewTableSize = 81;
inline constexpr float kViewTableLog2Min = -12.0f, kViewTableLog2Max = 8.0f;
std::vector<glm::vec3> view_table(ViewTransform view);
// What the table gives for an exposed colour: interpolated between the four
// nodes of the tetrahedron around it (as OpenColorIO interpolates tables; a
// grey between greys only), as the window's shader does (for tests that bound
// its error).
glm::vec3 view_table_lookup(const std::vector<glm::vec3>& table, glm::vec3 exposed);

}  // namespace igi
