#pragma once
// Light paths from the addressable sampler: same scene, settings and seed give
// bit-identical VPL sets in any process and with any thread count.
#include "methods/method.h"
#include "vpl/vpl.h"

namespace igi {

// Paths [k M, (k+1) M) form set k, so the union of all S sets is the first S M
// points of one low-discrepancy sequence scrambled by `seed`.
VplSets generate_vpls(const SceneContext& context, const RenderSettings& settings, uint32_t seed);

uint64_t hash_vpls(const std::vector<Vpl>& vpls);

}  // namespace igi
