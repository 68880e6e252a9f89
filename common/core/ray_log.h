#pragma once
// A record of the ray packets a method traced, so a benchmark can replay the
// very same rays through Embree alone. Recording is single-threaded only.
#include <vector>

#include <embree3/rtcore.h>

namespace igi {

struct alignas(64) LoggedPrimary {
  int valid[16];
  RTCRayHit16 rays;
};
struct alignas(64) LoggedShadow {
  int valid[16];
  RTCRay16 rays;
};

struct RayLog {
  std::vector<LoggedPrimary> primary;
  std::vector<LoggedShadow> shadow;
};

}  // namespace igi
