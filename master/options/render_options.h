#pragma once
// Command-line options shared by igi-render and igi-master: which scene,
// which method with which settings, what image. Declared once (CLI11), for
// both programs' command lines and help.
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "core/settings.h"
#include "image/exposure_check.h"
#include "scene/load_scene.h"

namespace CLI {
class App;
}

namespace igi {

struct RenderOptions {
  std::string scene = "cornell";
  RenderSettings settings;
  int width = 640, height = 480;
  int samples = 1;          // pt: samples per pixel; ir/igi: progressive passes
  uint32_t seed = 1;
  int threads = 0;          // 0: all hardware threads
  int tile_size = 64;  // the filter border (2 (N / 2) = 6 pixels at 6 x 6 sets) costs 1.41x the tile, 1.89x at 32
  // --exposure K|auto, --ev S|auto, --view: how 8-bit outputs (PNG, the
  // windows) show the image. A file is written at `exposure` (1 unless given);
  // igi-master's window meters unless a fixed exposure was given.
  ExposureChoice exposure;
  bool exposure_given = false;
  ViewTransform view = ViewTransform::Standard;
  std::string output = "render.png";
  std::string export_gltf;  // when set: write the scene as glTF and exit
  std::string camera_file;  // start from this camera (JSON, camera_bookmark.h); igi-master's window: its bookmark file
  bool quiet = false;
  bool show = false;             // open a window with the result
  std::string screenshot;        // with show: save the window's pixels and close
  bool help = false;
  // Animated scenes: frame i stands at time + i x time_step seconds, with
  // loop wrapped into the animation's length (scene/animation.h scene_time).
  double time = 0.0, time_step = 1.0 / 30.0;
  bool loop = false;
  glm::vec3 light_offset{0.0f};  // --move-lights: metres, as the window's keys move them
  // --environment: a constant sky's radiance or a map, replacing the scene's;
  // --environment-scale multiplies it, --environment-rotation turns a map.
  std::optional<SkyChoice> environment;
  // --caustics, --no-caustics or a --caustic-* option was given: the scene
  // does not choose (choose_caustics).
  bool caustics_given = false;
  float environment_scale = 1.0f, environment_rotation = 0.0f;
  LightUnits light_units = LightUnits::Photometric;  // --light-units: how a glTF file's lamps are read
};

// Declares the render options on `app`, writing into `options` (which must
// outlive the parse); call check_render_options() after the parse.
void add_render_options(CLI::App& app, RenderOptions& options);
// What no single option can check: the settings together, and the memory
// lightcuts and a caustic map would need. Throws cli::OptionError.
void check_render_options(const CLI::App& app, const RenderOptions& options);

// How the options ask the scene to be read: the sky (scale and rotation
// applied), or none; the lamps' units.
SceneOptions scene_options(const RenderOptions& options);

// Caustics by default where the scene has mirrors, glass or sharp GGX
// (photons::has_specular_surfaces): for ir and igi,
// unless an option chose, turns settings.caustics on when `scene` has such
// surfaces, and returns a note for the user; nothing otherwise. Throws
// cli::OptionError when the photon map would not fit in memory.
std::optional<std::string> choose_caustics(RenderOptions& options, const Scene& scene);

// Parses argv[1] on; throws cli::OptionError with a message naming the option and the value.
RenderOptions parse_render_options(const std::vector<std::string>& args);
std::string render_usage(const std::string& program);

}  // namespace igi
