#pragma once
// The view's sample points: camera rays through film positions of one
// low-discrepancy sequence, followed through mirrors and glass to the first
// surface that is not specular (as the G-buffer follows them). Both the
// light-importance estimate and the reverse VPLs of bidirectional instant
// radiosity start from them.
//
// Point i goes through film position sample_2d(i, 0, seed) scaled to the
// image: a pure function of (camera, image size, i, seed), so every worker
// traces the same points. Any power-of-two run of consecutive indices is a
// stratified net over the film (Sobol).
#include <cstdint>

#include "core/camera_front_end.h"
#include "core/frame.h"
#include "core/gbuffer.h"
#include "scene/accel.h"

namespace igi::importance {

// Invalid (GSample::valid() false) when the ray leaves the scene or its
// specular chain ends elsewhere.
GSample trace_camera_point(const Accel& accel, const CameraFrontEnd& camera, uint32_t index, uint32_t seed,
                           int specular_depth, RayCounts& rays);

}  // namespace igi::importance
