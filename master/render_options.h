#pragma once
// Command-line options shared by igi-render and (later) igi-master: which
// scene, which method with which settings, what image.
#include <string>
#include <vector>

#include "methods/settings.h"

namespace igi {

struct RenderOptions {
  std::string scene = "cornell";
  RenderSettings settings;
  int width = 640, height = 480;
  int samples = 1;          // pt: samples per pixel; ir/igi: progressive passes
  uint32_t seed = 1;
  int threads = 0;          // 0: all hardware threads
  int tile_size = 32;
  float exposure = 1.0f;
  std::string output = "render.png";
  std::string export_gltf;  // when set: write the scene as glTF and exit
  bool quiet = false;
  bool show = false;             // open a window with the result
  std::string screenshot;        // with show: save the window's pixels and close
  bool help = false;
  // Animated scenes: frame i stands at time + i x time_step seconds, with
  // loop wrapped into the animation's length (scene/animation.h scene_time).
  double time = 0.0, time_step = 1.0 / 30.0;
  bool loop = false;
};

// Parses argv; throws std::invalid_argument with a message naming the option.
RenderOptions parse_render_options(const std::vector<std::string>& args);
std::string render_usage(const std::string& program);

}  // namespace igi
