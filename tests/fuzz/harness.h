#pragma once
// What the fuzz targets check for one input, shared by the libFuzzer entry
// points (decode_fuzzer.cpp, scene_fuzzer.cpp, built with -DIGI_FUZZ=ON) and
// the replay test in the normal suite (replay_test.cpp), which runs every
// seed and every file under tests/fuzz/regressions/<target>/.
//
// Each check returns "" when the input was handled as the interface promises
// (accepted and consistent, or rejected with a proper error), otherwise what
// broke. Crashes and sanitizer reports need no return value: they end the run.
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <span>
#include <string>
#include <vector>

namespace igi::fuzz {

// protocol::decode: a rejected message has an error; an accepted one encodes
// back to the same bytes and decodes again. For a TileResult the master's
// in-place path (decode_tile_result + copy_tile_pixels) accepts exactly the
// same messages, with the same error, and copies the same pixels.
std::string check_decode(std::span<const uint8_t> bytes);

// display::decode, the display link's (master/viewer/display_messages.h), as
// check_decode: a rejected message has an error; an accepted one encodes back
// to the same bytes, and a Frame's pixels unpack to its size or are refused.
// The decode target runs both decoders on every input.
std::string check_display_decode(std::span<const uint8_t> bytes);

// load_gltf_memory (no external files): a rejected scene throws SceneError
// naming the input; an accepted one validates, has finite lights, camera and
// textures, and goes through what a renderer builds first (bounds, the
// automatic camera, the light set, texture lookups).
std::string check_scene(std::span<const uint8_t> bytes);

// A libFuzzer target's verdict on a check's result: 0 when it is "", else the
// failure goes to stderr after `target` and the run aborts, so that libFuzzer
// keeps the input as a crash.
inline int fail_unless_handled(const char* target, const std::string& failure) {
  if (failure.empty()) return 0;
  std::fprintf(stderr, "%s: %s\n", target, failure.c_str());
  std::abort();
}

// The name the scene target gives its input: no extension, so the bytes
// decide between .glb and .gltf.
inline constexpr const char* kSceneInputName = "fuzz-input";

}  // namespace igi::fuzz
