#pragma once
// What frame i of an igi-master run is: its camera (along --camera-path),
// seed, samples and sub-pixel position. One function, so that a test can
// render the very same frames in one process (tests/soak).
#include "core/frame.h"
#include "options/render_options.h"
#include "scene/scene.h"

namespace igi {

// --camera-path: where frame i's camera stands. Both paths turn the camera
// about the vertical axis through a pivot on its line of sight: the point of
// that line nearest the scene's centre (or the camera itself when the centre
// is behind it), so the camera keeps its distance and keeps looking at the pivot.
struct CameraPath {
  enum class Kind { None, Orbit, Swing };
  Kind kind = Kind::None;
  // Orbit: degrees a frame; 0 = one full turn over `frames` (a turntable, for a
  // scene seen from outside).
  double orbit_step_degrees = 0.0;
  // Swing: the camera swings this many degrees to either side and back over
  // `frames` (for a scene seen through an opening, such as the Cornell box).
  double swing_degrees = 20.0;
  int frames = 1;  // the whole run's frames: --first-frame + --frames, so a resumed run stands where the full one did
};

// The angle of frame i along the path, in radians (0 for Kind::None).
double camera_path_angle(const CameraPath& path, int i);

// camera_path: as above. progressive: frame i is pass i of one estimate,
// exactly as igi-render's passes: ir/igi take seed + i
// and sub-pixel position sample_2d(i, 0, seed) (pass 0 included, so the
// positions are one stratified set); pt keeps the seed and takes samples
// [i x spp, (i + 1) x spp) of its sequence. An animated scene's frame i
// stands at render.time + i x render.time_step (wrapped with render.loop),
// and is never progressive: every frame is a whole estimate of its own time.
FrameSetup plan_frame(const RenderOptions& render, const CameraPath& camera_path, const Scene& scene, int i,
                      bool progressive);

}  // namespace igi
