#pragma once
// Pass k of a progressive estimate, as every renderer takes it: igi-render's
// --spp passes, igi-master's --progressive frames and the window's
// accumulating frames.
//  - pt continues its sample sequence: the same seed, and samples
//    [k n, (k + 1) n) of every pixel (n samples a pass);
//  - ir, igi and lightcuts start a new estimate: seed + k (fresh VPL sets),
//    pass k of the clamp (FrameSetup::sample_begin, core/clamp.h), and the
//    sub-pixel position sample_2d(k, 0, seed), the next point of one
//    stratified 2D set (pass 0 included, so the positions of K passes are one
//    set). A single frame that is no pass keeps pass 0's clamp and no jitter.
// The passes are summed with their sample counts as weights and normalised
// on read-out (render/accumulator.h), so any number of them merge in any order.
#include <cstdint>

#include "core/frame.h"
#include "core/settings.h"

namespace igi {

// `base` (its seed and camera) as pass `pass` of `method`, pt taking `samples_per_pass` samples.
FrameSetup progressive_pass(const FrameSetup& base, MethodKind method, uint32_t pass, uint32_t samples_per_pass);

}  // namespace igi
