#pragma once
// The one interface every rendering method implements.
//
// Call order: begin_frame() once per frame (single-threaded), then any number
// of render_tile() calls from any threads at once. A tile's pixels depend only
// on (scene, settings, frame setup, pixel): never on tile size, border,
// thread or process. The Method borrows the scene, accel and lights; they must
// outlive it.
#include <memory>
#include <span>

#include <glm/glm.hpp>

#include "core/frame.h"
#include "core/settings.h"
#include "lighting/lights.h"
#include "scene/accel.h"

namespace igi {

class Method {
 public:
  virtual ~Method() = default;
  virtual void begin_frame(const FrameSetup& frame) = 0;
  // Writes the job's inner w x h linear RGB pixels, row-major, into `out`.
  virtual void render_tile(const TileJob& job, std::span<glm::vec3> out, RayCounts& rays) const = 0;
  // The same, and into `surfaces` (w x h) what the pixels show
  // (core/pixel_surface.h) from the method's own camera rays; false when
  // it has none to give (then the caller traces them: trace_pixel_surfaces).
  virtual bool render_tile_with_surfaces(const TileJob& /*job*/, std::span<glm::vec3> /*out*/,
                                         std::span<PixelSurface> /*surfaces*/, RayCounts& /*rays*/) const {
    return false;
  }
  // Content hash of the per-frame state (VPL sets); 0 for methods without one.
  virtual uint64_t frame_state_hash() const { return 0; }
};

struct SceneContext {
  const Scene& scene;
  const Accel& accel;
  const LightSet& lights;
};

std::unique_ptr<Method> make_method(const SceneContext& context, const RenderSettings& settings);

}  // namespace igi
