// The window shows what the renderer wrote: a screenshot of it under Xvfb
// equals the PNG (both are 8-bit sRGB of the same image).
#include <cstdlib>
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "image/image.h"
#include "image/metrics.h"
#include "support/image_compare.h"

namespace igi {
namespace {

TEST(Window, ScreenshotUnderXvfbMatchesTheWrittenImage) {
  if (std::system("command -v xvfb-run >/dev/null 2>&1") != 0) GTEST_SKIP() << "xvfb-run not installed";
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
  if (std::system("command -v xvfb-run >/dev/null 2>&1") != 0) GTEST_SKIP() << "xvfb-run not installed";
  const std::string shot = test::output_path("master-window.png"), frames = test::output_path("master-prog.png");
  const std::string common = std::string(" --workers 2 --worker-threads 1 --scene cornell --method igi --vpl-paths 8") +
                             " --size 160x120 --quiet";
  std::filesystem::remove(shot);
  const std::string window = std::string("timeout -s KILL 60 xvfb-run -a -s '-screen 0 640x480x24' ") + IGI_MASTER_BINARY +
                             common + " --screenshot " + shot + " --screenshot-after 4 >/dev/null 2>&1";
  ASSERT_EQ(std::system(window.c_str()), 0) << window;
  const std::string headless = std::string(IGI_MASTER_BINARY) + common + " --frames 4 --progressive -o " + frames +
                               " >/dev/null 2>&1";
  ASSERT_EQ(std::system(headless.c_str()), 0) << headless;
  // The window accumulates exactly the frames a progressive headless run writes.
  Image shown = read_image(shot), written = read_image(test::output_path("master-prog-0003.png"));
  EXPECT_LT(max_abs_error(shown, written), 0.01);
}

}  // namespace
}  // namespace igi
