#include "render/view_history.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <tuple>

#include "core/parallel.h"
#include "scene/camera_rays.h"

namespace igi {
namespace {

bool same_camera(const Camera& a, const Camera& b) {
  return a.position == b.position && a.forward == b.forward && a.up == b.up && a.vfov == b.vfov;
}

// Film coordinates (pixels) of world points in a camera's image.
struct Projection {
  CameraBasis basis;
  glm::vec3 right, down;  // basis.right and basis.down over their squared lengths
  explicit Projection(const CameraBasis& b)
      : basis(b), right(b.right / glm::dot(b.right, b.right)), down(b.down / glm::dot(b.down, b.down)) {}
  // false behind the camera.
  bool operator()(glm::vec3 point, glm::vec2& film) const {
    const glm::vec3 d = point - basis.origin;
    const float z = glm::dot(d, basis.forward);
    if (!(z > 0.0f)) return false;
    // direction(x, y) = forward + (x - x0) right + (y - y0) down, right and down orthogonal to forward.
    const float inv_z = 1.0f / z;
    film.x = basis.pixel_x0 + glm::dot(d, right) * inv_z;
    film.y = basis.pixel_y0 + glm::dot(d, down) * inv_z;
    return true;
  }
};

}  // namespace

ViewHistory::Upscale ViewHistory::upscale_of(const Image& frame) const {
  if (frame.width <= 0 || frame.height <= 0 || width_ % frame.width != 0 || height_ % frame.height != 0 ||
      width_ / frame.width != height_ / frame.height)
    throw std::invalid_argument("view history: a " + std::to_string(frame.width) + " x " +
                                std::to_string(frame.height) + " frame is not the " + std::to_string(width_) + " x " +
                                std::to_string(height_) + " image over a whole divisor");
  return {width_ / frame.width, frame.width};
}

glm::vec3 surface_normal(const PixelSurface& s) {
  return glm::normalize(glm::vec3(s.normal[0], s.normal[1], s.normal[2]) + glm::vec3(1e-9f));
}

ViewHistory::ViewHistory(int width, int height, int max_history)
    : width_(width), height_(height), max_history_(std::max(1, max_history)) {
  reset();
}

void ViewHistory::Layer::clear(size_t pixels) {
  sum.assign(pixels, glm::dvec3(0.0));
  weight.assign(pixels, 0.0);
  any = false;
}

void ViewHistory::Layer::add(const Image& frame, const Upscale& up, int width, double w) {
  any = true;
  const int height = int(sum.size() / size_t(width));
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const size_t i = size_t(y) * size_t(width) + size_t(x);
      sum[i] += glm::dvec3(frame.pixels[up.at(x, y)]) * w;
      weight[i] += w;
    }
}

void ViewHistory::reset() {
  const size_t pixels = size_t(width_) * height_;
  for (Layer* layer : {&still_, &carried_, &moving_, &preview_}) layer->clear(pixels);
  from_previews_.assign(pixels, 0);
  still_view_ = view_ = View{};
  empty_ = true;
  is_moving_ = false;
  carried_share_ = 1.0;
}

void ViewHistory::add(const Image& frame, std::span<const PixelSurface> surfaces, const Camera& camera,
                      double weight, glm::vec2 surface_offset) {
  const Upscale up = upscale_of(frame);
  if (!surfaces.empty() && surfaces.size() != frame.pixels.size())
    throw std::invalid_argument("view history: surfaces do not match the frame's pixels");
  const View& current = is_moving_ ? view_ : still_view_;
  if (!empty_ && !same_camera(camera, current.camera)) {
    View now{camera, std::move(spare_seen_), up.divisor};
    if (surfaces.empty()) now.seen.clear();
    else seen(surfaces, up, camera, surface_offset, now.seen);
    correspond(still_view_, now, from_still_);
    carry(still_, from_still_, spare_);  // from where it was made, in one step
    std::swap(carried_, spare_);
    if (moving_.any || preview_.any) correspond(view_, now, from_view_);
    for (Layer* layer : {&moving_, &preview_}) {
      carry(*layer, from_view_, spare_);
      std::swap(*layer, spare_);
    }
    spare_seen_ = std::move(view_.seen);  // its buffer, for the next move's
    view_ = std::move(now);
    is_moving_ = true;
    (weight < 1.0 ? preview_ : moving_).add(frame, up, width_, weight);
    const size_t kept = size_t(std::count_if(carried_.weight.begin(), carried_.weight.end(),
                                             [](double w) { return w > 0.0; }));
    carried_share_ = double(kept) / double(carried_.weight.size());
    return;
  }
  if (is_moving_) settle();
  if (up.divisor == 1) {  // a frame at every pixel: what only previews showed starts over from it
    for (size_t i = 0; i < from_previews_.size(); ++i)
      if (from_previews_[i]) {
        still_.sum[i] = glm::dvec3(0.0);
        still_.weight[i] = 0.0;
        from_previews_[i] = 0;
      }
  }
  still_.add(frame, up, width_, weight);
  still_view_.camera = camera;
  // Its surfaces: the first known, or finer ones (the first full frame after previews).
  if (!surfaces.empty() && (still_view_.seen.empty() || up.divisor < still_view_.divisor)) {
    still_view_.divisor = up.divisor;
    seen(surfaces, up, camera, surface_offset, still_view_.seen);
  }
  empty_ = false;
}

std::pair<glm::dvec3, double> ViewHistory::shown(size_t i) const {
  if (!is_moving_) return {still_.sum[i], still_.weight[i]};
  const double w = carried_.weight[i] + moving_.weight[i];
  if (w > 0.0) return {carried_.sum[i] + moving_.sum[i], w};
  return {preview_.sum[i], preview_.weight[i]};
}

void ViewHistory::settle() {
  for (size_t i = 0; i < still_.sum.size(); ++i) {
    std::tie(still_.sum[i], still_.weight[i]) = shown(i);
    from_previews_[i] = carried_.weight[i] + moving_.weight[i] <= 0.0 && preview_.weight[i] > 0.0;
  }
  still_.any = true;
  still_view_ = std::move(view_);
  view_ = View{};
  const size_t pixels = size_t(width_) * height_;
  for (Layer* layer : {&carried_, &moving_, &preview_}) layer->clear(pixels);
  is_moving_ = false;
}

// The point each full-size pixel shows: where its centre's ray meets the
// plane of the surface its frame pixel's ray (through `offset` in it) saw:
// exact on a plane at any divisor. Rows in parallel: each pixel's own
// arithmetic, whichever thread.
void ViewHistory::seen(std::span<const PixelSurface> surfaces, const Upscale& up, const Camera& camera,
                       glm::vec2 offset, std::vector<Seen>& out) const {
  const bool centred = up.divisor == 1 && offset == glm::vec2(0.5f);
  out.assign(size_t(width_) * height_, Seen{});
  const CameraBasis full(camera, width_, height_);
  const CameraBasis frame(camera, width_ / up.divisor, height_ / up.divisor);
  parallel_tasks(height_, [&](int y) {
    for (int x = 0; x < width_; ++x) {
      const PixelSurface& s = surfaces[up.at(x, y)];
      if (s.depth <= 0.0f || (s.flags & PixelSurface::kViewDependent)) continue;
      if (centred) {  // the pixel's own centre ray
        const glm::vec3 ray = glm::normalize(full.direction(float(x) + 0.5f, float(y) + 0.5f));
        out[size_t(y) * width_ + x] = {full.origin + s.depth * ray, surface_normal(s), true};
        continue;
      }
      const glm::vec3 seen_along =
          glm::normalize(frame.direction(float(x / up.divisor) + offset.x, float(y / up.divisor) + offset.y));
      const glm::vec3 hit = frame.origin + s.depth * seen_along, normal = surface_normal(s);
      const glm::vec3 ray = glm::normalize(full.direction(float(x) + 0.5f, float(y) + 0.5f));
      const float along = glm::dot(ray, normal);
      const float t = std::abs(along) > 1e-3f ? glm::dot(hit - full.origin, normal) / along : -1.0f;
      out[size_t(y) * width_ + x] = {t > 0.0f ? full.origin + t * ray : hit, normal, true};
    }
  });
}

void ViewHistory::correspond(const View& before, const View& now, std::vector<int32_t>& source) const {
  source.assign(size_t(width_) * height_, -1);
  if (now.seen.empty() || before.seen.empty()) return;
  const Projection project(CameraBasis(before.camera, width_, height_));
  const float tolerance2 = kPlaneTolerance * kPlaneTolerance;
  parallel_tasks(height_, [&](int y) {
    for (size_t i = size_t(y) * width_; i < size_t(y + 1) * width_; ++i) {
      const Seen& s = now.seen[i];
      glm::vec2 film;
      if (!s.carries || !project(s.point, film)) continue;
      if (!(film.x >= 0.0f && film.y >= 0.0f && film.x < float(width_) && film.y < float(height_))) continue;
      const size_t q = size_t(film.y) * width_ + size_t(film.x);
      const Seen& old = before.seen[q];
      if (!old.carries) continue;
      // The plane test against the distance from the old camera, squared (no root).
      const glm::vec3 from_camera = s.point - project.basis.origin;
      const float off_plane = glm::dot(s.point - old.point, old.normal);
      if (off_plane * off_plane > tolerance2 * glm::dot(from_camera, from_camera)) continue;
      if (glm::dot(s.normal, old.normal) < kNormalCos) continue;
      source[i] = int32_t(q);
    }
  });
}

void ViewHistory::carry(const Layer& from, const std::vector<int32_t>& source, Layer& to) const {
  to.clear(size_t(width_) * height_);
  if (!from.any) return;  // (a layer of no frames: sharp previews leave moving_ so)
  for (size_t i = 0; i < source.size(); ++i) {
    const int32_t q = source[i];
    if (q < 0 || from.weight[size_t(q)] <= 0.0) continue;
    to.any = true;
    to.weight[i] = std::min(from.weight[size_t(q)], double(max_history_));
    to.sum[i] = from.sum[size_t(q)] * (to.weight[i] / from.weight[size_t(q)]);
  }
}

Image ViewHistory::resolve() const {
  Image image(width_, height_);
  for (size_t i = 0; i < image.pixels.size(); ++i)
    if (const auto [sum, weight] = shown(i); weight > 0.0) image.pixels[i] = glm::vec3(sum / weight);
  return image;
}

double ViewHistory::weight() const {
  if (empty_) return 0.0;
  double total = 0.0;
  for (size_t i = 0; i < still_.weight.size(); ++i) total += shown(i).second;
  return total / double(still_.weight.size());
}

}  // namespace igi
