#pragma once
// A scene with its BVH and lights, ready to render in tests.
#include <algorithm>
#include <memory>
#include <vector>

#include "core/gbuffer.h"
#include "image/image.h"
#include "render/offline_render.h"
#include "sampling/sobol.h"
#include "scene/animation.h"
#include "scene/scene.h"

namespace igi::test {

// Settings for the VPL methods (ir, igi) as the tests vary them.
// Every option the VPL methods' defaults set is explicit here: a test keeps
// testing what it tested when the defaults change.
inline RenderSettings vpl_settings(MethodKind kind, int paths, float clamp = 0.0f, bool filter = true,
                                   int compensation = 0, int aa = 1) {
  RenderSettings s;
  s.method = kind;
  s.interleave = 3;  // 3 x 3 sets: the tests' images are small (6 x 6, the default, is tested where named)
  s.paths_per_set = paths;
  s.clamp = clamp;
  s.filter = filter;
  s.compensation_samples = compensation;
  s.aa_samples = aa;
  s.importance_paths = 0;  // lights by power (light importance, the default, is tested where named)
  s.bidir_vpls = 0;        // light paths alone (bidirectional IR by view, the default, is tested where named)
  return s;
}

// Luminance in double, for sums over many pixels.
inline double luminance(glm::vec3 c) { return 0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z; }

// A frame of width x height from the scene's camera.
inline FrameSetup camera_frame(const Scene& scene, int width, int height, uint32_t seed = 1) {
  FrameSetup f;
  f.camera = scene.camera_or_auto();
  f.width = width;
  f.height = height;
  f.seed = seed;
  return f;
}

struct Prepared {
  Scene scene;
  std::unique_ptr<Accel> accel;
  std::unique_ptr<LightSet> lights;

  explicit Prepared(Scene s) : scene((group_area_lights(s), std::move(s))), accel(std::make_unique<Accel>(scene)),
                               lights(std::make_unique<LightSet>(scene)) {}
  SceneContext context() const { return {scene, *accel, *lights}; }

  FrameSetup frame(int width, int height, uint32_t seed = 1) const { return camera_frame(scene, width, height, seed); }

  // The surface seen through each pixel centre, row-major.
  std::vector<GSample> visible_points(int width, int height) const {
    GBuffer gbuffer;
    RayCounts rays;
    build_gbuffer(*accel, frame(width, height), Region{0, 0, width, height}, 1, 1, 16, gbuffer, rays);
    return std::move(gbuffer.layers);
  }

  Image render(const RenderSettings& settings, int width, int height, int samples, uint32_t seed = 1,
               int threads = 0, int tile = 32) const {
    FrameOptions options;
    options.threads = threads;
    options.tile_size = tile;
    return render_offline(context(), settings, frame(width, height, seed), samples, options).image;
  }

  // The clamp (core/clamp.h) that bounds G at `distance` metres in one frame.
  float clamp_at(float distance) const { return distance / accel->mean_chord(); }

  // `passes` frames as render() takes them (seeds seed, seed + 1, ...; the
  // same sub-pixel positions), each clamped as a frame on its own, averaged:
  // for tests of one clamp's bias, which progressive passes relax.
  Image render_frames(const RenderSettings& settings, int width, int height, int passes, uint32_t seed = 1) const {
    Image sum(width, height);
    for (int pass = 0; pass < passes; ++pass) {
      FrameSetup f = frame(width, height, seed + uint32_t(pass));
      if (passes > 1) {
        const glm::vec2 jitter = sample_2d(uint32_t(pass), 0, seed);
        f.jitter_x = jitter.x;
        f.jitter_y = jitter.y;
      }
      const Image image = render_offline(context(), settings, f, 1, FrameOptions{}).image;
      for (size_t i = 0; i < sum.pixels.size(); ++i) sum.pixels[i] += image.pixels[i] / float(passes);
    }
    return sum;
  }
};

// The frame rendered tile by tile on this thread, tiles of tw x th with
// `border` from origin offset (ox, oy): the first row and column of tiles are
// cut short, so tile edges fall elsewhere than in a whole-frame render.
inline Image render_tiled(const Method& method, const FrameSetup& frame, int border, int tw, int th, int ox, int oy) {
  Image image(frame.width, frame.height);
  RayCounts rays;
  for (int y = -oy; y < frame.height; y += th)
    for (int x = -ox; x < frame.width; x += tw) {
      const int x0 = std::max(0, x), y0 = std::max(0, y);
      const int w = std::min(frame.width, x + tw) - x0, h = std::min(frame.height, y + th) - y0;
      if (w <= 0 || h <= 0) continue;
      std::vector<glm::vec3> pixels(size_t(w) * h);
      method.render_tile(TileJob{x0, y0, w, h, border}, pixels, rays);
      image.paste(pixels, x0, y0, w, h);
    }
  return image;
}

}  // namespace igi::test
