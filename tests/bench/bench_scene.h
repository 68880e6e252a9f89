#pragma once
// What the benchmark programs share: a scene ready to render, the command
// line, and main()'s error handling.
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <iostream>
#include <utility>

#include "cli/option_checks.h"

#include "core/frame.h"
#include "core/method.h"
#include "lighting/lights.h"
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

// The command line `declare(app, options)` declares (CLI11); --help prints it
// and ends the program (status 0), a bad value throws cli::OptionError.
template <class Options, class Declare>
Options parse_options(const char* about, const char* program, int argc, char** argv, Declare declare) {
  Options options;
  if (cli::parse_into(options, declare, {argv + 1, argv + argc})) return options;
  std::cout << cli::help<Options>(about, program, declare);
  std::exit(0);
}

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
