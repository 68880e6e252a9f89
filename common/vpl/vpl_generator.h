#pragma once
// Light paths from the addressable sampler: same scene, settings and seed give
// bit-identical VPL sets in any process and with any thread count.
#include "core/method.h"
#include "core/vpl.h"
#include "vpl/start_guide.h"

namespace igi {

// How a light path reached one of its VPLs: what bidirectional instant
// radiosity needs to weigh the VPL against a reverse VPL at the same point
// (common/importance/bidirectional.h).
struct LightVertex {
  enum class From : uint8_t {
    Light,     // the VPL is an Area VPL, on the emitter itself
    Vpl,       // the path came straight from VPL `index` (of the same vector)
    Punctual,  // the path came straight from point, spot or directional light `index` (LightSet entry)
    Specular,  // a mirror or glass came between this VPL and the path's previous vertex
  };
  From from = From::Light;
  uint32_t index = 0;
  int depth = -1;  // the light path's bounce at which it left this VPL; -1 on the light
};

// What the light-importance methods change about light paths (common/importance/).
struct LightPathOptions {
  const Distribution1D* selection = nullptr;  // lights chosen by this instead of by power (flux / its probability)
  const StartGuide* guide = nullptr;          // where on a light paths start (importance/view_guide.h)
  std::vector<LightVertex>* vertices = nullptr;  // filled with one entry per VPL, in the order of VplSets::vpls
};

// Paths [k M, (k+1) M) form set k, so the union of all S sets is the first S M
// points of one low-discrepancy sequence scrambled by `seed`.
VplSets generate_vpls(const SceneContext& context, const RenderSettings& settings, uint32_t seed,
                      const LightPathOptions& options = {});

uint64_t hash_vpls(const std::vector<Vpl>& vpls);

}  // namespace igi
