#pragma once
// The verdict on a soak run's frames: every frame 0..N-1 on disk, each
// bit-identical to the single-process render of the same frame (tiles are a
// pure function of scene, settings, seed, camera and pixel), and no other
// frame files. A mismatch writes the frame, the reference and their
// difference (x10) under DIR/mismatch/.
#include <memory>
#include <string>
#include <vector>

#include "image/image.h"
#include "view/frame_plan.h"
#include "options/render_options.h"

namespace igi::soak {

std::string frame_file(const std::string& dir, int frame);

struct FrameVerdict {
  int identical = 0;
  std::vector<int> missing;       // no file, or a file that cannot be read
  std::vector<int> differing;
  std::vector<std::string> notes; // one line per problem
};

class ReferenceRenderer {
 public:
  ReferenceRenderer(const RenderOptions& options, const CameraPath& path);
  ~ReferenceRenderer();
  // Frame i as igi-master renders it along `path` (plan_frame in master/view/frame_plan.h).
  Image render(int frame) const;

 private:
  struct Prepared;
  RenderOptions options_;
  CameraPath path_;
  std::unique_ptr<Prepared> prepared_;
};

FrameVerdict check_frames(const std::string& dir, int frames, const ReferenceRenderer& reference);

}  // namespace igi::soak
