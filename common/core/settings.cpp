#include "core/settings.h"

#include <cmath>
#include <cstdio>
#include <type_traits>
#include <variant>

#include "core/clamp.h"
#include "core/settings_table.h"
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

// ---- The one check of RenderSettings: each field within its row's bound
// (core/settings_table.h), then what must hold between fields. Each rule names
// the field (as the wire format does) and the option (as igi-render's command line does).
namespace {

using Check = std::optional<SettingsError>;

std::string text(double v) {
  char out[32];
  std::snprintf(out, sizeof out, "%g", v);
  return out;
}

Check wrong(const char* field, std::string message) { return SettingsError{field, std::move(message)}; }

// A count's or a number's bound, as its row says (core/settings_table.h).
Check bounded(const Setting& row, double v, bool integral) {
  const std::string option = row.option;
  auto number = [&](double x) { return integral ? std::to_string(long(x)) : text(x); };
  switch (row.bound) {
    case Bound::Method:
    case Bound::None:
      return std::nullopt;
    case Bound::ClosedOrAuto:
      if (v == kBidirAuto) return std::nullopt;
      [[fallthrough]];
    case Bound::Closed:
      if (v >= row.lo && v <= row.hi) return std::nullopt;
      if (integral)
        return wrong(row.field, option + ": expected " + number(row.lo) + ".." + number(row.hi) + row.note +
                                    ", got " + number(v));
      return wrong(row.field, option + ": expected " + row.what + " in [" + text(row.lo) + ", " + text(row.hi) +
                                  "]" + row.note + ", got " + text(v));
    case Bound::Open:
      if (v > row.lo && v < row.hi) return std::nullopt;
      return wrong(row.field, option + ": expected " + row.what + " in (" + text(row.lo) + ", " + text(row.hi) +
                                  "), got " + text(v));
    case Bound::AtLeast:
      if (v >= row.lo && v <= row.hi) return std::nullopt;
      return wrong(row.field, option + ": expected " + row.what + " >= " + text(row.lo) + ", got " + text(v));
    case Bound::Square:
      if (subpixel_side(int(v)) != 0 && v <= row.hi) return std::nullopt;
      return wrong(row.field, option + ": expected a square number of " + row.what + " (1, 4, 9, ..., " +
                                  number(row.hi) + "), got " + number(v));
  }
  return std::nullopt;
}

// Every field within its row's bound, in the table's order.
Check check_bounds(const RenderSettings& s) {
  for (const Setting& row : settings_table()) {
    Check error = std::visit(
        [&](auto member) -> Check {
          using T = std::remove_cvref_t<decltype(s.*member)>;
          if constexpr (std::is_same_v<T, MethodKind>) {
            if (uint8_t(s.*member) <= uint8_t(MethodKind::Lightcuts)) return std::nullopt;
            return wrong(row.field, std::string(row.option) + ": expected pt, ir, igi or lightcuts (0..3), got " +
                                        std::to_string(int(s.*member)));
          } else if constexpr (std::is_same_v<T, bool>) {
            return std::nullopt;
          } else {
            return bounded(row, double(s.*member), std::is_integral_v<T>);
          }
        },
        row.member);
    if (error) return error;
  }
  return std::nullopt;
}

// ---- What must hold between fields.

Check check_samples(const RenderSettings& s) {
  if (s.paths_per_set < s.aa_samples)
    return wrong("aa_samples", "--aa " + std::to_string(s.aa_samples) + " needs --vpl-paths >= " +
                                   std::to_string(s.aa_samples) +
                                   " (each sub-sample takes its own group of the set's light paths), got " +
                                   std::to_string(s.paths_per_set));
  // Only lightcuts uses both (the sample sweep in the tests sets them on other methods too).
  if (s.method == MethodKind::Lightcuts && s.lightcuts_spacing > 1 && s.lightcuts_samples > 1)
    return wrong("lightcuts_spacing", "--lightcuts-spacing and --lightcuts-samples cannot be combined: "
                                      "reconstruction cuts interpolate one gather point per pixel");
  return std::nullopt;
}

Check check_vpl_methods_only(const RenderSettings& s) {
  const bool vpl_method = s.method == MethodKind::InstantRadiosity || s.method == MethodKind::Igi;
  if (s.caustics && !vpl_method)
    return wrong("caustics", "--caustics: only the ir and igi methods add caustic photons (pt finds caustics by "
                             "itself), got --method " + std::string(method_name(s.method)));
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
  for (auto group : {check_bounds, check_samples, check_vpl_methods_only})
    if (auto error = group(s)) return error;
  return std::nullopt;
}

std::optional<std::string> settings_error(const RenderSettings& s) {
  if (auto error = check_settings(s)) return error->message;
  return std::nullopt;
}

}  // namespace igi
