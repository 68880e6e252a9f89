#include "methods/memory_check.h"

#include "lightcuts/lightcuts_settings.h"
#include "photons/caustic_settings.h"

namespace igi {

std::string memory_error(const RenderSettings& s, uint64_t memory_bytes) {
  if (s.method == MethodKind::Lightcuts)
    if (std::string e = lightcuts::memory_error(s, memory_bytes); !e.empty()) return e;
  return photons::memory_error(s, memory_bytes);  // "" without caustics
}

uint64_t machine_memory_bytes() { return lightcuts::physical_memory_bytes(); }

}  // namespace igi
