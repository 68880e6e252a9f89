// The window shows what the renderer wrote: a screenshot of it under Xvfb
// equals the PNG (both are 8-bit sRGB of the same image).
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>

#include <nlohmann/json.hpp>
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "image/image.h"
#include "image/metrics.h"
#include "support/image_compare.h"
#include "support/process.h"
#include "support/sanitizers.h"
#include "support/stats_file.h"
#include "support/xvfb.h"
#include "display/tile_overlay.h"
#include "protocol/curve.h"

namespace igi {
namespace {


TEST(Window, ScreenshotUnderXvfbMatchesTheWrittenImage) {
  IGI_NEED_XVFB();
  const std::string png = test::output_path("window-render.png"), shot = test::output_path("window-shot.png");
  std::filesystem::remove(shot);
  const std::string command = std::string("xvfb-run -a -s '-screen 0 640x480x24' ") + IGI_RENDER_BINARY +
                              " --scene cornell --method igi --vpl-paths 8 --size 160x120 --quiet -o " + png +
                              " --screenshot " + shot + " >/dev/null 2>&1";
  ASSERT_EQ(std::system(command.c_str()), 0) << command;
  Image written = read_image(png), shown = read_image(shot);
  ASSERT_EQ(shown.width, 160);
  ASSERT_EQ(shown.height, 120);
  // Both decode from 8-bit sRGB; allow one step of rounding.
  EXPECT_LT(max_abs_error(shown, written), 0.01) << "window content differs from the image";
  EXPECT_GT(written.mean().x, 0.02f) << "a lit Cornell box, not a black frame";
}

}  // namespace
}  // namespace igi

namespace igi {
namespace {

TEST(Window, MasterWindowShowsTheAccumulatedFramesOfTheCluster) {
  IGI_NEED_XVFB();
  const std::string shot = test::output_path("master-window.png"), frames = test::output_path("master-prog.png");
  // A fixed exposure (the window's default meters) and the agx view: the window's table against the PNG
  // writer's function.
  const std::string common = std::string(" --workers 2 --worker-threads 1 --scene cornell --method igi --vpl-paths 8") +
                             " --size 160x120 --quiet --ev 1 --view agx";
  std::filesystem::remove(shot);
  const std::string window = std::string("timeout -s KILL 60 xvfb-run -a -s '-screen 0 640x480x24' ") + IGI_MASTER_BINARY +
                             common + " --panel off --screenshot " + shot + " --screenshot-after 4 >/dev/null 2>&1";
  ASSERT_EQ(std::system(window.c_str()), 0) << window;
  const std::string headless = std::string(IGI_MASTER_BINARY) + common + " --frames 4 --progressive -o " + frames +
                               " >/dev/null 2>&1";
  ASSERT_EQ(std::system(headless.c_str()), 0) << headless;
  // The window accumulates exactly the frames a progressive headless run writes, and shows them as it writes them.
  Image shown = read_image(shot), written = read_image(test::output_path("master-prog-0003.png"));
  EXPECT_LT(max_abs_error(shown, written), 0.01);
  const std::string standard = test::output_path("master-prog-standard.png");
  ASSERT_EQ(std::system((std::string(IGI_MASTER_BINARY) + common + " --view standard --frames 4 --progressive -o " +
                         standard + " >/dev/null 2>&1").c_str()), 0);
  EXPECT_GT(max_abs_error(shown, read_image(test::output_path("master-prog-standard-0003.png"))), 0.05)
      << "and through the view asked for";
}

// The number after `words` in `text` (NaN when absent).
double number_after(const std::string& text, const std::string& words) {
  const size_t at = text.find(words);
  return at == std::string::npos ? std::nan("") : std::atof(text.c_str() + at + words.size());
}

// The window meters the image it shows as igi-master meters the image it
// writes (--exposure auto, the window's default): the first frame (a
// progressive run's frame 0), the same pixels (floats on the wire: as half
// floats the window's exposure is 0.01 EV off), the same exposure; it says
// so once, and holds it.
TEST(Window, TheWindowMetersItsImageAsTheMasterMetersAFile) {
  IGI_NEED_XVFB();
  const std::string shot = test::output_path("master-window-auto.png"), file = test::output_path("master-auto.png");
  const std::string common = std::string(IGI_MASTER_BINARY) + " --workers 2 --worker-threads 1 --pixels float" +
                             " --scene cornell --method igi --vpl-paths 8 --size 160x120";
  std::filesystem::remove(shot);
  const test::RunResult window = test::run("timeout -s KILL 60 xvfb-run -a -s '-screen 0 640x480x24' " + common +
                                           " --panel off --screenshot " + shot + " --screenshot-after 2 2>&1");
  ASSERT_EQ(window.exit_code, 0) << window.output;
  const test::RunResult headless =
      test::run(common + " --frames 1 --progressive --exposure auto -o " + file + " 2>&1");
  ASSERT_EQ(headless.exit_code, 0) << headless.output;
  const double shown = number_after(window.output, "igi-master: exposure metered: ");
  const double written = number_after(headless.output, "igi-master: exposure metered: ");
  EXPECT_NEAR(shown, 1.77, 0.1) << window.output;  // the box's walls are dim at exposure 1
  EXPECT_EQ(shown, written) << window.output << headless.output;
  const std::string fixed = test::output_path("master-ev0.png");
  ASSERT_EQ(std::system((common + " --frames 1 --progressive --quiet --ev 0 -o " + fixed + " >/dev/null").c_str()), 0);
  EXPECT_GT(read_image(shot).mean().x, 1.5f * read_image(fixed).mean().x) << "the box metered is brighter";
}

}  // namespace
}  // namespace igi

namespace igi {
namespace {

// The master's window under Xvfb (issue 18): 160x120, 2 workers of 1 thread,
// igi with 8 paths, at exposure 1 as headless runs write files.
std::string window_run(const std::string& shot, const std::string& extra, const std::string& screen = "640x480") {
  std::filesystem::remove(shot);
  return std::string("timeout -s KILL 60 xvfb-run -a -s '-screen 0 ") + screen + "x24' " + IGI_MASTER_BINARY +
         " --workers 2 --worker-threads 1 --scene cornell --method igi --vpl-paths 8 --size 160x120 --quiet --ev 0" +
         " --screenshot " + shot + " " + extra + " >/dev/null 2>&1";
}

std::string headless_run(const std::string& output, const std::string& extra) {
  return std::string(IGI_MASTER_BINARY) + " --workers 2 --worker-threads 1 --scene cornell --method igi" +
         " --size 160x120 --quiet --progressive -o " + output + " " + extra + " >/dev/null 2>&1";
}

// Whether the image in `shot` at (x, y) is `image` at its own size.
double differing_share(const Image& shot, const Image& image, int x, int y) {
  int n = 0;
  for (int j = 0; j < image.height; ++j)
    for (int i = 0; i < image.width; ++i) n += glm::length(shot.at(x + i, y + j) - image.at(i, j)) > 0.02f;
  return double(n) / double(image.width * image.height);
}

// The panel sits in a column left of the image, never over it (issue 65):
// where the screen has room the window is widened by the column and the
// image shows whole at its own size beside it; hidden (--panel off), the
// window is the image.
TEST(Window, ThePanelSitsBesideTheImageAndHidesWithTheOption) {
  IGI_NEED_XVFB();
  const std::string shown = test::output_path("panel-shown.png"), hidden = test::output_path("panel-hidden.png");
  ASSERT_EQ(std::system(window_run(shown, "--screenshot-after 1").c_str()), 0);
  ASSERT_EQ(std::system(window_run(hidden, "--screenshot-after 1 --panel off").c_str()), 0);
  const Image with = read_image(shown), without = read_image(hidden);
  ASSERT_EQ(without.width, 160);
  ASSERT_EQ(with.width, 160 + 220) << "widened by the panel's column";
  ASSERT_EQ(with.height, 120);
  EXPECT_EQ(differing_share(with, without, 220, 0), 0.0) << "the whole image, at its own size, beside the panel";
  double panel = 0.0;
  for (int y = 0; y < 120; ++y)
    for (int x = 0; x < 220; ++x) panel += glm::length(with.at(x, y)) / (220.0 * 120.0);
  EXPECT_GT(panel, 0.02) << "the panel's column: its title bar, widgets and the frame rate";
  EXPECT_GT(without.mean().x, 0.02f) << "a lit Cornell box";
}

// At 640x480 on a screen of 640x480 the window cannot widen: the image
// shows whole beside the panel, smaller, its aspect kept, on a dark
// surround; the frame rate sits at the foot of the panel's column, the keys'
// help (F1) in the middle. On a wider screen the window widens and the image
// keeps its size.
TEST(Window, AtTheDefaultSizeTheWholeImageShowsBesideThePanel) {
  IGI_NEED_XVFB();
  auto run = [](const std::string& name, const std::string& extra, const std::string& screen) {
    const std::string shot = test::output_path(name);
    std::filesystem::remove(shot);
    const std::string command = "timeout -s KILL 60 xvfb-run -a -s '-screen 0 " + screen + "x24' " +
                                IGI_MASTER_BINARY + " --workers 2 --worker-threads 1 --vpl-paths 4 --size 640x480 " +
                                "--quiet --ev 0 --screenshot-after 1 --screenshot " + shot + " " + extra + " >/dev/null 2>&1";
    EXPECT_EQ(std::system(command.c_str()), 0) << command;
    return read_image(shot);
  };
  const Image with = run("panel-640.png", "", "640x480"), without = run("panel-640-off.png", "--panel off", "640x480"),
              help = run("panel-640-help.png", "--panel off --test-show-help", "640x480"),
              wide = run("panel-640-wide.png", "", "1280x1024");
  ASSERT_EQ(with.width, 640);
  ASSERT_EQ(without.width, 640);
  ASSERT_EQ(help.width, 640);
  ASSERT_EQ(wide.width, 860);
  // 420 x 315 beside the 220-pixel column, centred in the height: rows 82 to 396.
  const glm::vec3 surround = with.at(430, 40);
  auto region_mean = [](const Image& image, int x0, int y0, int x1, int y1) {
    glm::dvec3 sum(0.0);
    for (int y = y0; y < y1; ++y)
      for (int x = x0; x < x1; ++x) sum += glm::dvec3(image.at(x, y));
    return glm::vec3(sum / double((x1 - x0) * (y1 - y0)));
  };
  EXPECT_LT(glm::length(region_mean(with, 220, 0, 640, 80) - surround), 1e-3f) << "the surround above the image";
  EXPECT_LT(glm::length(region_mean(with, 220, 399, 640, 480) - surround), 1e-3f) << "and below it";
  const glm::vec3 scaled = region_mean(with, 220, 82, 640, 397), whole = without.mean();
  EXPECT_LT(glm::length(scaled - whole), 0.1f * glm::length(whole)) << "the whole image, smaller";
  EXPECT_GT(glm::length(with.at(300, 81) - with.at(300, 84)), 0.0f) << "the image's top edge where the aspect puts it";
  EXPECT_GT(glm::length(region_mean(with, 0, 440, 200, 480)), 0.02f) << "the frame rate, at the foot of the column";
  EXPECT_EQ(differing_share(wide, without, 220, 0), 0.0) << "a wide screen: the image at its own size";
  auto differing = [](const Image& a, const Image& b, int x0, int y0, int x1, int y1) {
    int n = 0;
    for (int y = y0; y < y1; ++y)
      for (int x = x0; x < x1; ++x) n += glm::length(a.at(x, y) - b.at(x, y)) > 0.02f;
    return double(n) / ((x1 - x0) * (y1 - y0));
  };
  EXPECT_GT(differing(help, without, 220, 200, 420, 280), 0.3) << "the keys' help, in the middle";
  EXPECT_EQ(differing(help, without, 0, 0, 40, 480), 0.0) << "the help alone leaves the left edge";
  EXPECT_GT(without.mean().x, 0.02f) << "a lit Cornell box";
}

// A change made through the panel's commit (the widgets' path) after the first
// frame reaches the running workers: the next frames are the new settings' frames.
TEST(Window, ASettingsChangeThroughThePanelReachesTheWorkers) {
  IGI_NEED_XVFB();
  const std::string shot = test::output_path("panel-edit.png");
  ASSERT_EQ(std::system(window_run(shot, "--panel off --screenshot-after 2 --test-panel-edit '--vpl-paths 4 --no-filter'")
                            .c_str()), 0);
  const std::string edited = test::output_path("panel-edit-headless.png"), old = test::output_path("panel-old.png");
  ASSERT_EQ(std::system(headless_run(edited, "--frames 2 --vpl-paths 4 --no-filter").c_str()), 0);
  ASSERT_EQ(std::system(headless_run(old, "--frames 2 --vpl-paths 8").c_str()), 0);
  const Image shown = read_image(shot);
  const Image want = read_image(test::output_path("panel-edit-headless-0001.png"));
  const Image before = read_image(test::output_path("panel-old-0001.png"));
  EXPECT_LT(max_abs_error(shown, want), 0.01) << "the window shows the edited settings' frames";
  EXPECT_GT(max_abs_error(shown, before), 0.05) << "and not the old settings' frames";
}

// Solid overlay: each tile painted in its worker's colour; counting tiles by
// colour gives the per-worker tile counts of the statistics for the frame shown.
TEST(Window, TileOverlayColoursMatchTheStatisticsTileCounts) {
  IGI_NEED_XVFB();
  const std::string shot = test::output_path("overlay.png"), stats = test::output_path("overlay-stats.json");
  std::filesystem::remove(stats);
  ASSERT_EQ(std::system(window_run(shot, "--panel off --overlay solid --screenshot-after 1 --tile 32 --stats " + stats)
                            .c_str()), 0);
  const nlohmann::json j = test::read_stats(stats);
  ASSERT_FALSE(j["frames"].empty());
  const nlohmann::json& last = j["frames"].back();
  const Image image = read_image(shot);
  std::map<int, uint64_t> by_colour;
  for (int y = 0; y < 120; y += 32)
    for (int x = 0; x < 160; x += 32) {
      const glm::vec3 c = image.at(x + 8, y + 8);
      int found = -1;
      for (uint32_t w = 0; w < kPaletteSize && found < 0; ++w) {
        const auto p = worker_colour(w);
        const glm::vec3 want(srgb_to_linear(p[0] / 255.0f), srgb_to_linear(p[1] / 255.0f), srgb_to_linear(p[2] / 255.0f));
        if (glm::length(c - want) < 0.01f) found = int(w);
      }
      ASSERT_GE(found, 0) << "tile (" << x << ", " << y << ") is in no worker's colour";
      ++by_colour[found];
    }
  uint64_t total = 0;
  for (const auto& [name, w] : last["workers"].items()) {
    const int number = std::stoi(name.substr(name.find('-') + 1));
    EXPECT_EQ(by_colour[number], w["tiles"].get<uint64_t>()) << name;
    total += w["tiles"].get<uint64_t>();
  }
  EXPECT_EQ(total, 20u) << "5 x 4 tiles of 32 in 160x120";
}

}  // namespace
}  // namespace igi

namespace igi {
namespace {

// Issue 45: a user drags the mouse for 1.5 s. While the camera moves the
// window shows preview frames as they come (the title, its status line,
// names the level and changes), and after the stop full frames come back.
TEST(Window, ADragShowsPreviewFramesAndTheStopFullOnes) {
  IGI_NEED_XVFB();
  if (std::system("command -v xdotool >/dev/null 2>&1") != 0) {
    if (test::under_ci()) FAIL() << "xdotool not installed (scripts/setup.sh installs it)";
    GTEST_SKIP() << "xdotool not installed";
  }
  const std::string command = "timeout -s KILL " + std::to_string(int(60 * test::kSlowdown)) +
                              " xvfb-run -a -s '-screen 0 640x480x24' " +
                              IGI_WINDOW_SCRIPTS_DIR + "/drag_test.sh " + std::to_string(test::kSlowdown) + " " +
                              IGI_MASTER_BINARY + " 2>&1";
  const test::RunResult r = test::run(command, int(90 * test::kSlowdown));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  std::map<std::string, std::string> titles;
  std::istringstream lines(r.output);
  for (std::string line; std::getline(lines, line);)
    if (const size_t colon = line.find(": "); colon != std::string::npos) titles[line.substr(0, colon)] = line;
  ASSERT_EQ(titles.count("before") + titles.count("drag-1") + titles.count("drag-3") + titles.count("after"), 4u)
      << r.output;
  EXPECT_NE(titles["before"].find(" full "), std::string::npos) << r.output;
  for (const char* step : {"drag-1", "drag-2", "drag-3"})
    EXPECT_NE(titles[step].find("preview"), std::string::npos) << step << " shows no preview frame\n" << r.output;
  EXPECT_NE(titles["drag-1"], titles["drag-3"]) << "no new frame in the second half of the drag\n" << r.output;
  EXPECT_NE(titles["after"].find(" full "), std::string::npos) << "no full frame after the stop\n" << r.output;
}

// F12 writes the accumulated image as EXR and PNG and says so, on the
// terminal as well as in the window (it used to say so only inside the
// panel's folded "camera and images" section); M before it meters the
// exposure the window and the PNG show.
TEST(Window, F12WritesTheImageAndSaysSo) {
  IGI_NEED_XVFB();
  if (std::system("command -v xdotool >/dev/null 2>&1") != 0) {
    if (test::under_ci()) FAIL() << "xdotool not installed (scripts/setup.sh installs it)";
    GTEST_SKIP() << "xdotool not installed";
  }
  const std::filesystem::path dir = test::output_path("f12");
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const std::string command = "timeout -s KILL " + std::to_string(int(60 * test::kSlowdown)) +
                              " xvfb-run -a -s '-screen 0 640x480x24' " + IGI_WINDOW_SCRIPTS_DIR + "/f12_test.sh " +
                              std::to_string(test::kSlowdown) + " " + IGI_MASTER_BINARY + " " + dir.string() + " 2>&1";
  const test::RunResult r = test::run(command, int(90 * test::kSlowdown));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("igi-master: exposure metered: +1."), std::string::npos) << r.output;  // -2 EV before
  EXPECT_NE(r.output.find("igi-master: saved igi-shot-0000.exr and .png ("), std::string::npos) << r.output;
  const Image shot = read_image((dir / "igi-shot-0000.exr").string());
  EXPECT_EQ(shot.width, 320);
  EXPECT_GT(shot.mean().x, 0.02f) << "the lit box";
  // The PNG at the metered exposure (x 3.4): brighter than the EXR as exposure 1 shows it (clipped at white).
  double png = 0.0, at_one = 0.0;
  const Image shown = read_image((dir / "igi-shot-0000.png").string());
  for (size_t i = 0; i < shot.pixels.size(); ++i) png += shown.pixels[i].x, at_one += std::min(shot.pixels[i].x, 1.0f);
  EXPECT_GT(png, 2.0 * at_one);
}

// Issue 62: igi-view on one machine drives igi-master --viewer-listen on
// another (here both under one Xvfb): a drag in the viewer turns the camera
// (F5 saves the viewer's camera before and after it), F12 saves the master's
// float image on the master and on the viewer's machine, and a viewer killed
// with frames in flight leaves the master rendering for the next.
TEST(Window, AViewerDrivesAMasterAndOneKilledLeavesItRendering) {
  IGI_NEED_XVFB();
  if (std::system("command -v xdotool >/dev/null 2>&1") != 0) {
    if (test::under_ci()) FAIL() << "xdotool not installed (scripts/setup.sh installs it)";
    GTEST_SKIP() << "xdotool not installed";
  }
  namespace fs = std::filesystem;
  const fs::path dir = test::output_path("viewer");
  fs::remove_all(dir);
  fs::create_directories(dir / "viewers");
  const protocol::CurveKeyPair master = protocol::make_curve_keypair(), laptop = protocol::make_curve_keypair();
  protocol::write_key_files((dir / "master").string(), master);
  protocol::write_key_files((dir / "laptop").string(), laptop);
  fs::copy_file(dir / "laptop.pub", dir / "viewers" / "laptop.pub");
  const std::string command = "timeout -s KILL " + std::to_string(int(60 * test::kSlowdown)) +
                              " xvfb-run -a -s '-screen 0 640x480x24' " + IGI_WINDOW_SCRIPTS_DIR + "/viewer_test.sh " +
                              std::to_string(test::kSlowdown) + " " + IGI_MASTER_BINARY + " " + IGI_VIEW_BINARY + " " +
                              dir.string() + " 2>&1";
  const test::RunResult r = test::run(command, int(90 * test::kSlowdown));
  auto text = [&](const char* name) {
    std::ifstream in(dir / name);
    return std::string(std::istreambuf_iterator<char>(in), {});
  };
  const std::string logs = r.output + "\nmaster.log:\n" + text("master.log") + "\nviewer-1.log:\n" +
                           text("viewer-1.log") + "\nviewer-2.log:\n" + text("viewer-2.log");
  ASSERT_EQ(r.exit_code, 0) << logs;
  EXPECT_NE(r.output.find("second viewer: exit 0"), std::string::npos) << logs;
  EXPECT_NE(r.output.find("master: exit 0"), std::string::npos) << logs;
  EXPECT_NE(text("before.json"), text("after.json")) << "the drag did not turn the camera\n" << logs;
  EXPECT_NE(text("master.log").find("saved igi-shot-0000.exr and .png on the master"), std::string::npos) << logs;
  EXPECT_EQ(read_image((dir / "igi-shot-0000.exr").string()).width, 320);
  // ... and the viewer keeps the master's float image too, byte for byte, and a PNG at its exposure.
  EXPECT_EQ(text("laptop/igi-shot-0000.exr"), text("igi-shot-0000.exr"));
  EXPECT_TRUE(fs::exists(dir / "laptop" / "igi-shot-0000.png"));
  EXPECT_NE(text("viewer-1.log").find("kept here as igi-shot-0000.exr and .png"), std::string::npos) << logs;
  // It starts where the first viewer left the camera (after the drag, the box's green wall at the left).
  const Image second = read_image((dir / "second.png").string());
  float brightest = 0.0f;
  for (const glm::vec3& p : second.pixels) brightest = std::max(brightest, p.y);
  EXPECT_GT(brightest, 0.1f) << "the second viewer shows no image\n" << logs;
  EXPECT_NE(text("viewer-2.log").find("frames in"), std::string::npos) << logs;
}

}  // namespace
}  // namespace igi
