#pragma once
// Light paths that find the view: where on the sun's disc, and from which
// part of the sky, light paths start, learned for the frame.
//
// A directional light (and the environment) starts its paths on a disc that
// covers the whole scene. In a room lit through its windows a few percent of
// them enter, so the number of VPLs inside, and with it the room's
// brightness at one pass, swings with the seed (BreakfastRoom: up to 6x).
// Light importance (importance/light_importance.h) chooses which light a path
// starts from, not where on it; this chooses where.
//
// Per frame, for each such light: P pilot paths, their start numbers one
// stratified net over the light's start space (vpl/start_guide.h), walk
// kPilotVertices surfaces each; every VPL a pilot would leave (and the sky's
// directional one) is weighed by the light it gives kPilotLookups of
// kGuideCameraPoints points of the view (camera rays, importance/
// camera_points.h; clamped as pass 0 clamps, one shadow ray each). A pilot's
// value is what its VPLs give the view; a cell's, the mean of its pilots'.
// Paths then start by the density floor + (1 - floor) value / sum (the guide
// divides their power by it), so the paths that reach the view are many and
// light, not few and heavy; a fifth of the paths (the floor) still start
// by the plain rule, so light the pilots missed is never lost.
//
// A light is guided only where the pilots predict that the variance of a
// path's contribution falls at least kMinGuideGain times (in a closed room
// lit from inside, or an open scene, every start reaches the view alike, and
// its paths stay exactly as without a guide). The prediction is noisy where
// the view is lit by a heavy tail: Sponza's sky gave 1.7-6.4 over 16 frame
// seeds, so a bar of 4 guided one frame in eight and the image's brightness
// jumped with the choice; the sunroom's sun gives 45-85.
//
// Everything is a pure function of scene, settings and frame setup (camera,
// image size, seed): every peer builds the same guide, and its hash joins
// the VPL sets'. The pilots' seed is the frame's, so a still view keeps its
// paths; while the camera moves the same pilots and camera points move with
// it, and the warp moves each path's start continuously with the values.
#include <cstdint>

#include "core/frame.h"
#include "core/method.h"
#include "sampling/distribution.h"
#include "vpl/start_guide.h"

namespace igi::importance {

inline constexpr uint32_t kGuideCameraPoints = 256;
inline constexpr int kPilotLookups = 8;    // camera points each pilot VPL is weighed at
inline constexpr int kFirstLookups = 32;   // ... and the first (where the start decides most)
inline constexpr int kPilotVertices = 3;   // surfaces a pilot walks
inline constexpr float kGuideFloor = 0.2f;    // share of paths started by the plain rule
inline constexpr float kNearShare = 0.1f;     // share of paths started near where pilots found the view
inline constexpr int kNearCells = 4;          // how near: coarse cells
inline constexpr float kByValue = 0.25f;      // share of the rest placed by the pilots' values (tiered())
inline constexpr float kMaxGuideReach = 0.25f;  // a light whose pilots reach the view more often starts plainly
inline constexpr float kSureGuideReach = 0.03f;  // ... and one that reaches it less often is guided unchecked
inline constexpr float kMinGuideGain = 16.0f;
inline constexpr uint32_t kCheckPilots = 1024;
inline constexpr size_t kMaxRefinePilots = 8192;  // the second round's pilots, at most

struct GuideReport {
  uint32_t light = 0;
  float reach = 0.0f;  // share of the pilots whose VPLs light the view
  float gain = 1.0f;   // predicted variance of a plain start over a guided one
  bool guided = false;
};

// The guide for the frame's directional lights and environment; `selection`
// chooses lights as the frame does (nullptr: by power), and only lights it
// can choose are piloted. `report` (optional) gets one entry a piloted light.
StartGuide build_view_guide(const SceneContext& context, const RenderSettings& settings, const FrameSetup& frame,
                            RayCounts& rays, std::vector<GuideReport>* report = nullptr);

}  // namespace igi::importance
