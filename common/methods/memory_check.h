#pragma once
// Whether a frame's state fits on a machine: the lightcut VPLs and light
// tree, the caustic photon map, and what each render thread keeps for a
// tile. One rule for every place that asks: igi-render and igi-master before
// any work (against their own memory), the window's settings panel, and each
// worker against its own (a worker may have less memory than the master that
// checked first, and more threads).
#include <cstdint>
#include <string>

#include "core/memory.h"  // gib, machine_memory_bytes
#include "core/settings.h"

namespace igi {

// "" when it fits in `memory_bytes` (0: unknown, anything fits), else why not, naming the options.
std::string memory_error(const RenderSettings& settings, uint64_t memory_bytes);

// Bytes one render thread keeps for a tile of `width` x `height` pixels (its
// filter border added): ir and igi's G-buffer with every sub-sample, glass
// branch and glossy gather ray, and the sums shaded into it; lightcuts'
// gather points. An upper bound: a scene without glass or glossy surfaces
// fills less of it.
uint64_t tile_bytes(const RenderSettings& settings, int width, int height);
// "" when `threads` render threads' tiles fit in half of `memory_bytes` (0: unknown), else why not.
std::string tile_memory_error(const RenderSettings& settings, int width, int height, int threads, uint64_t memory_bytes);

}  // namespace igi
