#include "frames/frame_assembly.h"

#include <utility>

#include "core/pixel_surface.h"
#include "core/tiling.h"
#include "protocol/pixels.h"

namespace igi {

const std::vector<TileJob>& FrameAssembly::open(const FrameSetup& frame, const RenderSettings& settings) {
  OpenFrame open;
  open.setup = frame;
  open.settings = settings;
  open.pixels = pool_.acquire(frame.width, frame.height, format_);
  open.record.frame_id = frame.frame_id;
  if (frame.want_surfaces) open.surfaces.resize(size_t(frame.width) * size_t(frame.height));
  frames_[frame.frame_id] = std::move(open);
  const int border = tile_border(settings), tile = frame_tile_size(tile_size_, settings);
  if (tiles_.empty() || tiles_cut_ != std::tuple{frame.width, frame.height, border, tile}) {
    tiles_ = make_tiles(frame.width, frame.height, tile, tile, border);
    tiles_cut_ = {frame.width, frame.height, border, tile};
  }
  return tiles_;
}

FrameAssembly::OpenFrame* FrameAssembly::find(uint64_t frame_id) {
  auto it = frames_.find(frame_id);
  return it == frames_.end() ? nullptr : &it->second;
}

std::vector<uint64_t> FrameAssembly::ids() const {
  std::vector<uint64_t> ids;
  for (const auto& entry : frames_) ids.push_back(entry.first);
  return ids;
}

std::string FrameAssembly::paste(const protocol::TileResultView& view) {
  const protocol::TileResult& r = view.fields;
  OpenFrame& frame = frames_.at(r.frame_id);
  if (r.pixel_format != format_)
    return std::string("pixels as ") + pixel_format_name(r.pixel_format) + ", the session asked for " +
           pixel_format_name(format_);
  FrameBuffer& pixels = *frame.pixels;
  if (std::string error = protocol::copy_tile_pixels(view, pixels.pixel(r.tile.x, r.tile.y), pixels.row_bytes());
      !error.empty())
    return error;
  if (!frame.surfaces.empty()) {
    if (view.surface_bytes.empty()) return "no pixel surfaces, which its frame asked for";
    protocol::copy_tile_surfaces(view, &frame.surfaces[size_t(r.tile.y) * size_t(pixels.width) + size_t(r.tile.x)],
                                 size_t(pixels.width));
  }
  return {};
}

void FrameAssembly::count(OpenFrame& frame, const protocol::TileResult& r) {
  ++frame.record.tiles;
  frame.record.rays += r.rays;
  frame.record.nonfinite_pixels += r.nonfinite_pixels;
}

CompletedFrame FrameAssembly::complete(uint64_t frame_id, Clock::time_point began) {
  OpenFrame& f = frames_.at(frame_id);
  f.record.seconds = f.started ? std::chrono::duration<double>(Clock::now() - *f.started).count() : 0.0;
  f.record.completed_at = std::chrono::duration<double>(Clock::now() - began).count();
  CompletedFrame done{f.setup, std::move(f.pixels), std::move(f.record), std::move(f.surfaces),
                      surface_film_offset(f.setup, f.settings.aa_samples)};
  frames_.erase(frame_id);
  return done;
}

}  // namespace igi
