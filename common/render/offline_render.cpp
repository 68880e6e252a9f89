#include "render/offline_render.h"

#include <algorithm>
#include <chrono>
#include <stdexcept>

#include "render/accumulator.h"
#include "sampling/sobol.h"

namespace igi {

OfflineResult render_offline(const SceneContext& context, const RenderSettings& settings,
                             const FrameSetup& base, int samples, const FrameOptions& options,
                             const std::atomic<bool>* stop) {
  auto method = make_method(context, settings);
  if (!method) throw std::invalid_argument(std::string("method not available: ") + method_name(settings.method));
  const bool pt = settings.method == MethodKind::PathTracer;
  const int per_pass = pt ? std::min(samples, 16) : 1;
  const int passes = (samples + per_pass - 1) / per_pass;

  auto start = std::chrono::steady_clock::now();
  Accumulator accumulator(base.width, base.height);
  OfflineResult result;
  result.planned = passes;
  for (int pass = 0; pass < passes && !(stop && *stop); ++pass) {
    FrameSetup frame = base;
    if (pt) {
      frame.sample_begin = uint32_t(pass * per_pass);
      frame.sample_count = uint32_t(std::min(per_pass, samples - pass * per_pass));
    } else if (passes > 1) {
      // Fresh VPLs and a new sub-pixel position per pass (stratified over passes).
      frame.seed = base.seed + uint32_t(pass);
      frame.sample_begin = uint32_t(pass);
      glm::vec2 jitter = sample_2d(uint32_t(pass), 0, base.seed);
      frame.jitter_x = jitter.x;
      frame.jitter_y = jitter.y;
    }
    method->begin_frame(frame);
    FrameOptions pass_options = options;
    if (options.progress)
      pass_options.progress = [&](float f) { options.progress((float(pass) + f) / float(passes)); };
    Image image = render_frame(*method, frame, tile_border(settings), pass_options, result.rays);
    accumulator.add(image, double(frame.sample_count));
    ++result.passes;
  }
  if (result.passes > 0) result.image = accumulator.resolve();
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace igi
