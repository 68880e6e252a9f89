#pragma once
// --camera-path, --orbit-step, --swing: what igi-master is asked; view/frame_plan.h plans the frames.

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

}  // namespace igi
