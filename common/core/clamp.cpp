#include "core/clamp.h"

#include <cmath>

namespace igi {

float clamp_bound(float clamp, float mean_chord, uint32_t pass) {
  if (!(clamp > 0.0f)) return INFINITY;
  const float d = clamp * mean_chord;
  return std::sqrt(float(pass) + 1.0f) / (d * d);
}

}  // namespace igi
