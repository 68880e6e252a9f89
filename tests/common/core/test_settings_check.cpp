// The one check of RenderSettings (common/core/settings.h) and the table it
// reads (common/core/settings_table.h): each kind of bound, the rules between
// fields, and the table's own consistency.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <map>
#include <set>
#include <variant>

#include "core/settings.h"
#include "core/settings_table.h"

namespace igi {
namespace {

// The check's error for `s` edited by `edit`: "field: message", or "" when it passes.
template <class Edit>
std::string error_of(Edit edit) {
  RenderSettings s;
  edit(s);
  const auto e = check_settings(s);
  return e ? e->field + ": " + e->message : "";
}

TEST(SettingsCheck, TheDefaultsPass) { EXPECT_EQ(error_of([](RenderSettings&) {}), ""); }

TEST(SettingsCheck, EachKindOfBoundNamesTheFieldTheOptionAndTheRange) {
  EXPECT_EQ(error_of([](auto& s) { s.interleave = 0; }), "interleave: --vpl-sets: expected 1..16, got 0");
  EXPECT_EQ(error_of([](auto& s) { s.path_depth = -1; }),
            "path_depth: --path-depth: expected 0..1024 (0 = unbounded), got -1");
  EXPECT_EQ(error_of([](auto& s) { s.glossy_threshold = 2.0f; }),
            "glossy_threshold: --glossy-threshold: expected a GGX alpha in [0, 1] (0 = VPLs shade every glossy "
            "surface), got 2");
  EXPECT_EQ(error_of([](auto& s) { s.lightcuts_error = 1.0f; }),
            "lightcuts_error: --lightcuts-error: expected a number in (0, 1), got 1");
  EXPECT_EQ(error_of([](auto& s) { s.filter_depth_ratio = std::numeric_limits<float>::infinity(); }),
            "filter_depth_ratio: --filter-depth: expected a finite number >= 0, got inf");
  EXPECT_EQ(error_of([](auto& s) { s.aa_samples = 8; }),
            "aa_samples: --aa: expected a square number of sub-samples per pixel (1, 4, 9, ..., 64), got 8");
  EXPECT_EQ(error_of([](auto& s) { s.method = MethodKind(7); }),
            "method: --method: expected pt, ir, igi or lightcuts (0..3), got 7");
  EXPECT_EQ(error_of([](auto& s) { s.bidir_vpls = kBidirAuto; }), "") << "auto is no count, and passes";
  EXPECT_EQ(error_of([](auto& s) { s.bidir_vpls = -2; }),
            "bidir_vpls: --bidir: expected 0..65536 (0 = off, or auto), got -2");
}

TEST(SettingsCheck, NoNumberTakesNaN) {
  for (const Setting& row : settings_table()) {
    auto* member = std::get_if<float RenderSettings::*>(&row.member);
    if (!member) continue;
    RenderSettings s;
    s.*(*member) = std::nanf("");
    const auto e = check_settings(s);
    ASSERT_TRUE(e) << row.field << " took NaN";
    EXPECT_EQ(e->field, row.field);
  }
}

TEST(SettingsCheck, FieldsThatDoNotFitTogetherAreRefused) {
  EXPECT_EQ(error_of([](auto& s) { s.aa_samples = 16, s.paths_per_set = 8; }),
            "aa_samples: --aa 16 needs --vpl-paths >= 16 (each sub-sample takes its own group of the set's light "
            "paths), got 8");
  EXPECT_EQ(error_of([](auto& s) { s.method = MethodKind::PathTracer, s.caustics = true; }),
            "caustics: --caustics: only the ir and igi methods add caustic photons (pt finds caustics by itself), "
            "got --method pt");
  EXPECT_EQ(error_of([](auto& s) { s.method = MethodKind::Lightcuts, s.bidir_vpls = 8; }),
            "bidir_vpls: --bidir: only for --method ir or igi");
  EXPECT_EQ(error_of([](auto& s) { s.method = MethodKind::Lightcuts, s.lightcuts_spacing = 4, s.lightcuts_samples = 4; }),
            "lightcuts_spacing: --lightcuts-spacing and --lightcuts-samples cannot be combined: reconstruction cuts "
            "interpolate one gather point per pixel");
  EXPECT_EQ(error_of([](auto& s) { s.bidir_vpls = 2; }),
            "bidir_vpls: --bidir 2 with --aa 4: each sub-sample's group needs a VPL of its own, so keep at least 4");
  EXPECT_EQ(error_of([](auto& s) { s.bidir_vpls = 8, s.paths_per_set = 5000; }),
            "paths_per_set: --bidir needs --vpl-paths <= 4096 (every candidate is tested against every camera "
            "path), got 5000");
}

// A row a field, named as the wire names it, each option once, each member
// once: the table cannot list a field twice or two fields under one name.
TEST(SettingsTable, EveryRowIsItsOwnFieldAndOption) {
  std::set<std::string> fields, options;
  std::map<size_t, size_t> members;  // offset -> size
  for (const Setting& row : settings_table()) {
    EXPECT_TRUE(fields.insert(row.field).second) << row.field;
    EXPECT_EQ(std::string(row.wire), "settings." + std::string(row.field));
    for (const char* option : {row.option, row.off_option})
      if (*option) EXPECT_TRUE(options.insert(option).second) << option;
    EXPECT_TRUE(*row.option || *row.off_option) << row.field << " has no option";
    EXPECT_NE(row.methods, 0) << row.field << " is read by no method";
    EXPECT_EQ(setting_of_field(row.field), &row);
    const RenderSettings s;
    std::visit(
        [&](auto member) {
          const size_t offset = size_t(reinterpret_cast<const char*>(&(s.*member)) - reinterpret_cast<const char*>(&s));
          EXPECT_TRUE(members.emplace(offset, sizeof(s.*member)).second) << row.field << " shares its member";
        },
        row.member);
  }
  // Every member of RenderSettings has a row: between the rows' members
  // there is no gap a member could fill, only padding (under 4 bytes).
  size_t end = 0;
  for (const auto& [offset, size] : members) {
    EXPECT_LT(offset - end, alignof(int)) << "a RenderSettings member without a row at byte " << end;
    end = offset + size;
  }
  EXPECT_LT(sizeof(RenderSettings) - end, alignof(int)) << "a RenderSettings member without a row at the end";
  EXPECT_EQ(setting_of_option("--no-caustics"), setting_of_field("caustics"));
  EXPECT_EQ(setting_of_option(""), nullptr);
}

}  // namespace
}  // namespace igi
