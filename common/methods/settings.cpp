#include "methods/settings.h"

#include <cmath>

#include "lightcuts/lightcuts_settings.h"
#include "methods/clamp.h"
#include "methods/subpixel.h"
#include "photons/caustic_settings.h"

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

namespace {

std::optional<std::string> out_of_range(const char* option, int value, int lo, int hi, const char* what = "") {
  if (value >= lo && value <= hi) return std::nullopt;
  return std::string(option) + ": expected " + std::to_string(lo) + ".." + std::to_string(hi) + what + ", got " +
         std::to_string(value);
}

}  // namespace

std::optional<std::string> importance_settings_error(const RenderSettings& s) {
  if (auto e = out_of_range("--importance", s.importance_paths, 0, kMaxImportancePaths, " (0 = off)")) return e;
  if (!(s.importance_floor >= 0.0f && s.importance_floor <= 1.0f))
    return "--importance-floor: expected a share in [0, 1], got " + std::to_string(s.importance_floor);
  if (auto e = out_of_range("--bidir", s.bidir_vpls, 0, kMaxBidirVpls, " (0 = off)")) return e;
  if (auto e = out_of_range("--bidir-camera-paths", s.bidir_camera_paths, 0, kMaxBidirPaths, " (0 = --vpl-paths)"))
    return e;
  const bool vpl_method = s.method == MethodKind::InstantRadiosity || s.method == MethodKind::Igi;
  if (!vpl_method && s.importance_paths > 0) return std::string("--importance: only for --method ir or igi");
  if (!vpl_method && s.bidir_vpls > 0) return std::string("--bidir: only for --method ir or igi");
  if (s.bidir_vpls == 0) return std::nullopt;
  if (s.paths_per_set > kMaxBidirPaths)
    return "--bidir needs --vpl-paths <= " + std::to_string(kMaxBidirPaths) +
           " (every candidate is tested against every camera path), got " + std::to_string(s.paths_per_set);
  if (s.bidir_vpls < s.aa_samples)
    return "--bidir " + std::to_string(s.bidir_vpls) + " with --aa " + std::to_string(s.aa_samples) +
           ": each sub-sample's group needs a VPL of its own, so keep at least " + std::to_string(s.aa_samples);
  return std::nullopt;
}

std::optional<std::string> settings_error(const RenderSettings& s) {
  const char* unbounded = " (0 = unbounded)";
  if (auto e = out_of_range("--path-depth", s.path_depth, 0, kMaxDepth, unbounded)) return e;
  if (auto e = out_of_range("--light-depth", s.light_depth, 0, kMaxDepth, unbounded)) return e;
  if (auto e = out_of_range("--specular-depth", s.specular_depth, 0, kMaxDepth, unbounded)) return e;
  if (auto e = out_of_range("--vpl-sets", s.interleave, 1, kMaxInterleave)) return e;
  if (auto e = out_of_range("--vpl-paths", s.paths_per_set, 1, kMaxPathsPerSet)) return e;
  if (auto e = out_of_range("--compensate", s.compensation_samples, 0, kMaxCompensationSamples)) return e;
  if (auto e = out_of_range("--glossy-rays", s.glossy_rays, 1, kMaxGlossyRays)) return e;
  if (subpixel_side(s.aa_samples) == 0 || s.aa_samples > kMaxAntialiasSamples)
    return "--aa: expected a square number of sub-samples per pixel (1, 4, 9, ..., " +
           std::to_string(kMaxAntialiasSamples) + "), got " + std::to_string(s.aa_samples);
  if (s.paths_per_set < s.aa_samples)
    return "--aa " + std::to_string(s.aa_samples) + " needs --vpl-paths >= " + std::to_string(s.aa_samples) +
           " (each sub-sample takes its own group of the set's light paths), got " + std::to_string(s.paths_per_set);
  if (!(s.glossy_threshold >= 0.0f && s.glossy_threshold <= 1.0f))
    return "--glossy-threshold: expected a GGX alpha in [0, 1] (0 = VPLs shade every glossy surface), got " +
           std::to_string(s.glossy_threshold);
  if (!(s.clamp >= 0.0f && s.clamp <= kMaxClamp))
    return "--clamp: expected a fraction of the scene's mean chord in [0, " + std::to_string(int(kMaxClamp)) +
           "] (0 = off), got " + std::to_string(s.clamp);
  if (!(s.filter_normal_cos >= -1.0f && s.filter_normal_cos <= 1.0f))
    return "--filter-normal: expected a cosine in [-1, 1], got " + std::to_string(s.filter_normal_cos);
  if (!(s.filter_depth_ratio >= 0.0f) || !std::isfinite(s.filter_depth_ratio))
    return "--filter-depth: expected a finite number >= 0, got " + std::to_string(s.filter_depth_ratio);
  if (auto e = out_of_range("--wavelet", s.wavelet_levels, 0, kMaxWaveletLevels)) return e;
  if (auto e = out_of_range("--glass-branches", s.glass_branches, 1, kMaxGlassBranches)) return e;
  if (std::string e = lightcuts::settings_error(s); !e.empty()) return e;
  if (std::string e = photons::settings_error(s); !e.empty()) return e;
  return importance_settings_error(s);
}

}  // namespace igi
