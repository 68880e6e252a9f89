#pragma once
// The image the window shows, accumulated over frames, and how it survives a
// camera move: the master's history, never a worker's (tiles do not change).
//
// Still camera: each frame is added to a running sum per pixel, exactly as
// render/accumulator.h adds passes (the same image, bit for bit).
//
// Moved camera: the history is carried into the new view (reprojection).
// Each pixel's surface (PixelSurface: depth and normal of one camera ray's
// first hit, returned by the workers) gives the point it shows; that point
// is projected into an older view, and the old pixel it lands on is its
// history there when
//   - both pixels show a surface (neither ray left the scene),
//   - the point lies on the old pixel's surface: within kPlaneTolerance of
//     its distance from the plane through the old pixel's point along its
//     normal (a plane, not a depth, so that surfaces seen at a grazing angle
//     pass; SVGF, Schied et al. 2017, scales its depth test by the depth's
//     gradient for the same reason), and the normals agree within
//     kNormalCos: the same surface, not one in front of it,
//   - neither is view-dependent (glossy, mirror, glass: its colour changes
//     with the view, so its history is wrong from anywhere else).
// Every other pixel (disoccluded, off the old image, view-dependent, the sky)
// starts over. A carried pixel keeps its mean and at most `max_history`
// frames of weight, so it is a moving average over at most that many frames
// and nothing lags for long.
//
// Two layers, so that a moving image does not drift: the still image (the
// frames accumulated where the camera last stood still) is carried into each
// new view in one step from where it was made, never from view to view, as
// a nearest-pixel step rounds by up to half a pixel and sixty of them would
// smear every edge; the frames rendered while moving form a second layer,
// carried from each view to the next. Full moving frames (weight 1) are
// averaged with the carried still image; previews (weight < 1,
// frame_budget.h) show only where neither could be carried: they are
// blurred and biased (fewer pixels, no compensation), worse than one full
// frame however many are averaged. When the camera stands still again, what
// the view shows is the still image of the new view, but where it showed
// previews alone: the first frame at every pixel (a full frame, or a sharp
// preview refining after the stop) replaces them there, as their blocks
// averaged in would outweigh a sharp preview's small weight for seconds.
//
// Frames may come at a preview resolution (the full size over a divisor):
// each full-size pixel takes the colour of the preview pixel it lies in, and
// the point where its own centre's ray meets that pixel's surface plane (so
// at the full size too, where the surface's ray passed off the centre).
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include "core/frame.h"
#include "image/image.h"
#include "scene/camera.h"

namespace igi {

class ViewHistory {
 public:
  static constexpr float kPlaneTolerance = 0.01f;  // of the distance from the camera
  static constexpr float kNormalCos = 0.9f;

  ViewHistory(int width, int height, int max_history);

  // `frame` (and `surfaces`, row-major, one per pixel, or none) at the full
  // size or the full size over a whole divisor, counting `weight` frames
  // (a preview's is less than 1: frame_budget.h). Without surfaces a moved
  // camera starts every pixel over. `surface_offset`: where in its pixel
  // each surface's ray passed (core/pixel_surface.h: surface_film_offset).
  void add(const Image& frame, std::span<const PixelSurface> surfaces, const Camera& camera, double weight = 1.0,
           glm::vec2 surface_offset = glm::vec2(0.5f));
  void reset();
  Image resolve() const;

  // Frames behind the image: per pixel, averaged over the image (a still
  // camera's frame count; 0 when empty).
  double weight() const;
  // Of the last add() that moved the camera: the fraction of pixels that
  // carried their history (1 when it did not move).
  double carried() const { return carried_share_; }
  int width() const { return width_; }
  int height() const { return height_; }

 private:
  struct Upscale {  // where a full-size pixel finds its value in a frame `divisor` times smaller
    int divisor, frame_width;
    size_t at(int x, int y) const { return size_t(y / divisor) * size_t(frame_width) + size_t(x / divisor); }
  };
  struct Seen {  // what a full-size pixel shows
    glm::vec3 point{0.0f}, normal{0.0f};
    bool carries = false;  // a surface whose colour does not depend on the view
  };
  // Per-pixel sums and weights of one layer, at full size.
  struct Layer {
    std::vector<glm::dvec3> sum;
    std::vector<double> weight;
    bool any = false;  // some pixel has weight (else carrying it is skipped)
    void clear(size_t pixels);
    void add(const Image& frame, const Upscale& up, int width, double weight);
  };
  // A view: its camera and what its pixels show (empty: not known).
  struct View {
    Camera camera;
    std::vector<Seen> seen;
    int divisor = 0;  // of the frame `seen` came from
  };
  Upscale upscale_of(const Image& frame) const;
  void seen(std::span<const PixelSurface> surfaces, const Upscale& up, const Camera& camera, glm::vec2 offset,
            std::vector<Seen>& out) const;
  // Per pixel of view `now`, the pixel of view `before` whose history it takes (the tests above), or -1.
  void correspond(const View& before, const View& now, std::vector<int32_t>& source) const;
  // `from`, made in the view `source` reads, into `to`: at a capped weight.
  void carry(const Layer& from, const std::vector<int32_t>& source, Layer& to) const;
  void settle();  // the camera stands still again: what the view shows becomes the still image
  // Pixel i's sum and weight as the view shows it.
  std::pair<glm::dvec3, double> shown(size_t i) const;

  int width_, height_, max_history_;
  Layer still_;    // the frames accumulated where the camera last stood still...
  View still_view_;  // ... there
  View view_;      // while moving: the current view, and in it:
  Layer carried_;  // still_ carried in one step
  Layer moving_;   // full frames rendered while moving, carried from view to view
  Layer preview_;  // previews rendered while moving, likewise
  // Pixels the still image holds from previews alone (settle()): the next
  // frame at every pixel (a full frame, or a sharp preview refining after
  // the stop) replaces them, instead of averaging with their blocks.
  std::vector<uint8_t> from_previews_;
  // Buffers kept from frame to frame (a moving frame at 640x480 had
  // allocated 40 MB; with these and the correspondences shared, add() took
  // 20.6-28.7 ms of the window's thread before and 15.2-20.4 after:
  // tests/bench/view_history_bench.cpp): the correspondences of the
  // current view to the still one and to the last, a spare layer and a
  // spare view's surfaces.
  std::vector<int32_t> from_still_, from_view_;
  Layer spare_;
  std::vector<Seen> spare_seen_;
  bool empty_ = true, is_moving_ = false;
  double carried_share_ = 1.0;
};

// A surface's unit normal, decoded.
glm::vec3 surface_normal(const PixelSurface& s);

}  // namespace igi
