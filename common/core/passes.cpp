#include "core/passes.h"

#include "sampling/sobol.h"

namespace igi {

FrameSetup progressive_pass(const FrameSetup& base, MethodKind method, uint32_t pass, uint32_t samples_per_pass) {
  FrameSetup f = base;
  if (method == MethodKind::PathTracer) {  // the pass continues the sample sequence: same seed, the next samples
    f.sample_begin = pass * samples_per_pass;
    f.sample_count = samples_per_pass;
    return f;
  }
  f.seed = base.seed + pass;  // a new estimate: new VPLs, and the next point of one 2D set for the sub-pixel position
  f.sample_begin = pass;      // the pass: the clamp relaxes with it
  const glm::vec2 j = sample_2d(pass, 0, base.seed);
  f.jitter_x = j.x;
  f.jitter_y = j.y;
  return f;
}

}  // namespace igi
