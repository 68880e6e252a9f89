#include "display/settings_panel.h"

#include <algorithm>
#include <array>
#include <cstring>
#include <type_traits>
#include <utility>

#include <imgui.h>

#include "lightcuts/lightcuts_settings.h"
#include "methods/clamp.h"
#include "methods/memory_check.h"
#include "methods/subpixel.h"
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
  const int gather_side = std::clamp(subpixel_side(s.lightcuts_samples), 1, 8);  // 0: not a square
  s.lightcuts_samples = gather_side * gather_side;
  s.importance_paths = std::clamp(s.importance_paths, 0, kMaxImportancePaths);
  s.importance_floor = std::clamp(s.importance_floor, 0.0f, 1.0f);
  s.bidir_vpls = std::clamp(s.bidir_vpls, 0, kMaxBidirVpls);
  s.bidir_camera_paths = std::clamp(s.bidir_camera_paths, 0, kMaxBidirPaths);
  s.glass_branches = std::clamp(s.glass_branches, 1, kMaxGlassBranches);
  s.caustic_photons = std::clamp(s.caustic_photons, 1, 1 << 22);
  s.caustic_radius = std::clamp(s.caustic_radius, photons::kMinCausticRadius, photons::kMaxCausticRadius);
  return s;
}

std::optional<std::string> panel_settings_error(const RenderSettings& s) {
  if (auto error = settings_error(s)) return error;
  if (s.method == MethodKind::Lightcuts)
    if (std::string e = lightcuts::settings_error(s); !e.empty()) return e;
  if (s.caustics) {
    if (s.method != MethodKind::InstantRadiosity && s.method != MethodKind::Igi)
      return "caustics: only the ir and igi methods add caustic photons";
    if (std::string e = photons::settings_error(s); !e.empty()) return e;
  }
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

void SettingsPanel::draw() {
  RenderSettings s = editing_;
  ImGui::SliderFloat("exposure", &exposure_, 1.0f / 64, 64.0f, "%.3g", ImGuiSliderFlags_Logarithmic | kBound);
  draw_method(s);
  if (vpl_method(s.method)) {
    draw_vpls(s);
    draw_filter(s);
  }
  draw_extras(s);
  if (std::memcmp(&s, &editing_, sizeof s) != 0) commit(s);
  if (!error_.empty()) ImGui::TextColored(ImVec4(1.0f, 0.4f, 0.3f, 1.0f), "not sent: %s", error_.c_str());
}

void SettingsPanel::draw_method(RenderSettings& s) {
  if (ImGui::BeginCombo("method", method_name(s.method))) {
    for (MethodKind m : kMethods)
      if (ImGui::Selectable(method_name(m), m == s.method)) s.method = m;
    ImGui::EndCombo();
  }
  if (s.method == MethodKind::PathTracer) {
    ImGui::SliderInt("path depth (0 = RR)", &s.path_depth, 0, 64, "%d", kBound);
    return;
  }
  ImGui::SliderInt("light depth (0 = RR)", &s.light_depth, 0, 64, "%d", kBound);
  ImGui::SliderInt("specular depth", &s.specular_depth, 0, 64, "%d", kBound);
}

void SettingsPanel::draw_vpls(RenderSettings& s) {
  ImGui::SliderInt("VPL sets N (N x N)", &s.interleave, 1, kMaxInterleave, "%d", kBound);
  ImGui::DragInt("VPL paths per set", &s.paths_per_set, 1.0f, 1, kPanelMaxPaths, "%d", kBound);
  int side = std::max(1, int(subpixel_side(s.aa_samples)));
  if (ImGui::SliderInt("anti-aliasing s (s x s)", &side, 1, 8, "%d", kBound)) s.aa_samples = side * side;
  ImGui::SliderFloat("clamp (0 = off)", &s.clamp, 0.0f, kMaxClamp, "%.3f", kBound | ImGuiSliderFlags_Logarithmic);
  ImGui::SliderInt("compensation samples", &s.compensation_samples, 0, kMaxCompensationSamples, "%d", kBound);
  ImGui::SliderFloat("glossy threshold", &s.glossy_threshold, 0.0f, 1.0f, "%.2f", kBound);
  ImGui::SliderInt("glossy rays", &s.glossy_rays, 1, kMaxGlossyRays, "%d", kBound);
  ImGui::SliderInt("glass branches", &s.glass_branches, 1, kMaxGlassBranches, "%d", kBound);
}

void SettingsPanel::draw_filter(RenderSettings& s) {
  if (s.method != MethodKind::Igi && s.method != MethodKind::InstantRadiosity) return;
  if (s.method == MethodKind::Igi) {
    ImGui::Checkbox("discontinuity filter", &s.filter);
    if (s.filter) {
      ImGui::SliderFloat("filter normal cos", &s.filter_normal_cos, -1.0f, 1.0f, "%.2f", kBound);
      ImGui::SliderFloat("filter depth ratio", &s.filter_depth_ratio, 0.0f, 1.0f, "%.3f", kBound);
    }
  }
  ImGui::SliderInt("wavelet levels (0 = off)", &s.wavelet_levels, 0, kMaxWaveletLevels, "%d", kBound);
}

void SettingsPanel::draw_extras(RenderSettings& s) {
  if (s.method == MethodKind::Lightcuts) {
    ImGui::SliderFloat("lightcuts error", &s.lightcuts_error, 0.001f, 0.5f, "%.3f", ImGuiSliderFlags_Logarithmic | kBound);
    ImGui::DragInt("lightcuts max cut", &s.lightcuts_max_cut, 10.0f, 1, lightcuts::kMaxCut, "%d", kBound);
    ImGui::SliderInt("reconstruction spacing (0 = off)", &s.lightcuts_spacing, 0, lightcuts::kMaxSpacing, "%d", kBound);
    int side = std::max(1, int(subpixel_side(s.lightcuts_samples)));
    if (ImGui::SliderInt("gather points s (s x s)", &side, 1, 8, "%d", kBound)) s.lightcuts_samples = side * side;
  }
  if (s.method == MethodKind::InstantRadiosity || s.method == MethodKind::Igi) {
    ImGui::DragInt("importance paths (0 = off)", &s.importance_paths, 100.0f, 0, kMaxImportancePaths, "%d", kBound);
    if (s.importance_paths > 0)
      ImGui::SliderFloat("importance floor", &s.importance_floor, 0.0f, 1.0f, "%.2f", kBound);
    ImGui::DragInt("bidir VPLs kept (0 = off)", &s.bidir_vpls, 1.0f, 0, kMaxBidirVpls, "%d", kBound);
    if (s.bidir_vpls > 0)
      ImGui::DragInt("bidir camera paths (0 = M)", &s.bidir_camera_paths, 1.0f, 0, kMaxBidirPaths, "%d", kBound);
    ImGui::Checkbox("caustic photons", &s.caustics);
    if (s.caustics) {
      ImGui::DragInt("photon paths", &s.caustic_photons, 100.0f, 1, 1 << 22, "%d", kBound);
      ImGui::SliderFloat("photon radius", &s.caustic_radius, photons::kMinCausticRadius, photons::kMaxCausticRadius,
                         "%.4f", ImGuiSliderFlags_Logarithmic | kBound);
    }
  }
}

}  // namespace igi
