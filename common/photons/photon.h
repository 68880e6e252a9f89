#pragma once
// A caustic photon: light that reached a surface taking VPL light (Lambert,
// or GGX rougher than the glossy threshold) right after a mirror or glass.
//
// Units: flux in W, already divided by the number of photon PATHS shot in
// the frame (not the photons stored: a path that never meets a mirror or
// glass stores nothing but still counts), so a density estimate needs no
// further normalisation (pbrt-v2's photonmap does the same).
#include <glm/glm.hpp>

namespace igi {

struct Photon {
  // Every field initialised: the map is hashed and compared bit for bit.
  glm::vec3 position{0.0f};
  glm::vec3 incident{0.0f};  // unit, from the surface back towards the last mirror or glass
  glm::vec3 normal{0.0f};    // geometric normal on the side the light arrived from
  glm::vec3 flux{0.0f};
  // 1 when the path met a diffuse or glossy surface before its last mirrors
  // or glass (L (D|G)+ S+ D: light that bounced before it was focused, as
  // smooth as any indirect light), 0 for light straight from the emitter
  // (L S+ D: the sharp caustics). caustic_map.h gathers the two apart.
  uint32_t bounced = 0;
};

}  // namespace igi
