#include "lightcuts/cluster_bound.h"

#include <algorithm>
#include <cmath>

namespace igi::lightcuts {

ReceiverTerms receiver_terms(const GatherNode& node, const Box& directions) {
  ReceiverTerms t;
  Cone below = node.cone;
  below.frame = BoundFrame(-node.cone.axis());
  t.cos_x = std::max(max_cos(node.cone, directions), max_cos(below, directions));
  if (t.cos_x <= 0.0f) return t;
  t.diffuse = node.diffuse;
  t.glossy = node.glossy;
  return t;
}

}  // namespace igi::lightcuts
