#pragma once
// The settings a master's session reads: a dozen of igi-master's options
// (options/master_options.h session_settings() picks them), as plain values.
#include <string>

#include "core/settings.h"
#include "image/frame_buffer.h"

namespace igi {

struct SessionSettings {
  std::string listen = "tcp://127.0.0.1:0";  // where workers connect (--listen)
  RenderSettings settings;           // a frame's unless it names its own; the Welcome's
  int tile_size = 64;                // frames are cut into tiles of this size (--tile)
  PixelFormat pixel_format = PixelFormat::Float16;  // pixels on the wire (--pixels, as the output asks)
  std::string pixel_codec = "raw";   // and their packing: raw, zstd or lz4 (--pixel-codec)
  int credits = 2;                   // a worker's jobs at once, at least (--credits)
  int heartbeat_ms = 250;            // a message to every peer at least this often
  int timeout_ms = 1500;             // a peer silent this long is dead (or as its silences say)
  bool detailed_stats = false;       // per-worker figures in each frame's record (--stats, the window)
  bool quiet = false;                // no log lines but errors and quarantines
  int send_hwm = 0;                  // test hook: ZMQ_SNDHWM per peer; 0: ZeroMQ's default
  int force_duplicates = 0;          // test hook: hand this many jobs to two workers on purpose
};

}  // namespace igi
