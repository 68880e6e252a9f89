#pragma once
// Caustic photons: a fixed number of light paths per frame, every random
// number addressable, so every worker traces the identical photons.
//
// Path i (0 <= i < paths) is the light path of vpl/light_path.h with the
// Sobol index i, scrambled by a hash of the frame seed distinct from the VPL
// paths' (progressive passes, which advance the seed, shoot fresh photons).
// It bounces like a VPL path (BSDF sampling, Russian roulette by albedo,
// --light-depth), and keeps a photon at every surface that takes VPL light
// (bsdf.h: receives_vpls) and was reached straight from a mirror or glass:
// the light of paths L (D|G)* S+ D whose last segments pass through specular
// surfaces. That is exactly what the VPL methods miss: a VPL lights a point
// only by an unoccluded shadow ray, and shadow rays stop at glass. A sharp
// GGX surface is a bounce, not a mirror: it gets a VPL with a widened lobe
// (VplShading::vpl_bsdf) that lights what it reflects onto, so no photon
// follows it directly (that would count L G D twice), and none is stored on
// it (it gathers its lobe with rays, methods/glossy_gather.h). A photon
// records whether its path bounced off a non-specular surface before
// (Photon::bounced).
//
// A path stops after kMaxPhotonsPerPath photons (its flux by then has passed
// four diffuse-after-specular bounces): the map's size is bounded before any
// work (caustic_settings.h).
//
// Threads: paths are traced in fixed chunks on up to `threads` threads and
// concatenated in path order, so the result does not depend on the thread
// count.
#include <cstdint>
#include <vector>

#include "core/method.h"
#include "photons/photon.h"

namespace igi {

std::vector<Photon> trace_photon_paths(const SceneContext& context, const RenderSettings& settings, uint32_t seed,
                                       uint32_t paths, int threads, RayCounts& rays);

}  // namespace igi
