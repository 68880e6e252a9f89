#pragma once
// The lightcuts options of RenderSettings, their limits and their checks,
// shared by the command lines and the wire format.
//
//   lightcuts_error    refine until every cluster's bound is below this
//                      fraction of the cut's total, in (0, 1); 0.02 is the
//                      paper's Weber-law value
//   lightcuts_max_cut  and stop at this many nodes, >= 1
//   lightcuts_spacing  reconstruction cuts: full cuts every S pixels only
//                      (lightcuts/reconstruction.h); 0 or 1 = off
//   lightcuts_samples  multidimensional lightcuts: K = s x s gather points
//                      per pixel (1, 4, 9 ... 64); not with reconstruction
//   lightcuts_block    block cuts: one cut for the B x B pixels of a block
//                      on one Lambertian surface (lightcuts/cut.h), 0..8;
//                      0 or 1 = a cut per pixel; plain cuts only
//
// VPLs: all N x N sets of M light paths (--vpl-sets, --vpl-paths), each path
// leaving at most depth_limit(light_depth) + 1 VPLs (vpl/vpl_generator.cpp),
// ALL of them in one light tree. Unbounded light paths (the default) are
// bounded here by the generator's safety cap, so very large path counts need
// an explicit --light-depth to pass the memory check.
#include <cstdint>
#include <string>

#include "core/settings.h"

namespace igi::lightcuts {

// Their limits (kMaxCut, kMaxSpacing, kMaxSamples, kMaxBlock) are in
// core/settings.h with every other option's, where check_settings() reads them.

// Light paths per frame: S x M.
inline uint64_t light_paths(const RenderSettings& s) {
  return uint64_t(s.interleave) * uint64_t(s.interleave) * uint64_t(s.paths_per_set);
}
// The most VPLs a frame can hold: every path at full length.
inline uint64_t max_vpls(const RenderSettings& s) { return light_paths(s) * uint64_t(depth_limit(s.light_depth) + 1); }
// Bytes a VPL costs lightcuts at most: the VPL, its leaf, two tree nodes and build scratch.
uint64_t bytes_per_vpl();

// Mirrors and glass followed from the camera (the VPL methods' limit).
inline int specular_depth(const RenderSettings& s) { return depth_limit(s.specular_depth); }

// "" when the worst-case VPL count fits in `memory_bytes`, else why not.
std::string memory_error(const RenderSettings& s, uint64_t memory_bytes);

}  // namespace igi::lightcuts
