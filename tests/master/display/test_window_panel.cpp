// The window's panel without a window (issue 18): widgets offer the ranges the
// settings check accepts and rewrite nothing, a set that does not fit together is not sent, the panel draws in a
// headless ImGui context, and camera bookmarks round-trip and name bad fields.
#include <cstring>
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>
#include <imgui.h>

#include "view/camera_bookmark.h"
#include "display/cluster_panel.h"
#include "display/settings_panel.h"
#include "core/settings_table.h"
#include "display/tile_overlay.h"
#include "display/panel_layout.h"
#include "image/metrics.h"
#include "scene/load_scene.h"
#include "support/image_compare.h"
#include "support/process.h"

namespace igi {
namespace {

// The panel's widgets span the rows' ranges (core/settings_table.h; issue 48:
// ranges written once): each range's ends pass check_settings() and a step
// past either end fails it, naming the field, so the check and the panel
// cannot drift apart. Every row with a range, so a new setting is covered.
template <class T>
void expect_range(const Setting& row, T RenderSettings::*member) {
  RenderSettings s;
  s.method = MethodKind::Igi;
  s.paths_per_set = 64;  // room for every anti-aliasing count
  s.aa_samples = 1;
  const bool open = row.bound == Bound::Open;
  for (T v : {T(row.lo), T(row.hi)}) {
    s.*member = v;
    const auto error = check_settings(s);
    if (open) {
      ASSERT_TRUE(error) << row.field << " = " << v << ": an open range's end";
    } else {
      EXPECT_FALSE(error) << row.field << " = " << v << ": " << error->message;
    }
  }
  // One step past each end: the next integer, or the next float.
  const auto past = [](T v, bool up) {
    if constexpr (std::is_integral_v<T>) return T(up ? v + 1 : v - 1);
    else return std::nextafter(v, up ? std::numeric_limits<T>::infinity() : -std::numeric_limits<T>::infinity());
  };
  for (T v : {past(T(row.lo), false), past(T(row.hi), true)}) {
    if (row.bound == Bound::ClosedOrAuto && v == T(kBidirAuto)) continue;  // auto is not below the range
    s.*member = v;
    const auto error = check_settings(s);
    ASSERT_TRUE(error) << row.field << " = " << v << " passed the check";
    EXPECT_EQ(error->field, row.field);
  }
}

TEST(WindowPanel, EveryWidgetsRangeIsTheRangeTheSettingsCheckAccepts) {
  int ranges = 0;
  for (const Setting& row : settings_table()) {
    if (row.bound != Bound::Closed && row.bound != Bound::Open && row.bound != Bound::AtLeast &&
        row.bound != Bound::ClosedOrAuto)
      continue;
    ++ranges;
    if (auto* member = std::get_if<int RenderSettings::*>(&row.member)) expect_range(row, *member);
    if (auto* member = std::get_if<float RenderSettings::*>(&row.member)) expect_range(row, *member);
  }
  EXPECT_EQ(ranges, 25) << "every count and number but the square counts";
}

TEST(WindowPanel, CommitSendsValidChangesOnceAndHoldsBackSetsThatDoNotFit) {
  RenderSettings start;
  SettingsPanel panel(start, ToneMapping{});
  EXPECT_FALSE(panel.commit(start)) << "no change";
  EXPECT_FALSE(panel.take_change());
  RenderSettings pt_caustics = start;
  pt_caustics.method = MethodKind::PathTracer;
  pt_caustics.caustics = true;
  EXPECT_FALSE(panel.commit(pt_caustics));
  EXPECT_NE(panel.error().find("caustic"), std::string::npos) << panel.error();
  EXPECT_EQ(panel.settings().method, start.method) << "an invalid set is not sent";
  RenderSettings fewer = start;
  fewer.paths_per_set = start.aa_samples - 1;  // each sub-sample needs a path of its own
  EXPECT_FALSE(panel.commit(fewer)) << "not rewritten to fit: held back, with the reason";
  EXPECT_NE(panel.error().find("--vpl-paths"), std::string::npos) << panel.error();
  EXPECT_EQ(panel.settings().paths_per_set, start.paths_per_set);
  fewer.aa_samples = 1;
  EXPECT_TRUE(panel.commit(fewer));
  EXPECT_TRUE(panel.error().empty());
  EXPECT_EQ(panel.settings().paths_per_set, start.aa_samples - 1);
  EXPECT_EQ(panel.settings().aa_samples, 1);
  EXPECT_TRUE(panel.take_change());
  EXPECT_FALSE(panel.take_change()) << "taken once";
}

// Picking pt or lightcuts in a scene with glass (caustics on by default) or
// with bidirectional IR drops what they refuse instead of holding the pick
// back; ir and igi keep them.
TEST(WindowPanel, PickingAMethodDropsWhatItRefuses) {
  RenderSettings glass;
  glass.caustics = true;
  glass.bidir_vpls = 8;
  ASSERT_FALSE(panel_settings_error(glass));
  for (MethodKind m : {MethodKind::PathTracer, MethodKind::Lightcuts}) {
    RenderSettings s = glass;
    s.method = m;
    EXPECT_TRUE(panel_settings_error(s)) << method_name(m) << " refuses caustics and --bidir";
    const RenderSettings picked = with_method(glass, m);
    EXPECT_EQ(picked.method, m);
    EXPECT_EQ(picked.bidir_vpls, kBidirAuto) << "back to the default, which " << method_name(m) << " ignores";
    EXPECT_FALSE(panel_settings_error(picked)) << *panel_settings_error(picked);
    SettingsPanel panel(glass, ToneMapping{});
    EXPECT_TRUE(panel.commit(picked)) << method_name(m);
  }
  const RenderSettings ir = with_method(glass, MethodKind::InstantRadiosity);
  EXPECT_TRUE(ir.caustics);
  EXPECT_EQ(ir.bidir_vpls, 8);
}

// The window's V and the panel's combo go through the views in order, back to the first; the exposure is the
// meter's when it says so. Neither is sent: the settings stay as they were.
TEST(WindowPanel, TheViewsCycleAndTheExposureIsTheDisplaysOwn) {
  SettingsPanel panel(RenderSettings{}, ToneMapping{2.0f, ViewTransform::Standard});
  for (ViewTransform want : {ViewTransform::Neutral, ViewTransform::Agx, ViewTransform::Standard}) {
    panel.next_view();
    EXPECT_EQ(panel.tone().view, want);
  }
  panel.set_exposure(8.0f);
  EXPECT_EQ(panel.tone().exposure, 8.0f);
  EXPECT_FALSE(panel.take_change()) << "the display's own: nothing to send";
  EXPECT_FALSE(panel.take_meter_request());
}

// The widgets themselves, in an ImGui context with no window: every method's page draws.
TEST(WindowPanel, EveryMethodsPageDrawsHeadless) {
  ImGui::CreateContext();
  ImGuiIO& io = ImGui::GetIO();
  io.IniFilename = nullptr;
  io.DisplaySize = ImVec2(640, 480);
  unsigned char* pixels;
  int w, h;
  io.Fonts->GetTexDataAsRGBA32(&pixels, &w, &h);
  for (MethodKind m : {MethodKind::PathTracer, MethodKind::InstantRadiosity, MethodKind::Igi, MethodKind::Lightcuts}) {
    RenderSettings s;
    s.method = m;
    // Values past what the panel's sliders once showed (depth 64, 2^16 paths): shown as given, never rewritten.
    s.path_depth = 500;
    s.paths_per_set = 1 << 18;
    ASSERT_FALSE(check_settings(s));
    SettingsPanel panel(s, ToneMapping{2.0f});
    for (int frame = 0; frame < 2; ++frame) {  // ImGui sizes a new window in its first frame and draws it in the second
      ImGui::NewFrame();
      ImGui::Begin("panel");
      panel.draw();
      ImGui::End();
      ImGui::Render();
    }
    EXPECT_GT(ImGui::GetDrawData()->TotalVtxCount, 100) << method_name(m);
    EXPECT_FALSE(panel.take_change()) << "drawing alone changes nothing";
    EXPECT_EQ(std::memcmp(&panel.settings(), &s, sizeof s), 0) << method_name(m) << ": a value was rewritten";
  }
  ImGui::DestroyContext();
}

TEST(WindowPanel, WorkerColoursDifferAcrossThePalette) {
  for (uint32_t i = 0; i < kPaletteSize; ++i)
    for (uint32_t j = i + 1; j < kPaletteSize; ++j) {
      const auto a = worker_colour(i), b = worker_colour(j);
      int most = 0;
      for (int c = 0; c < 3; ++c) most = std::max(most, std::abs(int(a[c]) - int(b[c])));
      EXPECT_GE(most, 60) << i << " and " << j;
    }
  EXPECT_EQ(worker_colour(3), worker_colour(3 + kPaletteSize));
}

TEST(WindowPanel, WorkerLoadIsTilesPerSecondAndTheShareOfItsThreadsBusy) {
  FrameRecord f;
  f.seconds = 0.5;
  f.workers["worker-3"] = {40, 1.5, 0, 0};  // 40 tiles, 1.5 s of rendering over 4 threads in 0.5 s
  const WorkerLoad load = worker_load(PeerView{"worker-3", 3, 4, 0.0, 0.0}, f);
  EXPECT_DOUBLE_EQ(load.tiles_per_second, 80.0);
  EXPECT_DOUBLE_EQ(load.busy_share, 0.75);
  EXPECT_EQ(worker_load(PeerView{"worker-4", 4, 4, 0.0, 0.0}, f).tiles_per_second, 0.0) << "no tiles in this frame";
}

// A third of the image's width, 220 to 420 pixels, and every column of the
// cluster table inside it, in the font size the layout picks.
TEST(WindowPanel, TheClusterTableFitsThePanelAtEverySize) {
  ImGui::CreateContext();
  ImGuiIO& io = ImGui::GetIO();
  io.IniFilename = nullptr;
  load_panel_fonts();
  unsigned char* pixels;
  int w, h;
  io.Fonts->GetTexDataAsRGBA32(&pixels, &w, &h);
  std::vector<PeerView> peers;
  FrameRecord f;
  f.seconds = 0.04;
  for (uint32_t n : {8u, 9u, 10u, 11u}) {  // two-digit names, three-digit rates: the widest rows
    peers.push_back(PeerView{"worker-" + std::to_string(n), n, 128, 10.25, 0.52});
    f.workers["worker-" + std::to_string(n)] = {40, 0.04 * 128, 0, 0};
  }
  for (const glm::vec2 size : {glm::vec2(640, 480), glm::vec2(680, 510), glm::vec2(720, 540), glm::vec2(800, 600),
                               glm::vec2(1024, 768), glm::vec2(1920, 1080), glm::vec2(320, 240)}) {
    io.DisplaySize = ImVec2(size.x, size.y);
    const PanelLayout layout = panel_layout(int(size.x));
    EXPECT_EQ(layout.width, std::clamp(size.x / 3.0f, 220.0f, 420.0f));
    const PanelFont font = panel_font(layout.font_pixels);
    // The table's needs in a window of any width, and the room the panel gives it.
    auto measure = [&](const char* name, float width, float& room) {  // the table's need; the window's room
      float table = 0.0f;
      for (int frame = 0; frame < 2; ++frame) {  // ImGui sizes a new window in its first frame
        ImGui::NewFrame();
        ImGui::SetNextWindowSizeConstraints(ImVec2(width, 0), ImVec2(width, size.y));
        if (font.font) ImGui::PushFont(font.font);
        ImGui::Begin(name, nullptr, ImGuiWindowFlags_AlwaysAutoResize);
        ImGui::SetWindowFontScale(font.scale);
        room = ImGui::GetContentRegionAvail().x;
        table = draw_cluster_panel(peers, f);
        ImGui::End();
        if (font.font) ImGui::PopFont();
        ImGui::Render();
      }
      return table;
    };
    float room = 0.0f, wide_room = 0.0f;
    const float table = measure("panel", layout.width, room);
    EXPECT_EQ(measure("wide", 2000.0f, wide_room), table) << "what the table needs is its content's, not the window's";
    std::printf("%.0fx%.0f: panel %.0f px, %.0f-pixel text, table %.1f of %.1f px\n", size.x, size.y, layout.width,
                layout.font_pixels, table, room);
    EXPECT_GT(table, 0.0f);
    EXPECT_LE(table, room) << size.x << "x" << size.y << ": the table's last columns are cut off";
  }
  ImGui::DestroyContext();
}

// The image beside the panel, never under it: whole, its aspect kept, at its
// own size where the window has room (the window is widened by the panel's
// column where the screen allows), smaller where it has not.
TEST(WindowPanel, TheImageShowsWholeBesideThePanel) {
  const float panel = panel_layout(640).width;
  EXPECT_EQ(panel, 220.0f);
  EXPECT_EQ(window_width(640, panel, true, 1920), 860) << "room on the screen: wider by the panel";
  EXPECT_EQ(window_width(640, panel, true, 640), 640) << "no room: the image's width";
  EXPECT_EQ(window_width(640, panel, false, 1920), 640) << "--panel off";
  const Viewport wide = image_viewport(860, 480, 640, 480, panel);
  EXPECT_EQ(wide.x, 220.0f);
  EXPECT_EQ(wide.y, 0.0f);
  EXPECT_EQ(wide.width, 640.0f);
  EXPECT_EQ(wide.height, 480.0f);
  EXPECT_EQ(wide.scale, 1.0f);
  const Viewport narrow = image_viewport(640, 480, 640, 480, panel);  // 420 pixels beside the panel
  EXPECT_GE(narrow.x, panel);
  EXPECT_LE(narrow.x + narrow.width, 640.0f);
  EXPECT_NEAR(narrow.width / narrow.height, 640.0f / 480.0f, 0.01f) << "the aspect kept";
  EXPECT_EQ(narrow.width, 420.0f);
  const Viewport hidden = image_viewport(860, 480, 640, 480, 0.0f);  // Tab: centred at its own size
  EXPECT_EQ(hidden.x, 110.0f);
  EXPECT_EQ(hidden.width, 640.0f);
  const float big = panel_layout(1920).width;
  EXPECT_EQ(big, 420.0f);
  const Viewport hd = image_viewport(float(window_width(1920, big, true, 1920)), 1080, 1920, 1080, big);
  EXPECT_EQ(hd.x, 420.0f);
  EXPECT_EQ(hd.width, 1500.0f);
  EXPECT_NEAR(hd.height, 1500.0f * 1080.0f / 1920.0f, 0.5f);
  EXPECT_TRUE(panel_opens(640, 480, 640, 480, panel));
  EXPECT_TRUE(panel_opens(380, 120, 160, 120, panel)) << "a small image in a window widened for the panel";
  EXPECT_FALSE(panel_opens(160, 120, 160, 120, panel)) << "no room beside a small image";
}

TEST(CameraBookmark, RoundTripsAndNamesTheBadField) {
  const std::string path = test::output_path("bookmark.json");
  Camera c{{1, 2, 3}, glm::normalize(glm::vec3(0.2f, -0.1f, -1)), {0, 1, 0}, 0.7f};
  write_camera_file(path, c);
  const Camera r = read_camera_file(path);
  EXPECT_LT(glm::length(r.position - c.position), 1e-5f);
  EXPECT_LT(glm::length(r.forward - c.forward), 1e-5f);
  EXPECT_NEAR(r.vfov, c.vfov, 1e-5f);
  auto error_of = [&](const std::string& text) {
    std::ofstream(path) << text;
    try {
      read_camera_file(path);
    } catch (const std::runtime_error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(error_of("{\"position\": [0, 0], \"forward\": [0, 0, -1], \"up\": [0, 1, 0], \"vfov_degrees\": 40}")
                .find("\"position\""), std::string::npos);
  EXPECT_NE(error_of("{\"position\": [0, 0, 0], \"forward\": [0, 1, 0], \"up\": [0, 2, 0], \"vfov_degrees\": 40}")
                .find("\"up\""), std::string::npos);
  EXPECT_NE(error_of("{\"position\": [0, 0, 0], \"forward\": [0, 0, -1], \"up\": [0, 1, 0], \"vfov_degrees\": 0}")
                .find("vfov_degrees"), std::string::npos);
  EXPECT_NE(error_of("not json").find("not JSON"), std::string::npos);
  EXPECT_NE(error_of("{}").find(path), std::string::npos) << "the file is named";
}

// igi-master --camera FILE (headless here): the scene's own camera from a file
// gives the scene's image; another camera another image; a bad file stops the run naming it.
TEST(CameraBookmark, HeadlessMasterStartsFromTheFile) {
  const std::string same = test::output_path("camera-same.json"), moved = test::output_path("camera-moved.json");
  const Camera home = load_scene("cornell").camera_or_auto();
  write_camera_file(same, home);
  Camera other = home;
  other.position += 0.3f * glm::normalize(home.forward);
  write_camera_file(moved, other);
  auto render = [](const std::string& extra, const std::string& out) {
    return test::run(std::string(IGI_MASTER_BINARY) + " --workers 1 --worker-threads 1 --scene cornell --method igi" +
                     " --vpl-paths 4 --size 48x36 --frames 1 --quiet -o " + test::output_path(out) + " " + extra, 60);
  };
  ASSERT_EQ(render("", "camera-none.png").exit_code, 0);
  ASSERT_EQ(render("--camera " + same, "camera-same.png").exit_code, 0);
  ASSERT_EQ(render("--camera " + moved, "camera-moved.png").exit_code, 0);
  const Image none = read_image(test::output_path("camera-none.png"));
  EXPECT_LT(max_abs_error(read_image(test::output_path("camera-same.png")), none), 0.01f);
  EXPECT_GT(max_abs_error(read_image(test::output_path("camera-moved.png")), none), 0.1f);
  const std::string bad = test::output_path("camera-bad.json");
  std::ofstream(bad) << "{\"position\": [0, 0, 0]}";
  const test::RunResult r = render("--camera " + bad, "camera-bad.png");
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.output.find(bad + ": \"forward\""), std::string::npos) << r.output;
}

// igi-render --camera FILE: the same file igi-master takes; a bad one stops it before the scene loads.
TEST(CameraBookmark, IgiRenderStartsFromTheFile) {
  const std::string moved = test::output_path("render-camera-moved.json");
  Camera other = load_scene("cornell").camera_or_auto();
  other.position += 0.3f * glm::normalize(other.forward);
  write_camera_file(moved, other);
  auto render = [](const std::string& extra, const std::string& out) {
    return test::run(std::string(IGI_RENDER_BINARY) + " --scene cornell --vpl-paths 4 --aa 1 --size 48x36 --quiet -o " +
                     test::output_path(out) + " " + extra, 60);
  };
  ASSERT_EQ(render("", "render-camera-none.exr").exit_code, 0);
  ASSERT_EQ(render("--camera " + moved, "render-camera-moved.exr").exit_code, 0);
  EXPECT_GT(max_abs_error(read_image(test::output_path("render-camera-moved.exr")),
                          read_image(test::output_path("render-camera-none.exr"))), 0.1f);
  const std::string bad = test::output_path("render-camera-bad.json");
  std::ofstream(bad) << "{\"position\": [0, 0, 0]}";
  const test::RunResult r = render("--scene no-such-scene.glb --camera " + bad, "render-camera-bad.exr");
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.output.find(bad + ": \"forward\""), std::string::npos) << "the camera file, before the scene\n" << r.output;
}

}  // namespace
}  // namespace igi
