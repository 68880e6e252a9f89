#include "lightcuts/lightcuts_settings.h"

#include <cmath>
#include <cstdio>

#include <unistd.h>

#include "lightcuts/light_tree.h"
#include "vpl/vpl.h"

namespace igi::lightcuts {
namespace {

std::string number(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", v);
  return text;
}

std::string gib(double bytes) {
  char text[32];
  std::snprintf(text, sizeof text, "%.1f GiB", bytes / double(1ull << 30));
  return text;
}

}  // namespace

uint64_t bytes_per_vpl() {
  // Vpl, LightLeaf twice (input and tree order), 2 nodes and their build ranges, the build order.
  return sizeof(Vpl) + 2 * sizeof(LightLeaf) + 2 * (sizeof(LightNode) + 8) + 4;
}

std::string settings_error(const RenderSettings& s) {
  if (!(s.lightcuts_error > 0.0f && s.lightcuts_error < 1.0f))
    return "--lightcuts-error: " + number(s.lightcuts_error) + ", expected a number in (0, 1)";
  if (s.lightcuts_max_cut < 1 || s.lightcuts_max_cut > kMaxCut)
    return "--lightcuts-max-cut: " + std::to_string(s.lightcuts_max_cut) + ", expected 1 to " + std::to_string(kMaxCut);
  if (s.lightcuts_spacing < 0 || s.lightcuts_spacing > kMaxSpacing)
    return "--lightcuts-spacing: " + std::to_string(s.lightcuts_spacing) + ", expected 0 (off) to " +
           std::to_string(kMaxSpacing);
  const int side = int(std::lround(std::sqrt(double(s.lightcuts_samples))));
  if (s.lightcuts_samples < 1 || s.lightcuts_samples > kMaxSamples || side * side != s.lightcuts_samples)
    return "--lightcuts-samples: " + std::to_string(s.lightcuts_samples) +
           ", expected a square number of gather points per pixel: 1, 4, 9 ... 64";
  if (s.lightcuts_spacing > 1 && s.lightcuts_samples > 1)
    return "--lightcuts-spacing and --lightcuts-samples cannot be combined: reconstruction cuts interpolate "
           "one gather point per pixel";
  return "";
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

uint64_t physical_memory_bytes() {
  const long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGESIZE);
  return pages > 0 && page > 0 ? uint64_t(pages) * uint64_t(page) : 0;
}

}  // namespace igi::lightcuts
