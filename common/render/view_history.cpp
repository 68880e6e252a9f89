#include "render/view_history.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <tuple>

#include "scene/camera_rays.h"

namespace igi {
namespace {

bool same_camera(const Camera& a, const Camera& b) {
  return a.position == b.position && a.forward == b.forward && a.up == b.up && a.vfov == b.vfov;
}

// Film coordinates (pixels) of a world point in a camera's image; false behind it.
bool project(const CameraBasis& basis, glm::vec3 point, glm::vec2& film) {
  const glm::vec3 d = point - basis.origin;
  const float z = glm::dot(d, basis.forward);
  if (!(z > 0.0f)) return false;
  // direction(x, y) = forward + (x - x0) right + (y - y0) down, right and down orthogonal to forward.
  film.x = basis.pixel_x0 + glm::dot(d, basis.right) / (z * glm::dot(basis.right, basis.right));
  film.y = basis.pixel_y0 + glm::dot(d, basis.down) / (z * glm::dot(basis.down, basis.down));
  return true;
}

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
                      double weight) {
  const Upscale up = upscale_of(frame);
  if (!surfaces.empty() && surfaces.size() != frame.pixels.size())
    throw std::invalid_argument("view history: surfaces do not match the frame's pixels");
  const View& current = is_moving_ ? view_ : still_view_;
  if (!empty_ && !same_camera(camera, current.camera)) {
    View now{camera, surfaces.empty() ? std::vector<Seen>{} : seen(surfaces, up, camera), up.divisor};
    carried_ = carry(still_, still_view_, now);  // from where it was made, in one step
    moving_ = carry(moving_, view_, now);
    preview_ = carry(preview_, view_, now);
    view_ = std::move(now);
    is_moving_ = true;
    (weight < 1.0 ? preview_ : moving_).add(frame, up, width_, weight);
    size_t kept = 0;
    for (size_t i = 0; i < carried_.weight.size(); ++i) kept += carried_.weight[i] > 0.0;
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
  if (!surfaces.empty() && (still_view_.seen.empty() || up.divisor < still_view_.divisor))
    still_view_ = View{camera, seen(surfaces, up, camera), up.divisor};
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
// plane of the surface its frame pixel saw (exact on a plane at any divisor).
std::vector<ViewHistory::Seen> ViewHistory::seen(std::span<const PixelSurface> surfaces, const Upscale& up,
                                                 const Camera& camera) const {
  std::vector<Seen> out(size_t(width_) * height_);
  const CameraBasis full(camera, width_, height_);
  const CameraBasis frame(camera, width_ / up.divisor, height_ / up.divisor);
  for (int y = 0; y < height_; ++y)
    for (int x = 0; x < width_; ++x) {
      const PixelSurface& s = surfaces[up.at(x, y)];
      if (s.depth <= 0.0f || (s.flags & PixelSurface::kViewDependent)) continue;
      const glm::vec3 centre =
          glm::normalize(frame.direction(float(x / up.divisor) + 0.5f, float(y / up.divisor) + 0.5f));
      const glm::vec3 hit = frame.origin + s.depth * centre, normal = surface_normal(s);
      const glm::vec3 ray = glm::normalize(full.direction(float(x) + 0.5f, float(y) + 0.5f));
      const float along = glm::dot(ray, normal);
      const float t = std::abs(along) > 1e-3f ? glm::dot(hit - full.origin, normal) / along : -1.0f;
      out[size_t(y) * width_ + x] = {t > 0.0f ? full.origin + t * ray : hit, normal, true};
    }
  return out;
}

ViewHistory::Layer ViewHistory::carry(const Layer& from, const View& before, const View& now) const {
  Layer to;
  to.clear(size_t(width_) * height_);
  if (now.seen.empty() || before.seen.empty() || !from.any) return to;  // (a layer of no frames: sharp previews leave moving_ so)
  const CameraBasis old_basis(before.camera, width_, height_);
  for (size_t i = 0; i < now.seen.size(); ++i) {
    const Seen& s = now.seen[i];
    glm::vec2 film;
    if (!s.carries || !project(old_basis, s.point, film)) continue;
    const int qx = int(std::floor(film.x)), qy = int(std::floor(film.y));
    if (qx < 0 || qy < 0 || qx >= width_ || qy >= height_) continue;
    const size_t q = size_t(qy) * width_ + qx;
    const Seen& old = before.seen[q];
    if (!old.carries || from.weight[q] <= 0.0) continue;
    const float distance = glm::length(s.point - old_basis.origin);
    if (std::abs(glm::dot(s.point - old.point, old.normal)) > kPlaneTolerance * distance) continue;
    if (glm::dot(s.normal, old.normal) < kNormalCos) continue;
    to.any = true;
    to.weight[i] = std::min(from.weight[q], double(max_history_));
    to.sum[i] = from.sum[q] * (to.weight[i] / from.weight[q]);
  }
  return to;
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
