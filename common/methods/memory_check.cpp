#include "methods/memory_check.h"

#include <cstdio>

#include <glm/glm.hpp>

#include "core/gbuffer.h"
#include "core/tiling.h"
#include "lightcuts/gather_points.h"
#include "lightcuts/lightcuts_settings.h"
#include "photons/caustic_settings.h"

namespace igi {
std::string memory_error(const RenderSettings& s, uint64_t memory_bytes) {
  if (s.method == MethodKind::Lightcuts)
    if (std::string e = lightcuts::memory_error(s, memory_bytes); !e.empty()) return e;
  return photons::memory_error(s, memory_bytes);  // "" without caustics
}

uint64_t tile_bytes(const RenderSettings& s, int width, int height) {
  const int border = tile_border(s);
  const uint64_t pixels = uint64_t(width + 2 * border) * uint64_t(height + 2 * border);
  switch (s.method) {
    case MethodKind::PathTracer: return pixels * sizeof(glm::vec3);
    case MethodKind::Lightcuts:  // the points, their gather tree's copy and order
      return pixels * uint64_t(s.lightcuts_samples) * (2 * sizeof(lightcuts::GatherPoint) + 4);
    case MethodKind::InstantRadiosity:
    case MethodKind::Igi: {
      // A G-buffer sample; VPL sums, exact light, filter input and output; each glossy gather ray's hit;
      // the gather's light samples (one entry a sample).
      const uint64_t point = sizeof(GSample) + 4 * sizeof(glm::vec3) + sizeof(uint32_t) + sizeof(glm::vec3) +
                             uint64_t(s.glossy_rays) * (sizeof(GSample) + sizeof(uint32_t) + sizeof(glm::vec3));
      return pixels * uint64_t(s.aa_samples) * uint64_t(s.glass_branches) * point;
    }
  }
  return 0;
}

std::string tile_memory_error(const RenderSettings& s, int width, int height, int threads, uint64_t memory_bytes) {
  const double need = double(tile_bytes(s, width, height)) * double(threads);
  if (memory_bytes == 0 || need <= 0.5 * double(memory_bytes)) return "";
  std::string options;
  if (s.method == MethodKind::InstantRadiosity || s.method == MethodKind::Igi)
    options = " with --aa " + std::to_string(s.aa_samples) + ", --glass-branches " + std::to_string(s.glass_branches) +
              " and --glossy-rays " + std::to_string(s.glossy_rays);
  else if (s.method == MethodKind::Lightcuts)
    options = " with --lightcuts-samples " + std::to_string(s.lightcuts_samples);
  return "a tile of " + std::to_string(width) + " x " + std::to_string(height) + " pixels (--tile)" + options +
         " can need " + gib(need / threads) + " a render thread, " + gib(need) + " for " + std::to_string(threads) +
         (threads == 1 ? " thread" : " threads") + ", over half of this machine's " + gib(double(memory_bytes)) +
         ": lower --tile" + (options.empty() ? "" : " or the options named") + " (or use fewer threads)";
}

}  // namespace igi
