#pragma once
// A scene with its BVH and lights, ready to render in tests.
#include <memory>

#include "image/image.h"
#include "render/offline_render.h"
#include "scene/scene.h"

namespace igi::test {

struct Prepared {
  Scene scene;
  std::unique_ptr<Accel> accel;
  std::unique_ptr<LightSet> lights;

  explicit Prepared(Scene s) : scene(std::move(s)), accel(std::make_unique<Accel>(scene)),
                               lights(std::make_unique<LightSet>(scene)) {}
  SceneContext context() const { return {scene, *accel, *lights}; }

  FrameSetup frame(int width, int height, uint32_t seed = 1) const {
    FrameSetup f;
    f.camera = scene.camera_or_auto();
    f.width = width;
    f.height = height;
    f.seed = seed;
    return f;
  }

  Image render(const RenderSettings& settings, int width, int height, int samples, uint32_t seed = 1,
               int threads = 0, int tile = 32) const {
    FrameOptions options;
    options.threads = threads;
    options.tile_size = tile;
    return render_offline(context(), settings, frame(width, height, seed), samples, options).image;
  }
};

}  // namespace igi::test
