// Broken scene files (tests/data/bad_scenes/, listed in its MANIFEST with a
// substring each error must contain) through the real command, igi-render:
// each must end in a normal non-zero exit with an error naming the file and
// what is wrong, and no sanitizer report. The files are tiny and fail at
// load, so nothing is rendered.
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <future>
#include <iterator>
#include <set>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "support/process.h"

namespace igi {
namespace {

namespace fs = std::filesystem;

struct BadScene {
  std::string file;
  std::string expected;  // a substring of the error message
};

std::vector<BadScene> manifest() {
  std::ifstream in(fs::path(IGI_BAD_SCENES_DIR) / "MANIFEST");
  std::vector<BadScene> scenes;
  for (std::string line; std::getline(in, line);) {
    if (line.empty() || line[0] == '#') continue;
    const size_t tab = line.find('\t');
    if (tab == std::string::npos) {
      ADD_FAILURE() << "MANIFEST line without a tab: " << line;
      continue;
    }
    scenes.push_back({line.substr(0, tab), line.substr(tab + 1)});
  }
  return scenes;
}

std::string path_of(const BadScene& scene) { return (fs::path(IGI_BAD_SCENES_DIR) / scene.file).string(); }

TEST(BadScenes, ManifestListsEverySceneFileInTheFolder) {
  std::set<std::string> listed;
  for (const BadScene& scene : manifest()) listed.insert(scene.file);
  EXPECT_GE(listed.size(), 20u);
  for (const fs::directory_entry& entry : fs::directory_iterator(IGI_BAD_SCENES_DIR)) {
    const std::string extension = entry.path().extension().string();
    if (extension != ".gltf" && extension != ".glb") continue;
    EXPECT_TRUE(listed.count(entry.path().filename().string())) << entry.path() << " is not in the MANIFEST";
  }
}

// A few runs at a time: each is mostly the program's start-up.
std::vector<test::RunResult> run_all(const std::vector<std::string>& commands) {
  constexpr size_t kAtOnce = 4;
  std::vector<test::RunResult> results;
  for (size_t first = 0; first < commands.size(); first += kAtOnce) {
    std::vector<std::future<test::RunResult>> runs;
    for (size_t i = first; i < std::min(first + kAtOnce, commands.size()); ++i)
      runs.push_back(std::async(std::launch::async, [&c = commands[i]] { return test::run(c, 120); }));
    for (std::future<test::RunResult>& run : runs) results.push_back(run.get());
  }
  return results;
}

TEST(BadScenes, IgiRenderRejectsEachWithAClearErrorAndExitStatus) {
  const fs::path output = fs::path(IGI_TEST_OUTPUT_DIR) / "bad_scenes" / "never-written.png";
  fs::create_directories(output.parent_path());
  const std::vector<BadScene> scenes = manifest();
  std::vector<std::string> commands;
  for (const BadScene& scene : scenes)
    commands.push_back(std::string(IGI_RENDER_BINARY) + " --scene '" + path_of(scene) +
                       "' --size 8x8 --spp 1 --threads 1 --quiet -o '" + output.string() + "'");
  const std::vector<test::RunResult> results = run_all(commands);
  for (size_t i = 0; i < scenes.size(); ++i) {
    SCOPED_TRACE(scenes[i].file);
    const test::RunResult& r = results[i];
    // 1..125: the program's own exit, not a signal (the shell reports those
    // as 128 + N; -1 when the shell itself died) nor a missing command.
    EXPECT_GE(r.exit_code, 1) << r.output;
    EXPECT_LE(r.exit_code, 125) << r.output;
    EXPECT_NE(r.output.find(path_of(scenes[i])), std::string::npos) << "the error does not name the file:\n"
                                                                    << r.output;
    EXPECT_NE(r.output.find(scenes[i].expected), std::string::npos)
        << "expected '" << scenes[i].expected << "' in:\n" << r.output;
    EXPECT_EQ(r.output.find("ERROR: AddressSanitizer"), std::string::npos) << r.output;
    EXPECT_EQ(r.output.find("runtime error:"), std::string::npos) << r.output;
  }
  EXPECT_FALSE(fs::exists(output));
}

// The attack's size: 41 kB of '[' crashed igi-render (SIGSEGV) in tinygltf's
// recursion. deep-extras.gltf, deepened from 65 levels to 20,000.
TEST(BadScenes, JsonNestedTwentyThousandDeepIsAnErrorNotACrash) {
  std::ifstream in(fs::path(IGI_BAD_SCENES_DIR) / "deep-extras.gltf");
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string nested = std::string(65, '[') + std::string(65, ']');
  const size_t at = text.find(nested);
  ASSERT_NE(at, std::string::npos);
  text.replace(at, nested.size(), std::string(20000, '[') + std::string(20000, ']'));
  const fs::path scene = fs::path(IGI_TEST_OUTPUT_DIR) / "bad_scenes" / "deeper-extras.gltf";
  fs::create_directories(scene.parent_path());
  std::ofstream(scene) << text;
  const test::RunResult r = test::run(std::string(IGI_RENDER_BINARY) + " --scene '" + scene.string() +
                                      "' --size 8x8 --spp 1 --threads 1 --quiet -o /dev/null", 120);
  EXPECT_GE(r.exit_code, 1) << r.output;
  EXPECT_LE(r.exit_code, 125) << r.output;
  EXPECT_NE(r.output.find(scene.string() + ": JSON: arrays and objects nested deeper than 64 levels"),
            std::string::npos) << r.output;
}

}  // namespace
}  // namespace igi
