// The programs' command lines (CLI11, common/cli/option_checks.h): a bad value
// is refused before any work with one line that names the option and the
// value, and the program's usage exit status (1: igi-render, igi-master;
// 2: igi-worker, igi-soak).
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "build_id.h"
#include "options/master_options.h"
#include "options/render_options.h"
#include "core/settings_table.h"
#include "options/options_reference.h"
#include "methods/memory_check.h"
#include "photons/caustic_settings.h"
#include "protocol/codec.h"
#include "protocol/messages.h"
#include "scene/load_scene.h"
#include "support/image_compare.h"
#include "support/process.h"

namespace igi {
namespace {

struct Refusal {
  std::string command;
  int status;
  std::vector<std::string> expected;  // each must be in the output
};

void expect_refused(const Refusal& r) {
  const test::RunResult result = test::run(r.command, 30);
  EXPECT_EQ(result.exit_code, r.status) << r.command << "\n" << result.output;
  for (const std::string& text : r.expected)
    EXPECT_NE(result.output.find(text), std::string::npos) << r.command << ": no '" << text << "' in\n" << result.output;
  EXPECT_NE(result.output.find("--help"), std::string::npos) << "a hint to --help\n" << result.output;
  EXPECT_EQ(result.output.find("stoi"), std::string::npos) << result.output;
}

TEST(Options, IgiRenderNamesTheOptionAndTheBadValue) {
  expect_refused({std::string(IGI_RENDER_BINARY) + " --quiet -o /dev/null --threads x", 1,
                  {"igi-render: --threads", "'x'"}});
}

TEST(Options, IgiMasterNamesTheOptionAndTheBadValue) {
  expect_refused({std::string(IGI_MASTER_BINARY) + " --workers 0 --frames 1 --credits many", 1,
                  {"igi-master: --credits", "'many'"}});
}

TEST(Options, IgiWorkerNamesTheOptionAndTheBadValue) {
  expect_refused({std::string(IGI_WORKER_BINARY) + " --connect tcp://127.0.0.1:1 --threads x", 2,
                  {"igi-worker: --threads", "'x'"}});
}

TEST(Options, IgiSoakNamesTheOptionAndTheBadValue) {
  expect_refused({std::string(IGI_SOAK_BINARY) + " --frames ten --dir " + std::string(IGI_TEST_OUTPUT_DIR) +
                      "/soak-bad-option", 2, {"igi-soak: --frames", "'ten'"}});
}

// An output that could not be written is refused before the first ray, not after the render.
TEST(Options, AnUnwritableOutputIsRefusedBeforeTheRender) {
  for (const std::string& binary :
       {std::string(IGI_RENDER_BINARY), std::string(IGI_MASTER_BINARY) + " --workers 0 --frames 1"}) {
    expect_refused({binary + " -o /no/such/folder/x.png", 1, {"/no/such/folder does not exist"}});
    expect_refused({binary + " -o render.xyz", 1, {"render.xyz: no image format for its extension"}});
  }
}

TEST(Options, UnknownOptionsAreNamed) {
  expect_refused({std::string(IGI_RENDER_BINARY) + " --vpl-set 4", 1, {"unknown option '--vpl-set'"}});
  expect_refused({std::string(IGI_WORKER_BINARY) + " --connect tcp://127.0.0.1:1 --thread 2", 2,
                  {"unknown option '--thread'"}});
}

// The scene's pose: a time and a light offset that a frame setup can carry.
TEST(Options, SceneTimeAndLightMovesAreChecked) {
  expect_refused({std::string(IGI_RENDER_BINARY) + " --quiet -o /dev/null --move-lights 1,x,2", 1,
                  {"igi-render: --move-lights", "X,Y,Z", "'1,x,2'"}});
  expect_refused({std::string(IGI_MASTER_BINARY) + " --workers 0 --frames 1 --time nan", 1,
                  {"igi-master: --time", "'nan'"}});
  expect_refused({std::string(IGI_MASTER_BINARY) + " --workers 0 --frames 1 --time-step 1e10", 1,
                  {"--time-step", "'1e10'"}});
}

// The sky: a colour or a file that exists, scale and rotation only with it,
// rotation only for a map; a file that is no image is refused before any work.
TEST(Options, TheEnvironmentIsAColourOrAMapFile) {
  const std::string render = std::string(IGI_RENDER_BINARY) + " --quiet -o /dev/null";
  expect_refused({render + " --environment /no/such/sky.exr", 1, {"igi-render: --environment", "no such file",
                                                                   "'/no/such/sky.exr'"}});
  expect_refused({render + " --environment 1,x,1", 1, {"--environment", "not a colour"}});
  expect_refused({render + " --environment-scale 2", 1, {"--environment-scale", "need --environment"}});
  expect_refused({std::string(IGI_MASTER_BINARY) + " --workers 0 --frames 1 --environment 1,1,1 --environment-rotation 10",
                  1, {"--environment-rotation", "a constant sky"}});
  const std::string not_an_image = test::output_path("not-a-sky.exr");
  std::ofstream(not_an_image) << "no image";
  const test::RunResult r = test::run(render + " --environment " + not_an_image, 30);
  EXPECT_NE(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("environment map"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("not-a-sky.exr"), std::string::npos) << r.output;
}

// Above the upper bound: --vpl-sets N makes N x N sets, so 50000 would overflow an int.
TEST(Options, ValuesAboveTheirRangeAreRefused) {
  expect_refused({std::string(IGI_RENDER_BINARY) + " --quiet -o /dev/null --vpl-sets 50000", 1,
                  {"--vpl-sets: expected 1..16, got 50000"}});
  expect_refused({std::string(IGI_MASTER_BINARY) + " --workers 0 --frames 1 --size 20000x10", 1,
                  {"--size", "16384", "'20000x10'"}});
  expect_refused({std::string(IGI_WORKER_BINARY) + " --connect tcp://127.0.0.1:1 --threads 99999999999", 2,
                  {"--threads", "'99999999999'"}});
}

TEST(Options, TheTimeoutMustExceedTheHeartbeat) {
  expect_refused({std::string(IGI_MASTER_BINARY) + " --workers 0 --frames 1 --heartbeat-ms 500 --timeout-ms 400", 1,
                  {"--timeout-ms 400", "--heartbeat-ms 500"}});
  expect_refused({std::string(IGI_SOAK_BINARY) + " --heartbeat-ms 200 --timeout-ms 200 --dir " +
                      std::string(IGI_TEST_OUTPUT_DIR) + "/soak-bad-option", 2,
                  {"--timeout-ms 200", "--heartbeat-ms 200"}});
}

// What the command line lets through, the wire takes: the largest heartbeat
// and credits the master accepts make a Welcome that decodes, one more is
// refused naming the option (the Welcome would be refused by every worker).
TEST(Options, TheMastersLivenessAndCreditLimitsAreTheWires) {
  const std::string max_heartbeat = std::to_string(protocol::kMaxHeartbeatMs);
  const MasterOptions o = parse_master_options({"--workers", "0", "--frames", "1", "--heartbeat-ms", max_heartbeat,
                                                "--timeout-ms", std::to_string(protocol::kMaxHeartbeatMs + 1),
                                                "--credits", std::to_string(protocol::kMaxCredits)});
  protocol::Welcome welcome;
  welcome.scene_name = "cornell";
  welcome.heartbeat_ms = uint32_t(o.heartbeat_ms);
  welcome.timeout_ms = uint32_t(o.timeout_ms);
  welcome.credits = uint32_t(o.credits);
  const protocol::DecodeResult decoded = protocol::decode(protocol::encode(welcome));
  EXPECT_TRUE(decoded.message) << decoded.error;
  expect_refused({std::string(IGI_MASTER_BINARY) + " --workers 0 --frames 1 --timeout-ms 90000 --heartbeat-ms " +
                      std::to_string(protocol::kMaxHeartbeatMs + 1), 1,
                  {"igi-master: --heartbeat-ms", "<= " + max_heartbeat}});
  expect_refused({std::string(IGI_MASTER_BINARY) + " --workers 0 --frames 1 --credits " +
                      std::to_string(protocol::kMaxCredits + 1), 1,
                  {"igi-master: --credits", "<= " + std::to_string(protocol::kMaxCredits)}});
}

bool has_ipv6_loopback() {
  std::ifstream interfaces("/proc/net/if_inet6");
  for (std::string line; std::getline(interfaces, line);)
    if (line.rfind("00000000000000000000000000000001", 0) == 0) return true;
  return false;
}

// The loopback names that pass the local-endpoint check also bind (they
// failed with "No such device"): a frame rendered by a local worker.
TEST(Options, LocalhostAndIpv6LoopbackListenEndpointsWork) {
  std::vector<std::string> endpoints = {"tcp://localhost:0"};
  if (has_ipv6_loopback()) endpoints.push_back("tcp://[::1]:0");
  for (const std::string& endpoint : endpoints) {
    const std::string out = test::output_path("listen-loopback.png");
    std::filesystem::remove(out);
    const test::RunResult r = test::run(std::string(IGI_MASTER_BINARY) + " --workers 1 --worker-threads 1 --frames 1 "
                                        "--size 16x16 --quiet --listen '" + endpoint + "' -o " + out, 60);
    EXPECT_EQ(r.exit_code, 0) << endpoint << "\n" << r.output;
    EXPECT_TRUE(std::filesystem::exists(out)) << endpoint;
  }
  if (!has_ipv6_loopback()) GTEST_SKIP() << "no IPv6 loopback here: only tcp://localhost was tried";
}

// One memory rule for igi-render, igi-master, the window's panel and each worker:
// lightcut VPLs count only for lightcuts, a caustic map for any method that builds one.
TEST(Options, OneMemoryRuleCountsLightcutVplsAndCausticMaps) {
  constexpr uint64_t kGiB = 1ull << 30;
  RenderSettings lightcuts;
  lightcuts.method = MethodKind::Lightcuts;
  lightcuts.interleave = 64;
  lightcuts.paths_per_set = 4096;
  const std::string vpls = memory_error(lightcuts, 1 * kGiB);
  EXPECT_EQ(vpls.rfind("lightcuts: 64 x 64 sets x 4096 light paths", 0), 0u) << vpls;
  EXPECT_EQ(memory_error(lightcuts, 0), "") << "unknown memory: anything fits";
  RenderSettings igi = lightcuts;
  igi.method = MethodKind::Igi;
  EXPECT_EQ(memory_error(igi, 1 * kGiB), "") << "igi keeps one set a pixel, not a light tree";
  igi.caustics = true;
  igi.caustic_photons = 1 << 26;
  const std::string map = memory_error(igi, 16 * kGiB);
  EXPECT_EQ(map.rfind("--caustic-photons: 67108864", 0), 0u) << map;
  igi.caustic_photons = 20000;
  EXPECT_EQ(memory_error(igi, 16 * kGiB), "");
}

// A tile's scratch grows with its pixels, sub-samples, glass branches and glossy
// rays: the issue's --tile 1024 --aa 64 --glass-branches 8 asked for 66 GB a thread.
TEST(Options, TileScratchIsBoundedByMemoryBeforeAnyWork) {
  RenderSettings s;
  s.method = MethodKind::Igi;
  s.paths_per_set = 64;
  s.aa_samples = 1;
  s.glass_branches = 1;
  const uint64_t one = tile_bytes(s, 32, 32);
  EXPECT_GT(one, uint64_t(40 * 40) * 100) << "the border counts: 8 x 8 sets, 4 pixels a side";
  s.aa_samples = 16;
  s.glass_branches = 4;
  EXPECT_EQ(tile_bytes(s, 32, 32), 64 * one) << "linear in sub-samples and branches";
  s.aa_samples = 64;
  s.glass_branches = 8;
  EXPECT_GT(tile_bytes(s, 1024, 1024), 60ull << 30);
  EXPECT_EQ(tile_memory_error(s, 32, 32, 16, 16ull << 30), "") << "a default tile fits anywhere";
  const std::string error = tile_memory_error(s, 1024, 1024, 1, 128ull << 30);
  EXPECT_EQ(error.rfind("a tile of 1024 x 1024 pixels (--tile) with --aa 64, --glass-branches 8 and --glossy-rays 1", 0), 0u)
      << error;
  expect_refused({std::string(IGI_RENDER_BINARY) + " --tile 1024 --aa 64 --vpl-paths 64 --glass-branches 8 --threads 1",
                  1, {"a tile of 1024 x 1024 pixels (--tile) with --aa 64", "a render thread"}});
}

// igi-render's options that igi-master has no use for are refused, not ignored
// (one frame with --spp 4 was bit-identical to --spp 1).
TEST(Options, IgiMasterRefusesTheOptionsItWouldIgnore) {
  const std::string master = std::string(IGI_MASTER_BINARY) + " --workers 0 --frames 1 ";
  for (const Refusal& r : std::vector<Refusal>{
           {master + "--spp 4", 1, {"--spp: igi-master renders one pass of igi a frame", "--progressive"}},
           {master + "--threads 2", 1, {"--threads: igi-master renders nothing itself", "--worker-threads"}},
           {master + "--export-gltf x.gltf", 1, {"--export-gltf: igi-render writes the scene"}},
           {master + "--show", 1, {"--show: igi-master opens a window whenever --frames is not given"}}})
    expect_refused(r);
  const MasterOptions pt = parse_master_options({"--workers", "0", "--frames", "1", "--method", "pt", "--spp", "4"});
  EXPECT_EQ(pt.render.samples, 4) << "pt's samples per pixel stay";
}

// Caustics are on by default where the scene has mirrors, glass or GGX
// sharper than the glossy threshold (for ir and igi), unless an option
// chose; igi-render and igi-master say so.
TEST(Options, CausticsAreOnWhereTheSceneHasMirrorsOrGlassUnlessAnOptionChose) {
  const Scene glass = load_scene("glass"), cornell = load_scene("cornell");
  // The courtyard's ball is GGX at alpha 0.02, glossy-rough's floor at 0.3: lobes
  // sharper than a quarter of the threshold focus light.
  EXPECT_TRUE(photons::has_specular_surfaces(load_scene("courtyard"), 0.2f));
  EXPECT_FALSE(photons::has_specular_surfaces(load_scene("courtyard"), 0.0f)) << "0: VPLs shade every GGX lobe";
  EXPECT_FALSE(photons::has_specular_surfaces(load_scene("glossy-rough"), 0.5f));
  EXPECT_TRUE(photons::has_specular_surfaces(load_scene("glossy-rough"), 1.5f));
  struct Case {
    std::vector<std::string> args;
    const Scene* scene;
    bool caustics, note;
  };
  for (const Case& c : std::vector<Case>{{{}, &glass, true, true},
                                         {{"--no-caustics"}, &glass, false, false},
                                         {{"--caustics", "--no-caustics"}, &glass, false, false},
                                         {{"--caustic-photons", "4000"}, &glass, true, false},
                                         {{"--method", "ir"}, &glass, true, true},
                                         {{"--method", "pt"}, &glass, false, false},
                                         {{"--method", "lightcuts"}, &glass, false, false},
                                         {{}, &cornell, false, false},
                                         {{"--caustics"}, &cornell, true, false}}) {
    std::string name = c.scene == &glass ? "glass" : "cornell";
    for (const std::string& a : c.args) name += " " + a;
    RenderOptions o = parse_render_options(c.args);
    const std::optional<std::string> note = choose_caustics(o, *c.scene);
    EXPECT_EQ(o.settings.caustics, c.caustics) << name;
    ASSERT_EQ(note.has_value(), c.note) << name;
    if (note) EXPECT_NE(note->find("--no-caustics"), std::string::npos) << *note;
  }
  const std::string out = test::output_path("caustics-note.exr");
  for (const std::string program : {std::string(IGI_RENDER_BINARY) + " --threads 1",
                                    std::string(IGI_MASTER_BINARY) + " --workers 1 --worker-threads 1 --frames 1"}) {
    const auto r = test::run(program + " --scene glass --size 16x16 -o " + out);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_NE(r.output.find("caustics on: the scene has mirrors, glass or sharp glossy surfaces"), std::string::npos)
        << r.output;
  }
}

// --version prints the build id the handshake compares, and exits 0 before any other check.
TEST(Options, VersionPrintsTheBuildIdAndExitsZero) {
  for (const std::string program : {IGI_RENDER_BINARY, IGI_MASTER_BINARY, IGI_WORKER_BINARY}) {
    const test::RunResult r = test::run(program + " --version", 30);
    EXPECT_EQ(r.exit_code, 0) << program << "\n" << r.output;
    EXPECT_EQ(r.output, std::string(build_id()) + "\n") << program;
  }
}

TEST(Options, HelpListsTheOptionsAndExitsZero) {
  const std::pair<std::string, std::string> programs[] = {{IGI_RENDER_BINARY, "--vpl-sets"},
                                                           {IGI_MASTER_BINARY, "--heartbeat-ms"},
                                                           {IGI_WORKER_BINARY, "--connect"},
                                                           {IGI_SOAK_BINARY, "--faults"}};
  for (const auto& [binary, option] : programs) {
    const test::RunResult r = test::run(binary + " --help", 30);
    EXPECT_EQ(r.exit_code, 0) << binary << "\n" << r.output;
    EXPECT_NE(r.output.find(option), std::string::npos) << binary << "\n" << r.output;
  }
}

// --help shows the defaults the code has: each option's line ends in the
// struct's value (RenderOptions, and RenderSettings for every row of the
// settings' table), in both programs.
TEST(Options, HelpShowsTheDefaultsOfTheSettingsStructs) {
  const RenderOptions o{};
  const RenderSettings& s = o.settings;
  auto g = [](double v) {
    char text[32];
    std::snprintf(text, sizeof text, "%g", v);
    return std::string(text);
  };
  std::vector<std::pair<std::string, std::string>> defaults = {
      {"--spp", std::to_string(o.samples)},
      {"--size", std::to_string(o.width) + "x" + std::to_string(o.height)}, {"--seed", std::to_string(o.seed)},
      {"--tile", std::to_string(o.tile_size)}};
  for (const Setting& row : settings_table()) {
    if (!*row.option || std::holds_alternative<bool RenderSettings::*>(row.member)) continue;  // switches show none
    std::visit(
        [&](auto member) {
          using T = std::remove_cvref_t<decltype(s.*member)>;
          if constexpr (std::is_same_v<T, MethodKind>) defaults.push_back({row.option, method_name(s.*member)});
          else if constexpr (std::is_same_v<T, float>) defaults.push_back({row.option, g(s.*member)});
          else if constexpr (std::is_same_v<T, int>)
            defaults.push_back({row.option, s.*member == kBidirAuto ? "auto" : std::to_string(s.*member)});
        },
        row.member);
  }
  ASSERT_EQ(defaults.size(), 4u + 28u);
  for (const std::string binary : {IGI_RENDER_BINARY, IGI_MASTER_BINARY}) {
    const test::RunResult r = test::run(binary + " --help", 30);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    for (const auto& [option, value] : defaults) {
      // The option's entry: from "  --name " to the next line that starts an option.
      const size_t at = r.output.find("  " + option + " ");
      ASSERT_NE(at, std::string::npos) << binary << " lists " << option;
      const size_t next = r.output.find("\n  -", at + 1);
      const std::string entry = r.output.substr(at, next == std::string::npos ? std::string::npos : next - at);
      EXPECT_NE(entry.find("[" + value + "]"), std::string::npos)
          << binary << ": " << option << " should show [" << value << "]:\n" << entry;
    }
  }
}

// master/options/OPTIONS.md is what the settings' table and the command lines
// say now: scripts/options-reference.sh writes it after a change.
TEST(Options, TheOptionsReferenceIsCurrent) {
  const std::filesystem::path file =
      std::filesystem::path(IGI_TEST_DATA_DIR).parent_path().parent_path() / "master" / "options" / "OPTIONS.md";
  std::ifstream in(file);
  ASSERT_TRUE(in) << file;
  const std::string committed((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string current = options_reference();
  if (committed != current) {
    std::ofstream(test::output_path("OPTIONS.md")) << current;
    FAIL() << file << " is not the options reference of this build (the current one is "
           << test::output_path("OPTIONS.md") << "): run scripts/options-reference.sh";
  }
}

}  // namespace
}  // namespace igi
