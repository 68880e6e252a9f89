#include "display/settings_panel.h"

#include <algorithm>
#include <array>
#include <cstring>
#include <type_traits>
#include <utility>

#include <imgui.h>

#include "core/clamp.h"
#include "core/subpixel.h"
#include "lightcuts/lightcuts_settings.h"
#include "methods/memory_check.h"
#include "photons/caustic_settings.h"

namespace igi {
namespace {

// Changes are found by comparing bytes: copies of a plain struct carry its padding along.
static_assert(std::is_trivially_copyable_v<RenderSettings>);
constexpr ImGuiSliderFlags kBound = ImGuiSliderFlags_AlwaysClamp;  // typed (ctrl+click) values too
constexpr std::array<MethodKind, 4> kMethods{MethodKind::PathTracer, MethodKind::InstantRadiosity, MethodKind::Igi,
                                             MethodKind::Lightcuts};
constexpr int kPanelMaxPaths = 1 << 16;  // per set: far past interactive, well inside the wire's bound

bool vpl_method(MethodKind m) { return m == MethodKind::InstantRadiosity || m == MethodKind::Igi || m == MethodKind::Lightcuts; }

// A square sample count, s x s with 1 <= s <= 8, at most the paths per set.
int bounded_aa(int aa, int paths) {
  int side = std::clamp(subpixel_side(aa), 1, 8);  // 0: not a square
  while (side > 1 && side * side > paths) --side;
  return side * side;
}

}  // namespace

RenderSettings bounded(RenderSettings s) {
  s.path_depth = std::clamp(s.path_depth, 0, kMaxDepth);
  s.light_depth = std::clamp(s.light_depth, 0, kMaxDepth);
  s.specular_depth = std::clamp(s.specular_depth, 0, kMaxDepth);
  s.interleave = std::clamp(s.interleave, 1, kMaxInterleave);
  s.paths_per_set = std::clamp(s.paths_per_set, 1, kPanelMaxPaths);
  s.vpl_draws = std::clamp(s.vpl_draws, 0, kMaxVplDraws);
  s.aa_samples = bounded_aa(s.aa_samples, s.paths_per_set);
  s.glossy_threshold = std::clamp(s.glossy_threshold, 0.0f, 1.0f);
  s.glossy_rays = std::clamp(s.glossy_rays, 1, kMaxGlossyRays);
  s.clamp = std::clamp(s.clamp, 0.0f, kMaxClamp);
  s.compensation_samples = std::clamp(s.compensation_samples, 0, kMaxCompensationSamples);
  s.filter_normal_cos = std::clamp(s.filter_normal_cos, -1.0f, 1.0f);
  s.filter_depth_ratio = std::clamp(s.filter_depth_ratio, 0.0f, 1.0f);
  s.wavelet_levels = std::clamp(s.wavelet_levels, 0, kMaxWaveletLevels);
  s.lightcuts_error = std::clamp(s.lightcuts_error, 0.001f, 0.5f);
  s.lightcuts_max_cut = std::clamp(s.lightcuts_max_cut, 1, lightcuts::kMaxCut);
  s.lightcuts_spacing = std::clamp(s.lightcuts_spacing, 0, lightcuts::kMaxSpacing);
  s.lightcuts_block = std::clamp(s.lightcuts_block, 0, lightcuts::kMaxBlock);
  const int gather_side = std::clamp(subpixel_side(s.lightcuts_samples), 1, 8);  // 0: not a square
  s.lightcuts_samples = gather_side * gather_side;
  s.importance_paths = std::clamp(s.importance_paths, 0, kMaxImportancePaths);
  s.importance_floor = std::clamp(s.importance_floor, 0.0f, 1.0f);
  if (s.bidir_vpls != kBidirAuto) s.bidir_vpls = std::clamp(s.bidir_vpls, 0, kMaxBidirVpls);
  s.bidir_camera_paths = std::clamp(s.bidir_camera_paths, 0, kMaxBidirPaths);
  s.glass_branches = std::clamp(s.glass_branches, 1, kMaxGlassBranches);
  s.caustic_photons = std::clamp(s.caustic_photons, 1, 1 << 22);
  s.caustic_radius = std::clamp(s.caustic_radius, photons::kMinCausticRadius, photons::kMaxCausticRadius);
  return s;
}

RenderSettings with_method(RenderSettings s, MethodKind m) {
  s.method = m;
  if (m != MethodKind::InstantRadiosity && m != MethodKind::Igi) {
    s.caustics = false;
    if (s.bidir_vpls > 0) s.bidir_vpls = kBidirAuto;  // the default, which they ignore
  }
  return s;
}

std::optional<std::string> panel_settings_error(const RenderSettings& s) {
  if (auto error = settings_error(s)) return error;
  if (std::string e = memory_error(s, machine_memory_bytes()); !e.empty()) return e;
  return std::nullopt;
}

SettingsPanel::SettingsPanel(const RenderSettings& settings, float exposure)
    : committed_(settings), editing_(settings), exposure_(exposure) {}

bool SettingsPanel::commit(const RenderSettings& edited) {
  editing_ = bounded(edited);
  if (auto error = panel_settings_error(editing_)) {
    error_ = *error;
    return false;
  }
  error_.clear();
  if (std::memcmp(&editing_, &committed_, sizeof editing_) == 0) return false;
  committed_ = editing_;
  changed_ = true;
  return true;
}

bool SettingsPanel::take_change() { return std::exchange(changed_, false); }

namespace {

// The option a widget stands for, and what it does, when the mouse rests on it.
void tip(const char* option, const char* what) {
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s\n%s", what, option);
}

// A square count s x s (1, 4, ... 64) as a list of counts, the command line's unit.
void square_count(const char* label, int& count, const char* option, const char* what) {
  static const char* kCounts[] = {"1", "4", "9", "16", "25", "36", "49", "64"};
  int side = std::clamp(int(subpixel_side(count)), 1, 8);
  if (ImGui::BeginCombo(label, kCounts[side - 1])) {
    for (int i = 1; i <= 8; ++i)
      if (ImGui::Selectable(kCounts[i - 1], i == side)) count = i * i;
    ImGui::EndCombo();
  }
  tip(option, what);
}

}  // namespace

void SettingsPanel::draw() {
  RenderSettings s = editing_;
  if (ImGui::CollapsingHeader("quality", ImGuiTreeNodeFlags_DefaultOpen)) {
    ImGui::SliderFloat("exposure", &exposure_, 1.0f / 64, 64.0f, "%.3g", ImGuiSliderFlags_Logarithmic | kBound);
    tip("--exposure", "display brightness (not sent: the workers' colours stay linear)");
    draw_method(s);
  }
  if (vpl_method(s.method) && ImGui::CollapsingHeader("filter")) draw_filter(s);
  if (s.method != MethodKind::PathTracer && ImGui::CollapsingHeader("lighting")) draw_lighting(s);
  if (std::memcmp(&s, &editing_, sizeof s) != 0) commit(s);
  if (!error_.empty()) ImGui::TextColored(ImVec4(1.0f, 0.4f, 0.3f, 1.0f), "not sent: %s", error_.c_str());
}

void SettingsPanel::draw_method(RenderSettings& s) {
  if (ImGui::BeginCombo("method", method_name(s.method))) {
    for (MethodKind m : kMethods)
      if (ImGui::Selectable(method_name(m), m == s.method)) s = with_method(s, m);
    ImGui::EndCombo();
  }
  tip("--method", "pt: the path-traced reference; ir, igi: virtual point lights; lightcuts: VPL clusters");
  if (s.method == MethodKind::PathTracer) {
    ImGui::SliderInt("path depth", &s.path_depth, 0, 64, "%d", kBound);
    tip("--path-depth", "longest path in bounces, 0 = unbounded (Russian roulette)");
    return;
  }
  ImGui::DragInt("paths per set", &s.paths_per_set, 1.0f, 1, kPanelMaxPaths, "%d", kBound);
  tip("--vpl-paths", "light paths traced for each VPL set; their hits are the VPLs");
  ImGui::SliderInt("VPL sets (NxN)", &s.interleave, 1, kMaxInterleave, "%d", kBound);
  tip("--vpl-sets", "N x N interleaved VPL sets: each pixel of an N x N block takes its own");
  if (s.method == MethodKind::Lightcuts) return draw_lightcuts(s);
  ImGui::SliderInt("VPL draws", &s.vpl_draws, 0, kMaxVplDraws, "%d", kBound | ImGuiSliderFlags_Logarithmic);
  tip("--vpl-draws", "VPLs of all sets each point draws from a light tree (stochastic lightcuts); 0 = its set's");
  square_count("anti-aliasing", s.aa_samples, "--aa", "sub-samples per pixel, each shaded by its share of the light paths");
  ImGui::SliderFloat("clamp", &s.clamp, 0.0f, kMaxClamp, "%.3f", kBound | ImGuiSliderFlags_Logarithmic);
  tip("--clamp", "clamps VPL light closer than this share of the scene's mean chord; 0 = off");
  ImGui::SliderInt("compensation", &s.compensation_samples, 0, kMaxCompensationSamples, "%d", kBound);
  tip("--compensate", "eye samples per pixel that return the light the clamp removed; 0 = off");
}

void SettingsPanel::draw_lightcuts(RenderSettings& s) {
  ImGui::SliderFloat("clamp", &s.clamp, 0.0f, kMaxClamp, "%.3f", kBound | ImGuiSliderFlags_Logarithmic);
  tip("--clamp", "clamps VPL light closer than this share of the scene's mean chord; 0 = off");
  ImGui::SliderFloat("error bound", &s.lightcuts_error, 0.001f, 0.5f, "%.3f", ImGuiSliderFlags_Logarithmic | kBound);
  tip("--lightcuts-error", "refine until each cluster's error bound is below this share of the pixel");
  ImGui::DragInt("largest cut", &s.lightcuts_max_cut, 10.0f, 1, lightcuts::kMaxCut, "%d", kBound);
  tip("--lightcuts-max-cut", "at most this many clusters (shadow rays) in a pixel's cut");
  ImGui::SliderInt("cut spacing", &s.lightcuts_spacing, 0, lightcuts::kMaxSpacing, "%d", kBound);
  tip("--lightcuts-spacing", "full cuts every S pixels only, the rest reconstructed; 0 = off");
  ImGui::SliderInt("block", &s.lightcuts_block, 0, lightcuts::kMaxBlock, "%d", kBound);
  tip("--lightcuts-block", "one cut for the B x B pixels of a block on one diffuse surface; 0 or 1 = a cut per pixel");
  square_count("gather points", s.lightcuts_samples, "--lightcuts-samples", "gather points per pixel");
}

void SettingsPanel::draw_filter(RenderSettings& s) {
  if (s.method != MethodKind::Igi && s.method != MethodKind::InstantRadiosity)
    return ImGui::TextUnformatted("(lightcuts: no filter)");
  if (s.method == MethodKind::Igi) {
    ImGui::Checkbox("discontinuity filter", &s.filter);
    tip("--no-filter", "averages each pixel's VPL sets over similar neighbours");
    if (s.filter) {
      ImGui::SliderFloat("normal match", &s.filter_normal_cos, -1.0f, 1.0f, "%.2f", kBound);
      tip("--filter-normal", "neighbours need a normal dot product above this");
      ImGui::SliderFloat("depth match", &s.filter_depth_ratio, 0.0f, 1.0f, "%.3f", kBound);
      tip("--filter-depth", "neighbours need a relative depth difference below this");
    }
  }
  ImGui::SliderInt("wavelet levels", &s.wavelet_levels, 0, kMaxWaveletLevels, "%d", kBound);
  tip("--wavelet", "edge-avoiding wavelet filter after the discontinuity buffer; 0 = off");
}

void SettingsPanel::draw_lighting(RenderSettings& s) {
  ImGui::SliderInt("light depth", &s.light_depth, 0, 64, "%d", kBound);
  tip("--light-depth", "longest VPL light path, 0 = unbounded (Russian roulette)");
  ImGui::SliderInt("mirror depth", &s.specular_depth, 0, 64, "%d", kBound);
  tip("--specular-depth", "mirrors and glass followed from the camera, 0 = unbounded");
  if (s.method == MethodKind::Lightcuts) return;
  ImGui::SliderFloat("glossy cutoff", &s.glossy_threshold, 0.0f, 1.0f, "%.2f", kBound);
  tip("--glossy-threshold", "surfaces smoother than this roughness gather their lobe with rays");
  ImGui::SliderInt("glossy rays", &s.glossy_rays, 1, kMaxGlossyRays, "%d", kBound);
  tip("--glossy-rays", "gather rays per sub-sample of such a surface");
  ImGui::SliderInt("glass branches", &s.glass_branches, 1, kMaxGlassBranches, "%d", kBound);
  tip("--glass-branches", "glass seen from the camera splits into reflection and refraction this deep");
  ImGui::DragInt("importance", &s.importance_paths, 100.0f, 0, kMaxImportancePaths, "%d", kBound);
  tip("--importance", "light importance: camera paths that estimate each light's share of the view; 0 = lights by power");
  if (s.importance_paths > 0) {
    ImGui::SliderFloat("power share", &s.importance_floor, 0.0f, 1.0f, "%.2f", kBound);
    tip("--importance-floor", "share of light paths still started by power");
  }
  bool bidir_by_view = s.bidir_vpls == kBidirAuto;
  if (ImGui::Checkbox("bidirectional by view", &bidir_by_view)) s.bidir_vpls = bidir_by_view ? kBidirAuto : 0;
  tip("--bidir auto", "bidirectional instant radiosity where the view sees few of the light paths' VPLs (2 x light and camera paths)");
  if (!bidir_by_view) {
    ImGui::DragInt("bidirectional", &s.bidir_vpls, 1.0f, 0, kMaxBidirVpls, "%d", kBound);
    tip("--bidir", "bidirectional instant radiosity: per set, keep this many VPLs of light and camera paths by contribution; 0 = off");
  }
  if (s.bidir_vpls > 0) {
    ImGui::DragInt("camera paths", &s.bidir_camera_paths, 1.0f, 0, kMaxBidirPaths, "%d", kBound);
    tip("--bidir-camera-paths", "camera paths per set, 0 = as many as light paths");
  }
  ImGui::Checkbox("caustic photons", &s.caustics);
  tip("--caustics", "adds caustics from a photon map (light through mirrors, glass and sharp GGX)");
  if (s.caustics) {
    ImGui::DragInt("photon paths", &s.caustic_photons, 100.0f, 1, 1 << 22, "%d", kBound);
    tip("--caustic-photons", "photon paths shot per frame");
    ImGui::SliderFloat("photon radius", &s.caustic_radius, photons::kMinCausticRadius, photons::kMaxCausticRadius,
                       "%.4f", ImGuiSliderFlags_Logarithmic | kBound);
    tip("--caustic-radius", "photon gather radius, a share of the scene diagonal");
  }
}

}  // namespace igi
