#pragma once
// Every option of every method, as one plain value that travels with a frame.
#include <cstdint>
#include <optional>
#include <string>

namespace igi {

enum class MethodKind : uint8_t { PathTracer, InstantRadiosity, Igi, Lightcuts };

const char* method_name(MethodKind kind);
std::optional<MethodKind> parse_method(const std::string& name);

struct RenderSettings {
  MethodKind method = MethodKind::Igi;
  int max_depth = 16;          // pt: path vertices; igi/ir: specular chain length
  // Instant radiosity / IGI.
  int interleave = 3;          // N: N x N VPL sets, pixel set = (x mod N) + N (y mod N)
  int paths_per_set = 16;      // M: light paths started per VPL set
  // Geometry-term bound, scale-free: G <= 1 / (clamp * scene diagonal)^2, so
  // clamp is the distance (a fraction of the diagonal) below which 1/r^2 stops
  // growing. 0 turns clamping off.
  float clamp = 0.0f;
  // Bias compensation (Kollig and Keller): eye-path samples per pixel that
  // add back the light the clamp cut (methods/bias_compensation.h). 0 = off;
  // no effect without a clamp.
  int compensation_samples = 0;
  // Discontinuity buffer (igi).
  bool filter = true;
  float filter_normal_cos = 0.9f;   // neighbours need dot(n, n') above this
  float filter_depth_ratio = 0.05f; // and |d - d'| below this fraction of d
  // Lightcuts over the VPLs of all sets (common/lightcuts/lightcuts_settings.h).
  float lightcuts_error = 0.02f;  // refine until every cluster's bound < error x the cut's total
  int lightcuts_max_cut = 1000;   // and stop at this many nodes in a cut
  int lightcuts_spacing = 0;      // reconstruction cuts: full cuts every S pixels only; 0 = off
  int lightcuts_samples = 1;      // multidimensional lightcuts: K = s x s gather points per pixel
};

}  // namespace igi

namespace igi {
// Extra pixels around a tile that the method needs to read (the filter window).
inline int tile_border(const RenderSettings& s) {
  return s.method == MethodKind::Igi && s.filter ? s.interleave / 2 : 0;
}
}  // namespace igi
