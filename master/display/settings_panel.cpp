#include "display/settings_panel.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <type_traits>
#include <utility>

#include <imgui.h>

#include "image/exposure_check.h"
#include "methods/memory_check.h"

namespace igi {
namespace {

// Changes are found by comparing bytes: copies of a plain struct carry its padding along.
static_assert(std::is_trivially_copyable_v<RenderSettings>);
// A typed (ctrl+click) value is held to the widget's range, which is the check's (kLimits).
constexpr ImGuiSliderFlags kBound = ImGuiSliderFlags_AlwaysClamp;
constexpr ImGuiSliderFlags kLog = ImGuiSliderFlags_Logarithmic;
constexpr std::array<MethodKind, 4> kMethods{MethodKind::PathTracer, MethodKind::InstantRadiosity, MethodKind::Igi,
                                             MethodKind::Lightcuts};

bool vpl_method(MethodKind m) { return m == MethodKind::InstantRadiosity || m == MethodKind::Igi || m == MethodKind::Lightcuts; }

// Widgets over a range of kLimits (core/settings.h): the panel offers what the
// check accepts, no more and no less. ImGui writes a value only when the user
// moves the widget, so a value outside what a slider shows stays as it came.
bool slider(const char* label, int& v, Range<int> r, ImGuiSliderFlags flags = 0) {
  return ImGui::SliderInt(label, &v, r.lo, r.hi, "%d", kBound | flags);
}
bool slider(const char* label, float& v, Range<float> r, const char* format, ImGuiSliderFlags flags = 0) {
  return ImGui::SliderFloat(label, &v, r.lo, r.hi, format, kBound | flags);
}
// Wide ranges (paths, photons, cut sizes: up to 2^26): dragged, logarithmically.
bool drag(const char* label, int& v, Range<int> r, float speed) {
  return ImGui::DragInt(label, &v, speed, r.lo, r.hi, "%d", kBound | kLog);
}

}  // namespace

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

SettingsPanel::SettingsPanel(const RenderSettings& settings, const ToneMapping& tone)
    : committed_(settings), editing_(settings), tone_(tone) {}

void SettingsPanel::next_view() {
  tone_.view = kViewTransforms[(size_t(tone_.view) + 1) % kViewTransforms.size()];
}

bool SettingsPanel::commit(const RenderSettings& edited) {
  editing_ = edited;
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

// A square count s x s in `range` (1, 4, ... 64) as a list of counts, the
// command line's unit; a count that is not a square is shown as it is.
void square_count(const char* label, int& count, Range<int> range, const char* option, const char* what) {
  const int largest = int(std::sqrt(double(range.hi)));
  const std::string shown = std::to_string(count);
  if (ImGui::BeginCombo(label, shown.c_str())) {
    for (int side = 1; side <= largest; ++side)
      if (ImGui::Selectable(std::to_string(side * side).c_str(), side * side == count)) count = side * side;
    ImGui::EndCombo();
  }
  tip(option, what);
}

}  // namespace

void SettingsPanel::draw() {
  RenderSettings s = editing_;
  if (ImGui::CollapsingHeader("quality", ImGuiTreeNodeFlags_DefaultOpen)) {
    draw_tone();
    draw_method(s);
  }
  if (vpl_method(s.method) && ImGui::CollapsingHeader("filter")) draw_filter(s);
  if (s.method != MethodKind::PathTracer && ImGui::CollapsingHeader("lighting")) draw_lighting(s);
  if (std::memcmp(&s, &editing_, sizeof s) != 0) commit(s);
  if (!error_.empty()) ImGui::TextColored(ImVec4(1.0f, 0.4f, 0.3f, 1.0f), "not sent: %s", error_.c_str());
}

// Exposure in stops, the meter's button and the view: the display's own, not sent.
void SettingsPanel::draw_tone() {
  float stops = std::log2(tone_.exposure);
  if (ImGui::DragFloat("exposure", &stops, 0.02f, -kExposureStops, kExposureStops, "%+.2f EV", kBound))
    tone_.exposure = std::exp2(stops);
  tip("--ev, --exposure", "display brightness in stops (+1 doubles it); not sent: the workers' colours stay linear");
  ImGui::SameLine();
  if (ImGui::SmallButton("auto")) meter_requested_ = true;
  tip("--exposure auto, key M", "meter this image: its log-average luminance to middle grey");
  std::string views;
  for (ViewTransform v : kViewTransforms) views += std::string(view_name(v)) + '\0';
  int view = int(tone_.view);
  ImGui::Combo("view (V)", &view, views.c_str());
  tip("--view", "standard: clipped at white; neutral: Khronos PBR Neutral; agx: AgX, highlights roll off");
  tone_.view = ViewTransform(view);
}

void SettingsPanel::draw_method(RenderSettings& s) {
  if (ImGui::BeginCombo("method", method_name(s.method))) {
    for (MethodKind m : kMethods)
      if (ImGui::Selectable(method_name(m), m == s.method)) s = with_method(s, m);
    ImGui::EndCombo();
  }
  tip("--method", "pt: the path-traced reference; ir, igi: virtual point lights; lightcuts: VPL clusters");
  if (s.method == MethodKind::PathTracer) {
    slider("path depth", s.path_depth, kLimits.path_depth, kLog);
    tip("--path-depth", "longest path in bounces, 0 = unbounded (Russian roulette)");
    return;
  }
  drag("paths per set", s.paths_per_set, kLimits.paths_per_set, 1.0f);
  tip("--vpl-paths", "light paths traced for each VPL set; their hits are the VPLs");
  slider("VPL sets (NxN)", s.interleave, kLimits.interleave);
  tip("--vpl-sets", "N x N interleaved VPL sets: each pixel of an N x N block takes its own");
  if (s.method == MethodKind::Lightcuts) return draw_lightcuts(s);
  slider("VPL draws", s.vpl_draws, kLimits.vpl_draws, kLog);
  tip("--vpl-draws", "VPLs of all sets each point draws from a light tree (stochastic lightcuts); 0 = its set's");
  square_count("anti-aliasing", s.aa_samples, kLimits.aa_samples, "--aa", "sub-samples per pixel, each shaded by its share of the light paths");
  slider("clamp", s.clamp, kLimits.clamp, "%.3f", kLog);
  tip("--clamp", "clamps VPL light closer than this share of the scene's mean chord; 0 = off");
  slider("compensation", s.compensation_samples, kLimits.compensation_samples);
  tip("--compensate", "eye samples per pixel that return the light the clamp removed; 0 = off");
}

void SettingsPanel::draw_lightcuts(RenderSettings& s) {
  slider("clamp", s.clamp, kLimits.clamp, "%.3f", kLog);
  tip("--clamp", "clamps VPL light closer than this share of the scene's mean chord; 0 = off");
  slider("error bound", s.lightcuts_error, kLimits.lightcuts_error, "%.3f", kLog);
  tip("--lightcuts-error", "refine until each cluster's error bound is below this share of the pixel");
  drag("largest cut", s.lightcuts_max_cut, kLimits.lightcuts_max_cut, 10.0f);
  tip("--lightcuts-max-cut", "at most this many clusters (shadow rays) in a pixel's cut");
  slider("cut spacing", s.lightcuts_spacing, kLimits.lightcuts_spacing);
  tip("--lightcuts-spacing", "full cuts every S pixels only, the rest reconstructed; 0 = off");
  slider("block", s.lightcuts_block, kLimits.lightcuts_block);
  tip("--lightcuts-block", "one cut for the B x B pixels of a block on one diffuse surface; 0 or 1 = a cut per pixel");
  square_count("gather points", s.lightcuts_samples, kLimits.lightcuts_samples, "--lightcuts-samples", "gather points per pixel");
}

void SettingsPanel::draw_filter(RenderSettings& s) {
  if (s.method != MethodKind::Igi && s.method != MethodKind::InstantRadiosity)
    return ImGui::TextUnformatted("(lightcuts: no filter)");
  if (s.method == MethodKind::Igi) {
    ImGui::Checkbox("discontinuity filter", &s.filter);
    tip("--no-filter", "averages each pixel's VPL sets over similar neighbours");
    if (s.filter) {
      slider("normal match", s.filter_normal_cos, kLimits.filter_normal_cos, "%.2f");
      tip("--filter-normal", "neighbours need a normal dot product above this");
      // Any finite ratio: dragged, as no slider spans [0, FLT_MAX].
      ImGui::DragFloat("depth match", &s.filter_depth_ratio, 0.001f, kLimits.filter_depth_ratio.lo,
                       kLimits.filter_depth_ratio.hi, "%.3f", kBound);
      tip("--filter-depth", "neighbours need a relative depth difference below this");
    }
  }
  slider("wavelet levels", s.wavelet_levels, kLimits.wavelet_levels);
  tip("--wavelet", "edge-avoiding wavelet filter after the discontinuity buffer; 0 = off");
}

void SettingsPanel::draw_lighting(RenderSettings& s) {
  slider("light depth", s.light_depth, kLimits.light_depth, kLog);
  tip("--light-depth", "longest VPL light path, 0 = unbounded (Russian roulette)");
  slider("mirror depth", s.specular_depth, kLimits.specular_depth, kLog);
  tip("--specular-depth", "mirrors and glass followed from the camera, 0 = unbounded");
  if (s.method == MethodKind::Lightcuts) return;
  slider("glossy cutoff", s.glossy_threshold, kLimits.glossy_threshold, "%.2f");
  tip("--glossy-threshold", "surfaces smoother than this roughness gather their lobe with rays");
  slider("glossy rays", s.glossy_rays, kLimits.glossy_rays);
  tip("--glossy-rays", "gather rays per sub-sample of such a surface");
  slider("glass branches", s.glass_branches, kLimits.glass_branches);
  tip("--glass-branches", "glass seen from the camera splits into reflection and refraction this deep");
  drag("importance", s.importance_paths, kLimits.importance_paths, 100.0f);
  tip("--importance", "light importance: camera paths that estimate each light's share of the view; 0 = lights by power");
  if (s.importance_paths > 0) {
    slider("power share", s.importance_floor, kLimits.importance_floor, "%.2f");
    tip("--importance-floor", "share of light paths still started by power");
  }
  bool bidir_by_view = s.bidir_vpls == kBidirAuto;
  if (ImGui::Checkbox("bidirectional by view", &bidir_by_view)) s.bidir_vpls = bidir_by_view ? kBidirAuto : 0;
  tip("--bidir auto", "bidirectional instant radiosity where the view sees few of the light paths' VPLs (2 x light and camera paths)");
  if (!bidir_by_view) {
    drag("bidirectional", s.bidir_vpls, kLimits.bidir_vpls, 1.0f);
    tip("--bidir", "bidirectional instant radiosity: per set, keep this many VPLs of light and camera paths by contribution; 0 = off");
  }
  if (s.bidir_vpls > 0) {
    drag("camera paths", s.bidir_camera_paths, kLimits.bidir_camera_paths, 1.0f);
    tip("--bidir-camera-paths", "camera paths per set, 0 = as many as light paths");
  }
  ImGui::Checkbox("caustic photons", &s.caustics);
  tip("--caustics", "adds caustics from a photon map (light through mirrors, glass and sharp GGX)");
  if (s.caustics) {
    drag("photon paths", s.caustic_photons, kLimits.caustic_photons, 100.0f);
    tip("--caustic-photons", "photon paths shot per frame");
    slider("photon radius", s.caustic_radius, kLimits.caustic_radius, "%.4f", kLog);
    tip("--caustic-radius", "photon gather radius, a share of the scene diagonal");
  }
}

}  // namespace igi
