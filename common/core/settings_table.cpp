#include "core/settings_table.h"

#include <array>
#include <limits>

namespace igi {
namespace {

using R = RenderSettings;
constexpr double kFloatMax = std::numeric_limits<float>::max();

// One row per field, in the wire's order. Each says what the field does
// (what each method does with it: common/README.md), its range, its option
// and its widget; its default is RenderSettings' own.
constexpr std::array kSettings = std::to_array<Setting>({
    {.field = "method", .wire = "settings.method", .member = &R::method, .option = "--method",
     .value = "pt|ir|igi|lightcuts",
     .help = "rendering method: pt, the path-traced reference; ir and igi, virtual point lights (igi: each pixel "
             "shades its own set, the discontinuity buffer averages its neighbours'); lightcuts, VPL clusters",
     .methods = kAllMethods, .bound = Bound::Method, .widget = Widget::Combo, .label = "method"},
    {.field = "path_depth", .wire = "settings.path_depth", .member = &R::path_depth, .option = "--path-depth",
     .value = "D", .help = "longest path in bounces, 0 = unbounded (Russian roulette)", .methods = kPt,
     .bound = Bound::Closed, .lo = 0, .hi = kMaxDepth, .note = " (0 = unbounded)", .widget = Widget::LogSlider,
     .label = "path depth"},
    {.field = "light_depth", .wire = "settings.light_depth", .member = &R::light_depth, .option = "--light-depth",
     .value = "D", .help = "longest VPL light path, 0 = unbounded (Russian roulette)",
     .methods = kVplMethods | kLightcuts, .bound = Bound::Closed, .lo = 0, .hi = kMaxDepth, .note = " (0 = unbounded)",
     .widget = Widget::LogSlider, .section = Section::Lighting, .label = "light depth"},
    {.field = "specular_depth", .wire = "settings.specular_depth", .member = &R::specular_depth,
     .option = "--specular-depth", .value = "D", .help = "mirrors and glass followed from the camera, 0 = unbounded",
     .methods = kVplMethods | kLightcuts, .bound = Bound::Closed, .lo = 0, .hi = kMaxDepth, .note = " (0 = unbounded)",
     .widget = Widget::LogSlider, .section = Section::Lighting, .label = "mirror depth"},
    {.field = "interleave", .wire = "settings.interleave", .member = &R::interleave, .option = "--vpl-sets",
     .value = "N", .help = "N x N interleaved VPL sets: each pixel of an N x N block takes its own",
     .methods = kVplMethods | kLightcuts, .bound = Bound::Closed, .lo = 1, .hi = kMaxInterleave,
     .widget = Widget::Slider, .label = "VPL sets (NxN)"},
    {.field = "paths_per_set", .wire = "settings.paths_per_set", .member = &R::paths_per_set,
     .option = "--vpl-paths", .value = "M", .help = "light paths per VPL set; their hits are the VPLs",
     .methods = kVplMethods | kLightcuts, .bound = Bound::Closed, .lo = 1, .hi = kMaxPathsPerSet,
     .widget = Widget::Drag, .label = "paths per set"},
    {.field = "vpl_draws", .wire = "settings.vpl_draws", .member = &R::vpl_draws, .option = "--vpl-draws",
     .value = "K",
     .help = "each shading point draws K VPLs of all N x N sets from a light tree by their bound, one shadow ray "
             "each (stochastic lightcuts), instead of its set's; 0 = sets",
     .methods = kVplMethods, .bound = Bound::Closed, .lo = 0, .hi = kMaxVplDraws,
     .note = " VPLs drawn per shading point (0 = sets)", .widget = Widget::LogSlider, .label = "VPL draws"},
    {.field = "aa_samples", .wire = "settings.aa_samples", .member = &R::aa_samples, .option = "--aa", .value = "S",
     .help = "S sub-samples per pixel (1, 4, 9, ...), each shaded by 1/S of the pixel's light paths "
             "(anti-aliasing by VPL groups); needs --vpl-paths >= S",
     .methods = kVplMethods, .bound = Bound::Square, .lo = 1, .hi = kMaxAntialiasSamples,
     .what = "sub-samples per pixel", .widget = Widget::Squares, .label = "anti-aliasing"},
    {.field = "glossy_threshold", .wire = "settings.glossy_threshold", .member = &R::glossy_threshold,
     .option = "--glossy-threshold", .value = "A",
     .help = "GGX lobes with alpha below A gather their light with rays instead of VPL light, and those below "
             "A / 4, with caustics, pass their light on as photons; 0 = VPLs shade every glossy surface",
     .methods = kVplMethods, .bound = Bound::Closed, .lo = 0, .hi = 1, .what = "a GGX alpha",
     .note = " (0 = VPLs shade every glossy surface)", .widget = Widget::Slider, .section = Section::Lighting,
     .label = "glossy cutoff", .format = "%.2f"},
    {.field = "glossy_rays", .wire = "settings.glossy_rays", .member = &R::glossy_rays, .option = "--glossy-rays",
     .value = "K", .help = "gather rays per sub-sample of such a surface", .methods = kVplMethods,
     .bound = Bound::Closed, .lo = 1, .hi = kMaxGlossyRays, .widget = Widget::Slider, .section = Section::Lighting,
     .label = "glossy rays"},
    {.field = "clamp", .wire = "settings.clamp", .member = &R::clamp, .option = "--clamp", .value = "C",
     .help = "clamp 1/r^2 below distance C x the scene's mean chord (about a room); pass k of --spp clamps at "
             "C / (k + 1)^(1/4) of it, so passes converge; 0 = off",
     .methods = kVplMethods | kLightcuts, .bound = Bound::Closed, .lo = 0, .hi = kMaxClamp,
     .what = "a fraction of the scene's mean chord", .note = " (0 = off)", .widget = Widget::LogSlider,
     .label = "clamp", .format = "%.3f"},
    {.field = "compensation_samples", .wire = "settings.compensation_samples", .member = &R::compensation_samples,
     .option = "--compensate", .value = "N",
     .help = "bias compensation: N eye samples per pixel add back the light the clamp cut; 0 = off",
     .methods = kVplMethods, .bound = Bound::Closed, .lo = 0, .hi = kMaxCompensationSamples,
     .widget = Widget::Slider, .label = "compensation"},
    {.field = "filter", .wire = "settings.filter", .member = &R::filter,
     .help = "averages each pixel's VPL set over its similar neighbours", .methods = kIgi,
     .bound = Bound::None, .widget = Widget::Checkbox, .section = Section::Filter, .label = "discontinuity filter",
     .off_option = "--no-filter", .off_help = "skip the discontinuity buffer"},
    {.field = "filter_normal_cos", .wire = "settings.filter_normal_cos", .member = &R::filter_normal_cos,
     .option = "--filter-normal", .value = "C", .help = "neighbours need normal dot above C", .methods = kIgi,
     .bound = Bound::Closed, .lo = -1, .hi = 1, .what = "a cosine", .widget = Widget::Slider,
     .section = Section::Filter, .label = "normal match", .format = "%.2f", .shown_with = "filter"},
    {.field = "filter_depth_ratio", .wire = "settings.filter_depth_ratio", .member = &R::filter_depth_ratio,
     .option = "--filter-depth", .value = "R", .help = "neighbours need relative depth difference below R",
     .methods = kIgi, .bound = Bound::AtLeast, .lo = 0, .hi = kFloatMax, .what = "a finite number",
     .widget = Widget::Drag, .section = Section::Filter, .label = "depth match", .format = "%.3f", .speed = 0.001f,
     .shown_with = "filter"},
    {.field = "wavelet_levels", .wire = "settings.wavelet_levels", .member = &R::wavelet_levels,
     .option = "--wavelet", .value = "L",
     .help = "levels of the edge-avoiding wavelet filter after the discontinuity buffer (smooths one pass; a "
             "tile's border grows by 2^(L+1), so larger --tile costs less); 0 = off",
     .methods = kVplMethods, .bound = Bound::Closed, .lo = 0, .hi = kMaxWaveletLevels, .widget = Widget::Slider,
     .section = Section::Filter, .label = "wavelet levels"},
    {.field = "lightcuts_error", .wire = "settings.lightcuts_error", .member = &R::lightcuts_error,
     .option = "--lightcuts-error", .value = "E",
     .help = "refine a pixel's cut (over all --vpl-sets x --vpl-paths VPLs) until every cluster's error bound is "
             "below E x the pixel's total, 0 < E < 1",
     .methods = kLightcuts, .bound = Bound::Open, .lo = 0, .hi = 1, .what = "a number", .widget = Widget::LogSlider,
     .label = "error bound", .format = "%.3f"},
    {.field = "lightcuts_max_cut", .wire = "settings.lightcuts_max_cut", .member = &R::lightcuts_max_cut,
     .option = "--lightcuts-max-cut", .value = "N", .help = "at most N nodes (shadow rays) in a cut",
     .methods = kLightcuts, .bound = Bound::Closed, .lo = 1, .hi = lightcuts::kMaxCut, .widget = Widget::Drag,
     .label = "largest cut", .speed = 10.0f},
    {.field = "lightcuts_spacing", .wire = "settings.lightcuts_spacing", .member = &R::lightcuts_spacing,
     .option = "--lightcuts-spacing", .value = "S",
     .help = "reconstruction cuts: full cuts every S pixels only, the rest reconstructed; 0 = off",
     .methods = kLightcuts, .bound = Bound::Closed, .lo = 0, .hi = lightcuts::kMaxSpacing, .note = " (0 = off)",
     .widget = Widget::Slider, .label = "cut spacing"},
    {.field = "lightcuts_samples", .wire = "settings.lightcuts_samples", .member = &R::lightcuts_samples,
     .option = "--lightcuts-samples", .value = "K",
     .help = "K = 1, 4, 9 ... 64 gather points per pixel (multidimensional lightcuts); not with --lightcuts-spacing",
     .methods = kLightcuts, .bound = Bound::Square, .lo = 1, .hi = lightcuts::kMaxSamples,
     .what = "gather points per pixel", .widget = Widget::Squares, .label = "gather points"},
    {.field = "glass_branches", .wire = "settings.glass_branches", .member = &R::glass_branches,
     .option = "--glass-branches", .value = "B",
     .help = "glass seen from the camera splits into reflection and refraction at its first B - 1 surfaces, each "
             "branch filtered on its own; 1 = pick one by Fresnel",
     .methods = kVplMethods, .bound = Bound::Closed, .lo = 1, .hi = kMaxGlassBranches, .widget = Widget::Slider,
     .section = Section::Lighting, .label = "glass branches"},
    {.field = "caustics", .wire = "settings.caustics", .member = &R::caustics, .option = "--caustics",
     .help = "add caustics from a photon map (light through mirrors, glass and GGX sharper than "
             "--glossy-threshold / 4); the default where the scene has them",
     .methods = kVplMethods, .bound = Bound::None, .widget = Widget::Checkbox, .section = Section::Lighting,
     .label = "caustic photons", .off_option = "--no-caustics",
     .off_help = "no caustics, even where the scene has mirrors or glass (sharp GGX then holds VPLs)"},
    {.field = "caustic_photons", .wire = "settings.caustic_photons", .member = &R::caustic_photons,
     .option = "--caustic-photons", .value = "N", .help = "photon paths shot per frame, >= 1; implies --caustics",
     .methods = kVplMethods, .bound = Bound::Closed, .lo = 1, .hi = photons::kMaxCausticPhotons,
     .note = " photon paths per frame (leave out --caustics to turn caustics off)", .widget = Widget::Drag,
     .section = Section::Lighting, .label = "photon paths", .speed = 100.0f, .shown_with = "caustics",
     .implies = "caustics"},
    {.field = "caustic_radius", .wire = "settings.caustic_radius", .member = &R::caustic_radius,
     .option = "--caustic-radius", .value = "R",
     .help = "photon gather radius, a fraction of the scene diagonal; implies --caustics", .methods = kVplMethods,
     .bound = Bound::Closed, .lo = photons::kMinCausticRadius, .hi = photons::kMaxCausticRadius,
     .what = "a fraction of the scene diagonal", .widget = Widget::LogSlider, .section = Section::Lighting,
     .label = "photon radius", .format = "%.4f", .shown_with = "caustics", .implies = "caustics"},
    {.field = "importance_paths", .wire = "settings.importance_paths", .member = &R::importance_paths,
     .option = "--importance", .value = "N",
     .help = "start VPL light paths at lights by their estimated share of the image, from N camera paths (light "
             "importance for the view), 0 = by power",
     .methods = kVplMethods, .bound = Bound::Closed, .lo = 0, .hi = kMaxImportancePaths, .note = " (0 = off)",
     .widget = Widget::Drag, .section = Section::Lighting, .label = "importance", .speed = 100.0f},
    {.field = "importance_floor", .wire = "settings.importance_floor", .member = &R::importance_floor,
     .option = "--importance-floor", .value = "F", .help = "share of light paths still started by power, 0..1",
     .methods = kVplMethods, .bound = Bound::Closed, .lo = 0, .hi = 1, .what = "a share", .widget = Widget::Slider,
     .section = Section::Lighting, .label = "power share", .format = "%.2f", .shown_with = "importance_paths"},
    {.field = "bidir_vpls", .wire = "settings.bidir_vpls", .member = &R::bidir_vpls, .option = "--bidir",
     .value = "K|auto",
     .help = "bidirectional instant radiosity: per set, keep K of the VPLs of --vpl-paths light paths and R "
             "camera paths, by their estimated contribution; 0 = off; auto = where the view sees few of the "
             "light paths' VPLs, 2 x --vpl-paths light and camera paths and K = 2 x --vpl-paths, else off",
     .methods = kVplMethods, .bound = Bound::ClosedOrAuto, .lo = 0, .hi = kMaxBidirVpls,
     .note = " (0 = off, or auto)", .widget = Widget::AutoCount, .section = Section::Lighting,
     .label = "bidirectional"},
    {.field = "bidir_camera_paths", .wire = "settings.bidir_camera_paths", .member = &R::bidir_camera_paths,
     .option = "--bidir-camera-paths", .value = "R", .help = "with --bidir: camera paths per set, 0 = --vpl-paths",
     .methods = kVplMethods, .bound = Bound::Closed, .lo = 0, .hi = kMaxBidirPaths, .note = " (0 = --vpl-paths)",
     .widget = Widget::Drag, .section = Section::Lighting, .label = "camera paths", .shown_with = "bidir_vpls"},
    {.field = "lightcuts_block", .wire = "settings.lightcuts_block", .member = &R::lightcuts_block,
     .option = "--lightcuts-block", .value = "B",
     .help = "one cut shared by the B x B pixels of a block on one diffuse surface, 0 or 1 = a cut per pixel; "
             "plain cuts only",
     .methods = kLightcuts, .bound = Bound::Closed, .lo = 0, .hi = lightcuts::kMaxBlock,
     .note = " (0 or 1 = a cut per pixel)", .widget = Widget::Slider, .label = "block"},
    {.field = "light_guide", .wire = "settings.light_guide", .member = &R::light_guide, .option = "--light-guide",
     .help = "light paths that find the view: a sun's and the sky's paths start where pilot paths found they "
             "reach what the camera sees (a room lit through its windows), divided by that density; the default",
     .methods = kVplMethods, .bound = Bound::None, .widget = Widget::Checkbox, .section = Section::Lighting,
     .label = "paths find the view", .off_option = "--no-light-guide",
     .off_help = "start every light path where the plain rule does (uniformly over a sun's disc and the sky)"},
    {.field = "light_divisor", .wire = "settings.light_divisor", .member = &R::light_divisor,
     .option = "--light-divisor", .value = "D",
     .help = "shade light at one pixel in D x D and upsample it to every pixel along the pixels' own surfaces: "
             "camera rays, textures and edges at full resolution, light at 1/D^2 of its cost (the window's "
             "previews while the camera moves); 1 = every pixel",
     .methods = kVplMethods, .bound = Bound::Closed, .lo = 1, .hi = kMaxLightDivisor,
     .what = "pixels a side of a light sample"},
});

}  // namespace

std::span<const Setting> settings_table() { return kSettings; }

const Setting* setting_of_field(const std::string& field) {
  for (const Setting& s : kSettings)
    if (field == s.field) return &s;
  return nullptr;
}

const Setting* setting_of_option(const std::string& option) {
  for (const Setting& s : kSettings)
    if (!option.empty() && (option == s.option || option == s.off_option)) return &s;
  return nullptr;
}

std::string methods_text(Methods methods, const char* separator) {
  if (methods == kAllMethods) return "";
  std::string text;
  for (MethodKind m : {MethodKind::PathTracer, MethodKind::InstantRadiosity, MethodKind::Igi, MethodKind::Lightcuts})
    if (reads(methods, m)) text += (text.empty() ? "" : separator) + std::string(method_name(m));
  return text;
}

}  // namespace igi
