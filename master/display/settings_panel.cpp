#include "display/settings_panel.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <type_traits>
#include <utility>
#include <variant>

#include <imgui.h>

#include "core/settings_table.h"
#include "image/exposure_check.h"
#include "methods/memory_check.h"

namespace igi {
namespace {

// Changes are found by comparing bytes: copies of a plain struct carry its padding along.
static_assert(std::is_trivially_copyable_v<RenderSettings>);
constexpr std::array<MethodKind, 4> kMethods{MethodKind::PathTracer, MethodKind::InstantRadiosity, MethodKind::Igi,
                                             MethodKind::Lightcuts};

// A typed (ctrl+click) value is held to the widget's range, which is the row's (core/settings_table.h).
constexpr ImGuiSliderFlags kBound = ImGuiSliderFlags_AlwaysClamp;
constexpr ImGuiSliderFlags kLog = ImGuiSliderFlags_Logarithmic;

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
void tip(const Setting& row) { tip(*row.option ? row.option : row.off_option, row.help); }

// A square count s x s up to `largest_count` (1, 4, ... 64) as a list of counts,
// the command line's unit; a count that is not a square is shown as it is.
void square_count(const char* label, int& count, int largest_count) {
  const int largest = int(std::sqrt(double(largest_count)));
  const std::string shown = std::to_string(count);
  if (ImGui::BeginCombo(label, shown.c_str())) {
    for (int side = 1; side <= largest; ++side)
      if (ImGui::Selectable(std::to_string(side * side).c_str(), side * side == count)) count = side * side;
    ImGui::EndCombo();
  }
}

// ImGui writes a value only when the user moves the widget, so a value
// outside what a slider shows stays as it came.
void widget(const Setting& row, RenderSettings& s, MethodKind RenderSettings::*member) {
  if (ImGui::BeginCombo(row.label, method_name(s.*member))) {
    for (MethodKind m : kMethods)
      if (ImGui::Selectable(method_name(m), m == s.*member)) s = with_method(s, m);
    ImGui::EndCombo();
  }
  tip(row);
}

void widget(const Setting& row, RenderSettings& s, bool RenderSettings::*member) {
  ImGui::Checkbox(row.label, &(s.*member));
  tip(row);
}

void widget(const Setting& row, RenderSettings& s, int RenderSettings::*member) {
  int& v = s.*member;
  const int lo = int(row.lo), hi = int(row.hi);
  switch (row.widget) {
    case Widget::Squares: square_count(row.label, v, hi); break;
    case Widget::Drag: ImGui::DragInt(row.label, &v, row.speed, lo, hi, "%d", kBound | kLog); break;
    case Widget::AutoCount: {  // auto, or a count dragged
      bool by_view = v == kBidirAuto;
      const std::string label = std::string(row.label) + " by view";
      if (ImGui::Checkbox(label.c_str(), &by_view)) v = by_view ? kBidirAuto : 0;
      tip((std::string(row.option) + " auto").c_str(), row.help);
      if (by_view) return;
      ImGui::DragInt(row.label, &v, row.speed, lo, hi, "%d", kBound | kLog);
      break;
    }
    default:
      ImGui::SliderInt(row.label, &v, lo, hi, "%d", kBound | (row.widget == Widget::LogSlider ? kLog : 0));
  }
  tip(row);
}

void widget(const Setting& row, RenderSettings& s, float RenderSettings::*member) {
  float& v = s.*member;
  if (row.widget == Widget::Drag)  // any finite ratio: no slider spans [0, FLT_MAX]
    ImGui::DragFloat(row.label, &v, row.speed, float(row.lo), float(row.hi), row.format, kBound);
  else
    ImGui::SliderFloat(row.label, &v, float(row.lo), float(row.hi), row.format,
                       kBound | (row.widget == Widget::LogSlider ? kLog : 0));
  tip(row);
}

// The method reads it, and the switch or count it is shown with is on.
bool shown(const Setting& row, const RenderSettings& s) {
  if (row.widget == Widget::None || !reads(row.methods, s.method)) return false;
  const Setting* with = *row.shown_with ? setting_of_field(row.shown_with) : nullptr;
  if (!with) return true;
  return std::visit(
      [&](auto member) {
        if constexpr (std::is_same_v<std::remove_cvref_t<decltype(s.*member)>, MethodKind>) return true;
        else return s.*member > 0;
      },
      with->member);
}

bool any_shown(Section section, MethodKind m) {
  for (const Setting& row : settings_table())
    if (row.section == section && row.widget != Widget::None && reads(row.methods, m)) return true;
  return false;
}

}  // namespace

void SettingsPanel::draw() {
  RenderSettings s = editing_;
  constexpr std::pair<Section, const char*> kSections[] = {
      {Section::Quality, "quality"}, {Section::Filter, "filter"}, {Section::Lighting, "lighting"}};
  for (const auto& [section, name] : kSections) {
    if (section != Section::Quality && !any_shown(section, s.method)) continue;
    if (!ImGui::CollapsingHeader(name, section == Section::Quality ? ImGuiTreeNodeFlags_DefaultOpen : 0)) continue;
    if (section == Section::Quality) draw_tone();
    for (const Setting& row : settings_table())
      if (row.section == section && shown(row, s))
        std::visit([&](auto member) { widget(row, s, member); }, row.member);
  }
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

}  // namespace igi
