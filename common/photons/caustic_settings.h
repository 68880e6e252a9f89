#pragma once
// The caustic options of RenderSettings, their limits and their checks,
// shared by the command lines and the wire format.
//
//   caustics         on/off (--caustics, or any --caustic-* option)
//   caustic_photons  photon PATHS shot per frame, >= 1 (--caustic-photons)
//   caustic_radius   density-estimation radius as a fraction of the scene's
//                    diagonal, in [kMinCausticRadius, kMaxCausticRadius]
//                    (--caustic-radius); scale-free like --clamp
//
// Memory: a path keeps at most kMaxPhotonsPerPath photons (photon_paths.h),
// so a frame's map needs at most paths x that x kBytesPerPhoton.
#include <cstdint>
#include <string>

#include "core/settings.h"
#include "scene/scene.h"

namespace igi::photons {

// kMaxCausticPhotons, kMinCausticRadius and kMaxCausticRadius: core/settings.h,
// with every other option's limits, where check_settings() reads them.
inline constexpr int kMaxPhotonsPerPath = 4;
// A photon, its copy in the grid's order and the grid's per-photon share.
inline constexpr uint64_t kBytesPerPhoton = 2 * 52 + 16;

// "" when the largest possible map fits in half of `memory_bytes` (or caustics
// are off, or the memory is unknown: 0), else why not, naming the option.
std::string memory_error(const RenderSettings& s, uint64_t memory_bytes);

// Whether any triangle of the scene is a mirror, glass or GGX sharper than a
// quarter of the glossy threshold (material/bsdf.h: may_focus_light): where
// caustics can form. The command lines turn caustics on for such scenes
// unless told (--caustics, --no-caustics or a --caustic-* option).
bool has_specular_surfaces(const Scene& scene, float glossy_threshold);

}  // namespace igi::photons
