#pragma once
// Whether a frame's per-frame state fits on a machine: the lightcut VPLs and
// light tree, the caustic photon map. One rule for every place that asks:
// igi-render and igi-master before any work (against their own memory), the
// window's settings panel, and each worker against its own (a worker may
// have less memory than the master that checked first).
#include <cstdint>
#include <string>

#include "methods/settings.h"

namespace igi {

// "" when it fits in `memory_bytes` (0: unknown, anything fits), else why not, naming the options.
std::string memory_error(const RenderSettings& settings, uint64_t memory_bytes);
// This machine's physical memory; 0 when unknown.
uint64_t machine_memory_bytes();

}  // namespace igi
