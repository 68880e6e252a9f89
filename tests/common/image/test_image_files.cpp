// Image files (image/image.h), as headless frames, igi-render's -o and
// screenshots write them: a file is replaced whole or not at all, nothing is
// left beside it, equal images give byte-identical files, and a Ctrl-C leaves
// a partial image under its own name.
#include <chrono>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <thread>

#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>

#include "image/image.h"
#include "support/image_compare.h"
#include "support/process.h"

namespace igi {
namespace {

namespace fs = std::filesystem;

std::string file_bytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

Image gradient(int width, int height, float scale) {
  Image image(width, height);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) image.at(x, y) = scale * glm::vec3(float(x) / width, float(y) / height, 0.25f);
  return image;
}

size_t entries(const fs::path& folder) { return size_t(std::distance(fs::directory_iterator(folder), {})); }

TEST(ImageFiles, AWriteReplacesTheOldFileWholeAndLeavesNothingBeside) {
  const fs::path folder = test::fresh_test_dir("image-files");
  for (const char* name : {"frame.exr", "frame.png"}) {
    const fs::path path = folder / name;
    write_image(gradient(64, 48, 1.0f), path.string());
    const Image second = gradient(8, 4, 0.5f);
    write_image(second, path.string());
    const Image back = read_image(path.string());
    EXPECT_EQ(back.width, 8);
    EXPECT_EQ(back.height, 4);
    if (fs::path(name).extension() == ".exr") {
      EXPECT_TRUE(test::images_identical("image-files-replace", back, second));
    }
  }
  EXPECT_EQ(entries(folder), 2u) << "a temporary file was left in " << folder;
}

// Scoped: files this process writes stop at `bytes` (write() then fails with
// EFBIG instead of raising SIGXFSZ), even for root, whom permissions never stop.
struct FileSizeLimit {
  rlimit saved{};
  void (*saved_handler)(int) = nullptr;
  explicit FileSizeLimit(rlim_t bytes) {
    getrlimit(RLIMIT_FSIZE, &saved);
    saved_handler = std::signal(SIGXFSZ, SIG_IGN);
    const rlimit limit{bytes, saved.rlim_max};
    setrlimit(RLIMIT_FSIZE, &limit);
  }
  ~FileSizeLimit() {
    setrlimit(RLIMIT_FSIZE, &saved);
    std::signal(SIGXFSZ, saved_handler);
  }
};

TEST(ImageFiles, AFailedWriteLeavesTheOldFileUntouched) {
  const fs::path folder = test::fresh_test_dir("image-files");
  const fs::path path = folder / "frame.exr";
  write_image(gradient(4, 4, 1.0f), path.string());
  const std::string before = file_bytes(path);
  bool threw = false;
  {
    const FileSizeLimit limit(before.size() + 1024);  // the old file fits, the new one cannot be written
    try {
      write_image(gradient(512, 512, 1.0f), path.string());
    } catch (const std::exception& e) {
      threw = true;
      EXPECT_NE(std::string(e.what()).find(path.string()), std::string::npos) << e.what();
    }
  }
  EXPECT_TRUE(threw);
  EXPECT_EQ(file_bytes(path), before);
  EXPECT_EQ(entries(folder), 1u) << "a temporary file was left in " << folder;
}

TEST(ImageFiles, AWriteIntoAMissingFolderFailsNamingThePath) {
  const fs::path path = test::output_path("image-files-no-such-folder") + "/frame.exr";
  try {
    write_image(gradient(4, 4, 1.0f), path);
    ADD_FAILURE() << "wrote into a folder that does not exist";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
  }
}

// A link is followed: its target gets the image, and the link stays a link.
TEST(ImageFiles, AWriteThroughALinkReplacesItsTarget) {
  const fs::path folder = test::fresh_test_dir("image-files");
  fs::create_directories(folder / "real");
  write_image(gradient(4, 4, 1.0f), (folder / "real" / "frame.png").string());
  fs::create_symlink("real/frame.png", folder / "link.png");
  write_image(gradient(6, 2, 1.0f), (folder / "link.png").string());
  EXPECT_TRUE(fs::is_symlink(folder / "link.png"));
  EXPECT_EQ(read_image((folder / "real" / "frame.png").string()).width, 6);
  EXPECT_EQ(entries(folder / "real"), 1u);
}

// A device is written in place (-o /dev/null), never renamed over. The test
// makes its own null device, so that a mistake cannot replace /dev/null.
TEST(ImageFiles, AWriteToADeviceGoesStraightToIt) {
  const fs::path device = test::fresh_test_dir("image-files") / "null.png";
  if (::mknod(device.c_str(), S_IFCHR | 0666, makedev(1, 3)) != 0)
    GTEST_SKIP() << "cannot make a device node here (not root, or a container without mknod)";
  write_image(gradient(4, 4, 1.0f), device.string());
  EXPECT_TRUE(fs::is_character_file(device));
  EXPECT_EQ(entries(device.parent_path()), 1u);
}

// OpenImageIO stamps EXR headers with the time unless told otherwise: the
// second write comes more than a second later, so a stamp would differ.
TEST(ImageFiles, EqualImagesGiveByteIdenticalFiles) {
  const fs::path folder = test::fresh_test_dir("image-files");
  const Image image = gradient(32, 16, 2.0f);
  const char* names[] = {"frame.exr", "frame.png"};
  for (const char* name : names) write_image(image, (folder / ("first-" + std::string(name))).string());
  std::this_thread::sleep_for(std::chrono::milliseconds(1100));
  for (const char* name : names) {
    write_image(image, (folder / ("second-" + std::string(name))).string());
    EXPECT_EQ(file_bytes(folder / ("first-" + std::string(name))), file_bytes(folder / ("second-" + std::string(name))))
        << name;
  }
}


// Ctrl-C on igi-render writes the passes finished so far, beside the output
// and named as partial (out.partial.exr), says how many, and exits 130; the
// output's own name is never a partial image.
TEST(ImageFiles, CtrlCOnIgiRenderWritesThePassesDoneAsPartial) {
  const std::filesystem::path dir = test::output_path("interrupted");
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const std::string out = (dir / "out.exr").string(), log = (dir / "log.txt").string();
  pid_t render = test::start(std::string(IGI_RENDER_BINARY) + " --scene cornell --size 32x24 --vpl-paths 4 --spp 1000000 "
                             "--threads 1 -o " + out + " >" + log + " 2>&1");
  std::this_thread::sleep_for(std::chrono::milliseconds(1500));  // loading, then many 2 ms passes
  kill(render, SIGINT);
  EXPECT_EQ(test::wait_exit(render, 60), 130);
  std::ifstream in(log);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("interrupted after "), std::string::npos) << text;
  EXPECT_NE(text.find(" of 1000000 passes: wrote them to " + (dir / "out.partial.exr").string()), std::string::npos)
      << text;
  EXPECT_FALSE(std::filesystem::exists(out));
  const Image partial = read_image((dir / "out.partial.exr").string());
  EXPECT_EQ(partial.width, 32);
  double sum = 0.0;
  for (int y = 0; y < partial.height; ++y)
    for (int x = 0; x < partial.width; ++x) sum += partial.at(x, y).g;
  EXPECT_GT(sum, 0.0) << "the lit box, not an empty image";
}

}  // namespace
}  // namespace igi
