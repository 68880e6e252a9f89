#pragma once
// The VPL sets of one frame for ir and igi, with the view's say in them:
//  - neither option: light paths from lights chosen by power (vpl/vpl_generator.h);
//  - --importance N: light paths from lights chosen by their estimated share
//    of the image (importance/light_importance.h);
//  - --light-guide (the default): a sun's and the sky's paths start where
//    pilots found they reach the view (importance/view_guide.h);
//  - --bidir K: each set resampled from light-path and camera-path candidates
//    (importance/bidirectional.h), its light paths chosen either way;
//  - --bidir auto (the default): 2 M light and camera paths and K = 2 M
//    where the view sees few of the light paths' VPLs, else light paths
//    alone (choose_bidir below).
// A pure function of scene, settings and frame setup (camera, image size,
// seed): every worker computes the same sets, and their hash covers the light
// probabilities and the guide too.
#include "core/frame.h"
#include "core/method.h"
#include "core/vpl.h"
#include "vpl/vpl_generator.h"

namespace igi::importance {

// --bidir auto. Where the light paths end far from what the camera sees
// (the corridor scene: its lamp two turns away), each point of the view sees
// few VPLs, and those make blotches and a mean that wanders from pass to
// pass; bidirectional IR puts VPLs where the camera looks. A probe measures
// it: kProbePaths light paths, their lights chosen as the frame chooses them
// (by power or by importance) but with a seed of their own, and kViewProbes
// camera points (one net over the film, also with its own seed), so the
// passes of a view decide alike (with light importance the lights' choice is
// the frame's own estimate, so a view near the threshold may not). Where a
// point sees on average under
// kBidirReach of those VPLs and punctual lights (in front of both,
// unoccluded), each set starts 2 M light paths and 2 M camera paths and
// keeps 2 M VPLs (M = --vpl-paths; at least --aa): about the cost of the M light paths'
// own VPLs there, and more of the paths that do reach the view. Measured at
// the suite's cameras: the corridor 7 %; rooms and rooms-10 43-48 % (by
// power 6 % and 0 %: there auto turns it on too); the Cornell box, the lit
// corner, glossy and glass 55-75 %. Elsewhere light paths alone are sharper
// at one pass (tests/bench/history/RESULTS-to-2026-12-05.md, "Bidirectional IR by view"). The
// probe costs up to kViewProbes x (about 5 kProbePaths) shadow rays a frame.
inline constexpr uint32_t kViewProbes = 64;
inline constexpr int kProbePaths = 32;
inline constexpr float kBidirReach = 0.2f;
// Past this many light paths a set, auto stays off: bidirectional IR's cost
// grows as M^2 (every candidate against every camera path).
inline constexpr int kMaxAutoBidirPaths = 256;

// The share of the probe's VPLs and punctual lights a point of the view
// sees, averaged over the probe's camera points; 1 when no probe ray finds
// a surface. `rays` counts the probe's rays.
float light_path_reach(const SceneContext& context, const RenderSettings& settings, const FrameSetup& frame,
                       const LightPathOptions& light_paths, RayCounts& rays);
// The settings a frame's sets are made with: `settings` unless bidir_vpls
// is kBidirAuto; then, by the probe, bidirectional IR off (0), or on with
// 2 M light paths, 2 M camera paths and 2 M VPLs kept a set (ir and igi;
// other methods: off).
RenderSettings choose_bidir(const SceneContext& context, const RenderSettings& settings, const FrameSetup& frame,
                            const LightPathOptions& light_paths, RayCounts& rays);

// `rays` counts what the estimate and the candidates traced (not the light paths).
VplSets generate_view_vpls(const SceneContext& context, const RenderSettings& settings, const FrameSetup& frame,
                           RayCounts& rays);

}  // namespace igi::importance
