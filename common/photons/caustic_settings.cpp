#include "photons/caustic_settings.h"

#include <cstdio>

namespace igi::photons {
namespace {

std::string number(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", v);
  return text;
}

}  // namespace

std::string settings_error(const RenderSettings& s) {
  if (s.caustic_photons < 1 || s.caustic_photons > kMaxCausticPhotons)
    return "--caustic-photons: " + std::to_string(s.caustic_photons) + ", expected 1 to " +
           std::to_string(kMaxCausticPhotons) + " photon paths per frame (leave out --caustics to turn caustics off)";
  if (!(s.caustic_radius >= kMinCausticRadius && s.caustic_radius <= kMaxCausticRadius))
    return "--caustic-radius: " + number(s.caustic_radius) + ", expected a fraction of the scene diagonal in [" +
           number(kMinCausticRadius) + ", " + number(kMaxCausticRadius) + "]";
  return "";
}

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

}  // namespace igi::photons
