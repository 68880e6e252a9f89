#include "lightcuts/lightcuts_settings.h"

#include "core/memory.h"
#include "core/vpl.h"
#include "lightcuts/light_tree.h"

namespace igi::lightcuts {
uint64_t bytes_per_vpl() {
  // Vpl, LightLeaf twice (input and tree order), 2 nodes and their build ranges, the build order.
  return sizeof(Vpl) + 2 * sizeof(LightLeaf) + 2 * (sizeof(LightNode) + 8) + 4;
}

std::string memory_error(const RenderSettings& s, uint64_t memory_bytes) {
  const double need = double(max_vpls(s)) * double(bytes_per_vpl());
  if (memory_bytes == 0 || need <= 0.5 * double(memory_bytes)) return "";
  return "lightcuts: " + std::to_string(s.interleave) + " x " + std::to_string(s.interleave) + " sets x " +
         std::to_string(s.paths_per_set) + " light paths (--vpl-sets, --vpl-paths) can leave up to " +
         std::to_string(max_vpls(s)) + " VPLs (" + std::to_string(depth_limit(s.light_depth) + 1) +
         " a path, --light-depth), which with the light tree need up to " + gib(need) + ", over half of this machine's " +
         gib(double(memory_bytes)) + ": lower --vpl-paths, --vpl-sets or --light-depth";
}

}  // namespace igi::lightcuts
