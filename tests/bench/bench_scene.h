#pragma once
// What the benchmark programs share: a scene ready to render, and main()'s
// error handling.
#include <cstdint>
#include <cstdio>
#include <exception>
#include <utility>

#include "lighting/lights.h"
#include "methods/method.h"
#include "render/frame.h"
#include "scene/accel.h"
#include "scene/scene.h"
#include "support/render_fixture.h"  // test::camera_frame

namespace igi::bench {

// A scene with its BVH and lights, alive for one scene's measurements.
struct PreparedScene {
  Scene scene;
  Accel accel;
  LightSet lights;
  explicit PreparedScene(Scene s) : scene(std::move(s)), accel(scene), lights(scene) {}
  SceneContext context() const { return {scene, accel, lights}; }
  FrameSetup frame(int width, int height, uint32_t seed = 1) const {
    return test::camera_frame(scene, width, height, seed);
  }
};

// Runs a benchmark's body; a bad option or file ends it with status 1 and
// the program's name before the message.
template <class Body>
int run_main(const char* program, Body&& body) {
  try {
    return body();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: %s\n", program, e.what());
    return 1;
  }
}

}  // namespace igi::bench
