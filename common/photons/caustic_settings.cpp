#include "photons/caustic_settings.h"

#include <cstdio>

#include "material/bsdf.h"

namespace igi::photons {

std::string memory_error(const RenderSettings& s, uint64_t memory_bytes) {
  if (!s.caustics || memory_bytes == 0) return "";
  const double need = double(s.caustic_photons) * kMaxPhotonsPerPath * double(kBytesPerPhoton);
  if (need <= 0.5 * double(memory_bytes)) return "";
  char text[256];
  std::snprintf(text, sizeof text,
                "--caustic-photons: %d photon paths can store up to %.1f GiB of photons (%d a path), over half of "
                "this machine's %.1f GiB: lower --caustic-photons",
                s.caustic_photons, need / double(1ull << 30), kMaxPhotonsPerPath, double(memory_bytes) / double(1ull << 30));
  return text;
}

bool has_specular_surfaces(const Scene& scene, float glossy_threshold) {
  for (uint32_t m : scene.triangle_material)
    if (may_focus_light(scene.materials[m], glossy_threshold)) return true;
  return false;
}

}  // namespace igi::photons
