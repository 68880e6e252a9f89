#pragma once
// Every option of every method, as one plain value that travels with a frame.
#include <cstdint>
#include <limits>
#include <optional>
#include <string>

namespace igi {

enum class MethodKind : uint8_t { PathTracer, InstantRadiosity, Igi, Lightcuts };

const char* method_name(MethodKind kind);
std::optional<MethodKind> parse_method(const std::string& name);

// A path length of 0 means unbounded: Russian roulette alone ends the path,
// under this safety cap (albedo 0.9 leaves 0.9^256 ~ 2e-12 of the light there).
inline constexpr int kDepthSafetyCap = 256;
inline int depth_limit(int depth) { return depth > 0 ? depth : kDepthSafetyCap; }

// Bounds of the options: the settings' rows (core/settings_table.h) and the code that sizes arrays by them.
inline constexpr int kMaxDepth = 1024;
inline constexpr int kMaxInterleave = 16;
inline constexpr int kMaxPathsPerSet = 1 << 20;
inline constexpr int kMaxVplDraws = 1024;
inline constexpr int kMaxCompensationSamples = 256;
inline constexpr int kMaxAntialiasSamples = 64;  // 8 x 8 sub-samples
inline constexpr int kMaxGlossyRays = 64;
inline constexpr int kMaxGlassBranches = 8;
inline constexpr int kMaxImportancePaths = 1 << 20;  // camera paths of the light-importance estimate
inline constexpr int kMaxBidirPaths = 4096;          // bidirectional: light and camera paths per set
inline constexpr int kMaxBidirVpls = 1 << 16;        // bidirectional: VPLs kept per set
inline constexpr int kBidirAuto = -1;               // bidirectional: chosen by the view
inline constexpr int kMaxWaveletLevels = 5;
inline constexpr int kMaxLightDivisor = 16;
// Above this the clamp distance (core/clamp.h) would exceed several rooms:
// nothing is left unclamped, and the image is a blur of VPL light.
inline constexpr float kMaxClamp = 4.0f;

// The wavelet filter's footprint (wavelet/wavelet_filter.h): pixels an
// output pixel reads on each side; 0 for 0 levels (no filter).
constexpr int wavelet_footprint(int levels) { return levels > 0 ? 2 << levels : 0; }

namespace lightcuts {  // lightcuts/lightcuts_settings.h says what each option does
inline constexpr int kMaxCut = 1 << 20;
inline constexpr int kMaxSpacing = 64;
inline constexpr int kMaxSamples = 64;
inline constexpr int kMaxBlock = 8;  // block cuts of at most 8 x 8 pixels
}  // namespace lightcuts

namespace photons {  // photons/caustic_settings.h says what each option does
inline constexpr int kMaxCausticPhotons = 1 << 26;
inline constexpr float kMinCausticRadius = 1e-5f;
inline constexpr float kMaxCausticRadius = 0.25f;
}  // namespace photons

// A member's initializer is its default (--help, the options reference and
// the panel read it from here); each member has a row in core/settings_table.h,
// which says its option, range and widget. The measurements behind the
// defaults of anti-aliasing, clamp and compensation: tests/bench/history/
// RESULTS-to-2026-12-05.md, "Convergence".
struct RenderSettings {
  MethodKind method = MethodKind::Igi;
  // Path lengths, in surface interactions after the camera or the light; 0 = unbounded.
  int path_depth = 0;       // pt: the whole path
  int light_depth = 0;      // ir/igi: VPL light paths
  int specular_depth = 16;  // ir/igi: mirrors and glass followed from the camera
  // Instant radiosity / IGI.
  // N: N x N VPL sets, pixel set = (x mod N) + N (y mod N). Six: 36 sets
  // of M paths, 4x the VPLs of 3 x 3 for the same shadow rays a pixel, so a
  // building's rooms are lit in one pass (tests/bench/history/RESULTS-to-2026-12-05.md, "Six VPL
  // sets by default"); ir sums all of them at every pixel.
  int interleave = 6;
  int paths_per_set = 16;      // M: light paths started per VPL set
  // Stochastic VPL selection (stochastic lightcuts, Yuksel 2019): each shading
  // point draws K VPLs of all S sets from a light tree by their bound, one
  // shadow ray each, instead of its set's group (methods/vpl_draws.h). 0 = sets.
  int vpl_draws = 0;
  // Anti-aliasing by VPL groups: S = s x s stratified sub-samples per pixel,
  // each shaded by 1/S of the pixel's light paths (core/subpixel.h). 1 = off.
  int aa_samples = 4;
  // GGX surfaces with alpha below this are too sharp for VPLs (each would show
  // as a highlight of its own): their lobe is gathered with BSDF-sampled rays
  // shaded by the VPLs where they land (methods/glossy_gather.h), and light
  // paths pass through them without leaving VPLs. 0 = VPLs shade every GGX surface.
  float glossy_threshold = 0.2f;
  int glossy_rays = 1;         // gather rays per sub-sample of such a surface
  // Geometry-term bound (core/clamp.h), scale-free and consistent: clamp
  // is the distance, a fraction of the scene's mean chord (about a room),
  // below which 1/r^2 stops growing in one frame; progressive pass k clamps
  // at clamp / (k + 1)^(1/4) of it, so passes converge to the unclamped
  // estimate. 0 turns clamping off.
  float clamp = 0.3f;
  // Bias compensation (Kollig and Keller): eye-path samples per pixel that
  // add back the light the clamp cut (methods/bias_compensation.h). 0 = off;
  // no effect without a clamp. On by default since the clamp is a fraction of
  // the mean chord: its rays are short, so it costs 1.1-1.2x a frame, and it
  // takes the corner scene's 16-pass mean from 0.958 to 0.981 of pt
  // (tests/bench/history/RESULTS-to-2026-12-05.md, "Convergence").
  int compensation_samples = 4;
  // Discontinuity buffer (igi).
  bool filter = true;
  float filter_normal_cos = 0.9f;   // neighbours need dot(n, n') above this
  float filter_depth_ratio = 0.05f; // and |d - d'| below this fraction of d
  // ir/igi: levels of the edge-avoiding wavelet filter (wavelet/wavelet_filter.h)
  // after the discontinuity buffer, which smooths the blotches it leaves;
  // passes use fewer levels as they accumulate. 0 = off.
  int wavelet_levels = 0;
  // Lightcuts over the VPLs of all sets (common/lightcuts/lightcuts_settings.h).
  float lightcuts_error = 0.02f;  // refine until every cluster's bound < error x the cut's total
  int lightcuts_max_cut = 1000;   // and stop at this many nodes in a cut
  int lightcuts_spacing = 0;      // reconstruction cuts: full cuts every S pixels only; 0 = off
  int lightcuts_samples = 1;      // multidimensional lightcuts: K = s x s gather points per pixel
  // ir/igi: glass seen from the camera splits into reflection and refraction
  // at its first B - 1 surfaces, each branch a G-buffer layer of its own
  // (core/gbuffer.h); past them glass picks one by Fresnel. 1 = always pick.
  int glass_branches = 3;
  // ir/igi: caustic photon map (common/photons/): light that reached a
  // diffuse surface through mirrors or glass, added after the filter.
  bool caustics = false;
  int caustic_photons = 20000;    // photon paths shot per frame (photons/caustic_settings.h)
  float caustic_radius = 0.01f;   // density-estimation radius, a fraction of the scene diagonal
  // Light importance for the current view (ir/igi; common/importance/light_importance.h):
  // VPL light paths start at lights in proportion to an estimate of what each
  // adds to the image, from this many camera paths. 0 = lights by power. On
  // by default: in a building of many rooms it puts the paths in the rooms
  // the camera sees (rooms-10 at one pass: FLIP 0.09 against 0.18); with one
  // light it is skipped, and elsewhere it costs a few thousand short paths
  // a frame. pt and lightcuts ignore it (tests/bench/history/RESULTS-to-2026-12-05.md, "Light
  // importance by default").
  int importance_paths = 4096;
  float importance_floor = 0.2f;  // share of the light paths still started by power (no light starved)
  // Bidirectional instant radiosity (ir/igi; common/importance/bidirectional.h):
  // each set's M light paths and R camera paths give candidate VPLs, of which
  // this many are kept by their estimated contribution to the image. 0 = off;
  // kBidirAuto (the default): 2 M (of 2 M light paths) where the view sees
  // few of the light paths' VPLs, else off (importance/view_vpls.h; the
  // corridor scene at one pass: FLIP 0.097 against 0.168 by light paths alone).
  int bidir_vpls = kBidirAuto;
  int bidir_camera_paths = 0;     // R; 0 = as many as light paths (M)
  // Lightcuts' block cuts: the B x B pixels of a block on one Lambertian
  // surface share one light cut, bounded once for all of them, with their
  // shadow rays in packets (lightcuts/cut.h). 0 or 1: a cut per pixel.
  // Plain cuts only (no --lightcuts-spacing, one gather point a pixel).
  int lightcuts_block = 4;
  // Light paths that find the view (ir/igi; common/importance/view_guide.h):
  // a directional light's and the sky's paths start where pilot paths found
  // that they reach what the camera sees, their power divided by that
  // density. Where a sun lights a room through its windows a few percent of
  // the plain rule's paths enter, and the room's brightness at one pass
  // swung with the seed (BreakfastRoom: 0.27 to 1.57 of pt); where most
  // paths reach the view the paths stay the plain rule's, bit for bit.
  bool light_guide = true;
  // Light at one pixel in D x D: camera rays at every pixel, light shaded on
  // a lattice and upsampled along the pixels' surfaces
  // (methods/light_upsample.h); the window's previews while the camera moves. 1 = off.
  int light_divisor = 1;
};


// The one check of RenderSettings, called by the command lines, the window's
// panel, the methods and the wire decoder: the first rule broken, or nothing
// when every field is within its row's bound (core/settings_table.h) and the
// fields fit together. `field` is the
// member's name (the wire's "settings.aa_samples"), `message` names
// igi-render's option ("--aa: expected ..., got 8").
struct SettingsError {
  std::string field;
  std::string message;
};
std::optional<SettingsError> check_settings(const RenderSettings& settings);
// check_settings()'s message.
std::optional<std::string> settings_error(const RenderSettings& settings);

}  // namespace igi
