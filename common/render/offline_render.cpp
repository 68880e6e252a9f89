#include "render/offline_render.h"

#include <algorithm>
#include <chrono>
#include <stdexcept>

#include "render/accumulator.h"
#include "core/passes.h"

namespace igi {

OfflineResult render_offline(const SceneContext& context, const RenderSettings& settings,
                             const FrameSetup& base, int samples, const FrameOptions& options,
                             const std::atomic<bool>* stop) {
  FrameJob job(context, settings);  // as a worker renders a frame's tiles (render/frame_job.h)
  const bool pt = settings.method == MethodKind::PathTracer;
  const int per_pass = pt ? std::min(samples, 16) : 1;
  const int passes = (samples + per_pass - 1) / per_pass;

  auto start = std::chrono::steady_clock::now();
  Accumulator accumulator(base.width, base.height);
  OfflineResult result;
  result.planned = passes;
  for (int pass = 0; pass < passes && !(stop && *stop); ++pass) {
    // pt's passes share out its samples (the last may take fewer); a single
    // pass of the others is a plain frame (core/passes.h).
    FrameSetup frame = base;
    if (pt || passes > 1) frame = progressive_pass(base, settings.method, uint32_t(pass), uint32_t(per_pass));
    if (pt) frame.sample_count = uint32_t(std::min(per_pass, samples - pass * per_pass));
    job.begin(frame);
    FrameOptions pass_options = options;
    if (options.progress)
      pass_options.progress = [&](float f) { options.progress((float(pass) + f) / float(passes)); };
    Image image = render_frame(job, pass_options, result.rays);
    accumulator.add(image, double(frame.sample_count));
    ++result.passes;
  }
  if (result.passes > 0) result.image = accumulator.resolve();
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace igi
