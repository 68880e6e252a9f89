#pragma once
// A node of a finished one-point cut with what its shadow ray found: what
// reconstruction cuts (lightcuts/reconstruction.h) read from the samples.
#include <cstdint>

namespace igi::lightcuts {

enum class Visibility : uint8_t { Occluded, Visible, Unknown /* no ray: nothing to see */ };

struct CutNode {
  uint32_t light;  // light tree node
  Visibility visibility;
};

}  // namespace igi::lightcuts
