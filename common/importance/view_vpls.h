#pragma once
// The VPL sets of one frame for ir and igi, with the view's say in them:
//  - neither option: light paths from lights chosen by power (vpl/vpl_generator.h);
//  - --importance N: light paths from lights chosen by their estimated share
//    of the image (importance/light_importance.h);
//  - --bidir K: each set resampled from light-path and camera-path candidates
//    (importance/bidirectional.h), its light paths chosen either way.
// A pure function of scene, settings and frame setup (camera, image size,
// seed): every worker computes the same sets, and their hash covers the light
// probabilities too.
#include "methods/method.h"
#include "render/frame.h"
#include "vpl/vpl.h"

namespace igi::importance {

// `rays` counts what the estimate and the candidates traced (not the light paths).
VplSets generate_view_vpls(const SceneContext& context, const RenderSettings& settings, const FrameSetup& frame,
                           RayCounts& rays);

}  // namespace igi::importance
