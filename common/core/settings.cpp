#include "core/settings.h"

#include <cmath>
#include <cstdio>

#include "core/clamp.h"
#include "core/subpixel.h"

namespace igi {

const char* method_name(MethodKind kind) {
  switch (kind) {
    case MethodKind::PathTracer: return "pt";
    case MethodKind::InstantRadiosity: return "ir";
    case MethodKind::Igi: return "igi";
    case MethodKind::Lightcuts: return "lightcuts";
  }
  return "unknown";
}

std::optional<MethodKind> parse_method(const std::string& name) {
  for (MethodKind k : {MethodKind::PathTracer, MethodKind::InstantRadiosity, MethodKind::Igi, MethodKind::Lightcuts})
    if (name == method_name(k)) return k;
  return std::nullopt;
}

// ---- The one check of RenderSettings. Each rule names the field (as the wire
// format does) and the option (as igi-render's command line does).
namespace {

using Check = std::optional<SettingsError>;

std::string text(double v) {
  char out[32];
  std::snprintf(out, sizeof out, "%g", v);
  return out;
}

Check wrong(const char* field, std::string message) { return SettingsError{field, std::move(message)}; }

Check integer(const char* field, const char* option, int v, Range<int> range, const char* note = "") {
  if (v >= range.lo && v <= range.hi) return std::nullopt;
  return wrong(field, std::string(option) + ": expected " + std::to_string(range.lo) + ".." + std::to_string(range.hi) + note +
                          ", got " + std::to_string(v));
}

// lo <= v <= hi, which NaN fails; `what` says what the number is.
Check closed(const char* field, const char* option, float v, Range<float> range, const char* what,
             const char* note = "") {
  if (v >= range.lo && v <= range.hi) return std::nullopt;
  return wrong(field, std::string(option) + ": expected " + what + " in [" + text(range.lo) + ", " + text(range.hi) + "]" +
                          note + ", got " + text(v));
}

Check check_paths(const RenderSettings& s) {
  const char* unbounded = " (0 = unbounded)";
  if (uint8_t(s.method) > uint8_t(MethodKind::Lightcuts))
    return wrong("method", "--method: expected pt, ir, igi or lightcuts (0..3), got " + std::to_string(int(s.method)));
  if (auto e = integer("path_depth", "--path-depth", s.path_depth, kLimits.path_depth, unbounded)) return e;
  if (auto e = integer("light_depth", "--light-depth", s.light_depth, kLimits.light_depth, unbounded)) return e;
  if (auto e = integer("specular_depth", "--specular-depth", s.specular_depth, kLimits.specular_depth, unbounded)) return e;
  if (auto e = integer("interleave", "--vpl-sets", s.interleave, kLimits.interleave)) return e;
  if (auto e = integer("paths_per_set", "--vpl-paths", s.paths_per_set, kLimits.paths_per_set)) return e;
  if (auto e = integer("vpl_draws", "--vpl-draws", s.vpl_draws, kLimits.vpl_draws, " VPLs drawn per shading point (0 = sets)"))
    return e;
  if (subpixel_side(s.aa_samples) == 0 || s.aa_samples > kLimits.aa_samples.hi)
    return wrong("aa_samples", "--aa: expected a square number of sub-samples per pixel (1, 4, 9, ..., " +
                                   std::to_string(kLimits.aa_samples.hi) + "), got " + std::to_string(s.aa_samples));
  if (s.paths_per_set < s.aa_samples)
    return wrong("aa_samples", "--aa " + std::to_string(s.aa_samples) + " needs --vpl-paths >= " +
                                   std::to_string(s.aa_samples) +
                                   " (each sub-sample takes its own group of the set's light paths), got " +
                                   std::to_string(s.paths_per_set));
  if (auto e = closed("glossy_threshold", "--glossy-threshold", s.glossy_threshold, kLimits.glossy_threshold,
                      "a GGX alpha",
                      " (0 = VPLs shade every glossy surface)"))
    return e;
  if (auto e = integer("glossy_rays", "--glossy-rays", s.glossy_rays, kLimits.glossy_rays)) return e;
  if (auto e = closed("clamp", "--clamp", s.clamp, kLimits.clamp, "a fraction of the scene's mean chord", " (0 = off)"))
    return e;
  return integer("compensation_samples", "--compensate", s.compensation_samples, kLimits.compensation_samples);
}

Check check_filters(const RenderSettings& s) {
  if (auto e = closed("filter_normal_cos", "--filter-normal", s.filter_normal_cos, kLimits.filter_normal_cos, "a cosine")) return e;
  if (!(s.filter_depth_ratio >= kLimits.filter_depth_ratio.lo && s.filter_depth_ratio <= kLimits.filter_depth_ratio.hi))
    return wrong("filter_depth_ratio", "--filter-depth: expected a finite number >= 0, got " + text(s.filter_depth_ratio));
  if (auto e = integer("wavelet_levels", "--wavelet", s.wavelet_levels, kLimits.wavelet_levels)) return e;
  return integer("glass_branches", "--glass-branches", s.glass_branches, kLimits.glass_branches);
}

Check check_lightcuts(const RenderSettings& s) {
  if (!(s.lightcuts_error > kLimits.lightcuts_error.lo && s.lightcuts_error < kLimits.lightcuts_error.hi))
    return wrong("lightcuts_error", "--lightcuts-error: expected a number in (" + text(kLimits.lightcuts_error.lo) + ", " +
                                        text(kLimits.lightcuts_error.hi) + "), got " + text(s.lightcuts_error));
  if (auto e = integer("lightcuts_max_cut", "--lightcuts-max-cut", s.lightcuts_max_cut, kLimits.lightcuts_max_cut))
    return e;
  if (auto e = integer("lightcuts_spacing", "--lightcuts-spacing", s.lightcuts_spacing, kLimits.lightcuts_spacing,
                       " (0 = off)"))
    return e;
  if (auto e = integer("lightcuts_block", "--lightcuts-block", s.lightcuts_block, kLimits.lightcuts_block,
                       " (0 or 1 = a cut per pixel)"))
    return e;
  if (subpixel_side(s.lightcuts_samples) == 0 || s.lightcuts_samples > kLimits.lightcuts_samples.hi)
    return wrong("lightcuts_samples", "--lightcuts-samples: expected a square number of gather points per pixel "
                                      "(1, 4, 9, ..., " + std::to_string(kLimits.lightcuts_samples.hi) + "), got " +
                                      std::to_string(s.lightcuts_samples));
  // Only lightcuts uses both (the sample sweep in the tests sets them on other methods too).
  if (s.method == MethodKind::Lightcuts && s.lightcuts_spacing > 1 && s.lightcuts_samples > 1)
    return wrong("lightcuts_spacing", "--lightcuts-spacing and --lightcuts-samples cannot be combined: "
                                      "reconstruction cuts interpolate one gather point per pixel");
  return std::nullopt;
}

Check check_caustics(const RenderSettings& s) {
  if (auto e = integer("caustic_photons", "--caustic-photons", s.caustic_photons, kLimits.caustic_photons,
                       " photon paths per frame (leave out --caustics to turn caustics off)"))
    return e;
  if (auto e = closed("caustic_radius", "--caustic-radius", s.caustic_radius, kLimits.caustic_radius,
                      "a fraction of the scene diagonal"))
    return e;
  const bool vpl_method = s.method == MethodKind::InstantRadiosity || s.method == MethodKind::Igi;
  if (s.caustics && !vpl_method)
    return wrong("caustics", "--caustics: only the ir and igi methods add caustic photons (pt finds caustics by "
                             "itself), got --method " + std::string(method_name(s.method)));
  return std::nullopt;
}

Check check_importance(const RenderSettings& s) {
  const char* off = " (0 = off)";
  if (auto e = integer("importance_paths", "--importance", s.importance_paths, kLimits.importance_paths, off)) return e;
  if (auto e = closed("importance_floor", "--importance-floor", s.importance_floor, kLimits.importance_floor, "a share")) return e;
  if (s.bidir_vpls != kBidirAuto)
    if (auto e = integer("bidir_vpls", "--bidir", s.bidir_vpls, kLimits.bidir_vpls, " (0 = off, or auto)")) return e;
  if (auto e = integer("bidir_camera_paths", "--bidir-camera-paths", s.bidir_camera_paths, kLimits.bidir_camera_paths,
                       " (0 = --vpl-paths)"))
    return e;
  const bool vpl_method = s.method == MethodKind::InstantRadiosity || s.method == MethodKind::Igi;
  if (!vpl_method && s.bidir_vpls > 0) return wrong("bidir_vpls", "--bidir: only for --method ir or igi");
  if (s.bidir_vpls <= 0) return std::nullopt;  // off, or auto (which keeps within these limits)
  if (s.paths_per_set > kMaxBidirPaths)
    return wrong("paths_per_set", "--bidir needs --vpl-paths <= " + std::to_string(kMaxBidirPaths) +
                                      " (every candidate is tested against every camera path), got " +
                                      std::to_string(s.paths_per_set));
  if (s.bidir_vpls < s.aa_samples)
    return wrong("bidir_vpls", "--bidir " + std::to_string(s.bidir_vpls) + " with --aa " +
                                   std::to_string(s.aa_samples) + ": each sub-sample's group needs a VPL of its "
                                   "own, so keep at least " + std::to_string(s.aa_samples));
  return std::nullopt;
}

}  // namespace

std::optional<SettingsError> check_settings(const RenderSettings& s) {
  for (auto group : {check_paths, check_filters, check_lightcuts, check_caustics, check_importance})
    if (auto error = group(s)) return error;
  return std::nullopt;
}

std::optional<std::string> settings_error(const RenderSettings& s) {
  if (auto error = check_settings(s)) return error->message;
  return std::nullopt;
}

}  // namespace igi
