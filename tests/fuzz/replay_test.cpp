// The fuzz targets' checks (fuzz/harness.h) on their seeds and on every input
// kept in tests/fuzz/regressions/<target>/: a crash found by scripts/fuzz.sh,
// copied there, stays fixed in every build, sanitized or not.
#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "fuzz/harness.h"
#include "fuzz/seeds.h"
#include "protocol/codec.h"
#include "viewer/display_messages.h"
#include "scene/gltf_loader.h"
#include "scene/scene_file.h"

namespace igi::fuzz {
namespace {

namespace fs = std::filesystem;

std::vector<Seed> regressions(const std::string& target) {
  std::vector<Seed> inputs;
  const fs::path dir = fs::path(IGI_FUZZ_REGRESSIONS_DIR) / target;
  for (const fs::directory_entry& entry : fs::directory_iterator(dir)) {
    if (!entry.is_regular_file() || entry.path().filename() == "README") continue;
    std::optional<std::vector<uint8_t>> bytes = read_file_bytes(entry.path().string());
    EXPECT_TRUE(bytes) << entry.path();
    if (bytes) inputs.push_back({entry.path().filename().string(), std::move(*bytes)});
  }
  std::sort(inputs.begin(), inputs.end(), [](const Seed& a, const Seed& b) { return a.name < b.name; });
  return inputs;
}

std::vector<Seed> scene_seeds_here() {
  return scene_seeds((fs::path(IGI_TEST_OUTPUT_DIR) / "fuzz_seeds").string());
}

TEST(FuzzReplay, DecodeSeedsCoverEveryMessageTypeAndDecode) {
  const std::vector<Seed> seeds = decode_seeds();
  const size_t types = size_t(protocol::MessageType::CancelFrame);
  EXPECT_GE(seeds.size(), types);
  std::vector<bool> seen(types + 1, false);
  for (const Seed& seed : seeds) {
    const protocol::DecodeResult result = protocol::decode(seed.bytes);
    ASSERT_TRUE(result.message) << seed.name << ": " << result.error;
    seen[size_t(protocol::type_of(*result.message))] = true;
    EXPECT_EQ(check_decode(seed.bytes), "") << seed.name;
  }
  EXPECT_EQ(std::count(seen.begin() + 1, seen.end(), true), std::ptrdiff_t(types)) << "a seed of every type";
}

// Every truncation of every seed is rejected with an error, never accepted.
TEST(FuzzReplay, DecodeSeedsCutShortAreRejected) {
  for (const Seed& seed : decode_seeds())
    for (size_t size = 0; size < seed.bytes.size(); ++size) {
      const std::span<const uint8_t> cut(seed.bytes.data(), size);
      EXPECT_FALSE(protocol::decode(cut).message) << seed.name << " cut to " << size;
      EXPECT_EQ(check_decode(cut), "") << seed.name << " cut to " << size;
    }
}

TEST(FuzzReplay, DisplaySeedsCoverEveryMessageTypeAndDecode) {
  std::vector<bool> seen(display::kTypes + 1, false);
  for (const Seed& seed : display_seeds()) {
    const display::Decoded result = display::decode(seed.bytes);
    ASSERT_TRUE(result.message) << seed.name << ": " << result.error;
    seen[size_t(display::type_of(*result.message))] = true;
    EXPECT_EQ(check_display_decode(seed.bytes), "") << seed.name;
    EXPECT_FALSE(protocol::decode(seed.bytes).message) << seed.name << ": the workers' decoder took it";
    EXPECT_EQ(check_decode(seed.bytes), "") << seed.name;
  }
  EXPECT_EQ(std::count(seen.begin() + 1, seen.end(), true), display::kTypes) << "a seed of every type";
}

// Every truncation of every display seed is rejected with an error, never accepted.
TEST(FuzzReplay, DisplaySeedsCutShortAreRejected) {
  for (const Seed& seed : display_seeds())
    for (size_t size = 0; size < seed.bytes.size(); ++size) {
      const std::span<const uint8_t> cut(seed.bytes.data(), size);
      const display::Decoded result = display::decode(cut);
      EXPECT_FALSE(result.message) << seed.name << " cut to " << size;
      EXPECT_FALSE(result.error.empty()) << seed.name << " cut to " << size;
      EXPECT_EQ(check_display_decode(cut), "") << seed.name << " cut to " << size;
    }
}

TEST(FuzzReplay, SceneSeedsLoadAndPassTheChecks) {
  const std::vector<Seed> seeds = scene_seeds_here();
  ASSERT_EQ(seeds.size(), 10u);
  for (const Seed& seed : seeds) {
    EXPECT_NO_THROW(load_gltf_memory(seed.bytes, kSceneInputName)) << seed.name;
    EXPECT_EQ(check_scene(seed.bytes), "") << seed.name;
  }
}

TEST(FuzzReplay, SceneSeedsCutShortAreRejectedNamingTheInput) {
  for (const Seed& seed : scene_seeds_here())
    for (size_t size : {size_t(0), size_t(11), size_t(20), seed.bytes.size() / 2, seed.bytes.size() - 1}) {
      const std::span<const uint8_t> cut(seed.bytes.data(), size);
      EXPECT_THROW(load_gltf_memory(cut, kSceneInputName), SceneError) << seed.name << " cut to " << size;
      EXPECT_EQ(check_scene(cut), "") << seed.name << " cut to " << size;
    }
}

// Each input as kept, and again with its header's version (bytes 4-5,
// little-endian) set to this build's: a protocol bump would otherwise turn
// every older input into a version refusal that never reaches the payload.
TEST(FuzzReplay, DecodeRegressions) {
  for (const Seed& input : regressions("decode")) {
    EXPECT_EQ(check_decode(input.bytes), "") << input.name;
    EXPECT_EQ(check_display_decode(input.bytes), "") << input.name;
    if (input.bytes.size() < 6) continue;
    std::vector<uint8_t> current = input.bytes;
    current[4] = uint8_t(protocol::kVersion & 0xff);
    current[5] = uint8_t(protocol::kVersion >> 8);
    EXPECT_EQ(check_decode(current), "") << input.name << " at version " << protocol::kVersion;
    const protocol::DecodeResult result = protocol::decode(current);
    EXPECT_EQ(result.error.find("protocol version"), std::string::npos)
        << input.name << " at version " << protocol::kVersion << ": " << result.error;
  }
}

TEST(FuzzReplay, SceneRegressions) {
  for (const Seed& input : regressions("scene")) EXPECT_EQ(check_scene(input.bytes), "") << input.name;
}

}  // namespace
}  // namespace igi::fuzz
