#pragma once
// Every field of RenderSettings, once: a row each, in the wire's order, with
// what every side needs to know of it. The one check (check_settings()), the
// codec (protocol/codec.cpp), the command lines (master/options/), the
// window's panel (master/display/settings_panel.cpp) and the options
// reference (master/options/OPTIONS.md, generated) all read these rows, so a
// setting is added in two places: its member (with its default) in
// RenderSettings, and its row here (settings_table.cpp). What must hold
// between fields (anti-aliasing samples within the paths per set, caustics
// only for ir and igi...) is check_settings()'s own code.
#include <cstdint>
#include <span>
#include <string>
#include <variant>

#include "core/settings.h"

namespace igi {

// Which methods read a setting: a mask of (1 << MethodKind).
using Methods = uint8_t;
inline constexpr Methods kPt = 1 << int(MethodKind::PathTracer), kIr = 1 << int(MethodKind::InstantRadiosity),
                         kIgi = 1 << int(MethodKind::Igi), kLightcuts = 1 << int(MethodKind::Lightcuts);
inline constexpr Methods kVplMethods = kIr | kIgi;
inline constexpr Methods kAllMethods = kPt | kIr | kIgi | kLightcuts;
inline bool reads(Methods methods, MethodKind m) { return (methods >> int(m)) & 1; }

// How check_settings() bounds a value (and how its message reads).
enum class Bound : uint8_t {
  Method,   // one of the MethodKinds
  None,     // a switch: any value
  Closed,   // lo <= v <= hi ("expected 0..1024" for a count, "expected a share in [0, 1]" for a number)
  Open,     // lo < v < hi
  AtLeast,  // a finite v >= lo
  Square,   // a square count s x s, 1 <= v <= hi
  ClosedOrAuto,  // lo <= v <= hi, or kBidirAuto (chosen by the view)
};

// How the window's panel offers it.
enum class Widget : uint8_t {
  None,       // not on the panel
  Combo,      // the method
  Checkbox,   // a switch
  Slider,     // over the range
  LogSlider,  // over the range, logarithmically
  Drag,       // wide ranges: dragged (logarithmically for counts)
  Squares,    // a square count, as a list of counts (the command line's unit)
  AutoCount,  // a count or kBidirAuto: a checkbox for auto, dragged otherwise
};
enum class Section : uint8_t { Quality, Filter, Lighting };

using SettingMember = std::variant<MethodKind RenderSettings::*, bool RenderSettings::*, int RenderSettings::*,
                                   float RenderSettings::*>;

struct Setting {
  const char* field;  // RenderSettings' member, as check_settings() names it
  const char* wire;   // its name on the wire, in a decoder's errors ("settings.<field>")
  SettingMember member;
  // The command line: the option that sets it (for a switch, that turns it
  // on; "" for none), what --help calls its value, and what it does (for
  // --help, where the methods that read it and the default are added, the
  // panel's tooltip and the options reference).
  const char* option = "";
  const char* value = "";
  const char* help = "";
  Methods methods;
  // The check: the range, what the number is ("a GGX alpha") or what is
  // counted ("gather points per pixel"), and a note after the range ("(0 = off)").
  Bound bound;
  double lo = 0.0, hi = 0.0;
  const char* what = "";
  const char* note = "";
  // The panel: its widget, section and label; a number's printf format and
  // drag speed; and the switch or count it is shown with (only while that is on).
  Widget widget = Widget::None;
  Section section = Section::Quality;
  const char* label = "";
  const char* format = "%d";
  float speed = 1.0f;
  const char* shown_with = "";
  // A switch's option that turns it off, and its help; an option that also
  // turns a switch on (--caustic-photons turns on caustics).
  const char* off_option = "";
  const char* off_help = "";
  const char* implies = "";
};

// The rows, in the wire's order (which the codec's bytes follow).
std::span<const Setting> settings_table();
// The row of a field, or of an option (its on or off option); nullptr when none.
const Setting* setting_of_field(const std::string& field);
const Setting* setting_of_option(const std::string& option);
// "ir/igi", "lightcuts", "" (every method): the methods' names as --help prefixes them.
std::string methods_text(Methods methods, const char* separator = "/");

}  // namespace igi
