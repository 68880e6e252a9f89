#pragma once
// The master's frames being assembled: each open frame's buffer (from the
// pool, in the session's pixel format), its pixel surfaces when it wants
// them, and its record. A worker's tile and the master's own are pasted the
// same way (paste()): pixels straight from the received bytes into the
// buffer, row by row, checked as they go. Which results count is not this
// room's: the scheduler and the referee say so; this only holds pixels.
//
// Single-threaded: the session thread owns it. A completed frame's buffer
// goes back to the pool when its last copy goes, on whatever thread.
#include <chrono>
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <tuple>
#include <vector>

#include <glm/vec2.hpp>

#include "core/frame.h"
#include "core/settings.h"
#include "frames/frame_buffer_pool.h"
#include "protocol/codec.h"

namespace igi {

struct PeerStats {
  uint64_t tiles = 0;
  double busy_seconds = 0.0;
  uint64_t bytes_in = 0, bytes_out = 0;
};

// Which worker's result filled a tile (the window's tile overlay).
struct TileSource {
  TileJob tile;
  uint32_t worker = 0;  // the N of its peer name "worker-N"
};

struct FrameRecord {
  uint64_t frame_id = 0;
  double seconds = 0.0;  // from its first job out to its last result in
  double completed_at = 0.0;  // seconds from the session's start to its last result (frames overlap: rates from these)
  uint64_t tiles = 0;    // results whose pixels were used
  RayCounts rays;
  uint64_t nonfinite_pixels = 0;  // zeroed by workers (they send finite pixels only)
  std::map<std::string, PeerStats> workers;  // by peer name; only with detailed statistics
  std::vector<TileSource> tile_sources;      // one per used result; only with record_tile_sources()
  // Session totals when the frame completed.
  uint64_t reissued = 0, duplicated = 0, late_dropped = 0, verified = 0, failed_results = 0, quarantined = 0;
  uint64_t own_tiles = 0;  // jobs the master rendered itself
};

struct CompletedFrame {
  FrameSetup setup;
  std::shared_ptr<FrameBuffer> pixels;  // back to the session's pool when the last copy goes
  FrameRecord record;
  std::vector<PixelSurface> surfaces;  // one a pixel when setup.want_surfaces, else none
  glm::vec2 surface_offset{0.5f};      // where in its pixel each surface's ray passes (core/pixel_surface.h)
};

class FrameAssembly {
 public:
  using Clock = std::chrono::steady_clock;
  struct OpenFrame {
    FrameSetup setup;
    RenderSettings settings;
    std::shared_ptr<FrameBuffer> pixels;
    FrameRecord record;
    std::vector<PixelSurface> surfaces;
    std::optional<Clock::time_point> started;  // its first job out
  };

  // Frames cut into tiles of `tile_size` (frame_tile_size(): larger with lattice light) and their filter border.
  FrameAssembly(PixelFormat format, int tile_size) : format_(format), tile_size_(tile_size) {}
  PixelFormat pixel_format() const { return format_; }

  // Opens the frame; returns its tiles (cut once per size and border).
  const std::vector<TileJob>& open(const FrameSetup& frame, const RenderSettings& settings);
  bool cancel(uint64_t frame_id) { return frames_.erase(frame_id) > 0; }
  OpenFrame* find(uint64_t frame_id);
  std::vector<uint64_t> ids() const;  // oldest first

  // A result's pixels (and surfaces, where its frame wants them) into its
  // open frame; an error says why they cannot be (nothing is counted then).
  std::string paste(const protocol::TileResultView& view);
  // A pasted result counts in its frame's record: tiles, rays, non-finite pixels.
  static void count(OpenFrame& frame, const protocol::TileResult& result);
  // The frame, taken out: its record's times measured from its first job
  // and from `began` (the session's start).
  CompletedFrame complete(uint64_t frame_id, Clock::time_point began);

 private:
  PixelFormat format_;
  int tile_size_;
  FrameBufferPool pool_;
  std::map<uint64_t, OpenFrame> frames_;
  std::vector<TileJob> tiles_;                    // the tiles of a frame as tiles_cut_ says
  std::tuple<int, int, int, int> tiles_cut_{0, 0, 0, 0};  // width, height, border, tile size of tiles_
};

}  // namespace igi
