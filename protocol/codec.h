#pragma once
// Bytes <-> messages. The format (all little-endian):
//   header   u32 magic (kMagic), u16 version (kVersion), u8 type (MessageType), u8 flags (0)
//   payload  the message's fields in declaration order:
//            integers as their width (int as i32), floats as IEEE-754 bits,
//            bools and enums as u8, strings and byte arrays as u32 length + bytes,
//            vectors as u32 count + elements.
//
// decode() is the only way bytes from a peer become a Message: it checks the
// total size, the header, every length before use, every enum and number
// against its range (the limits are in messages.h), and that no bytes trail
// the payload. A decoded message is valid, and encoding it again gives the
// same bytes. encode() does not validate: a message that breaks a limit is
// encoded as it is and rejected by the receiver's decode().
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "protocol/messages.h"
#include "protocol/wire.h"

namespace igi::protocol {

std::vector<uint8_t> encode(const Message& message);

struct DecodeResult {
  std::optional<Message> message;
  std::string error;  // empty on success; otherwise names the message type and field
};

// Never throws on bad bytes, never reads out of bounds, never allocates more
// than the bytes could justify, but for packed blocks: one unpacks to at most its
// tile's pixels (at most a 1024 x 1024 float tile, 12.6 MB, the largest raw
// result a peer may send) or surfaces (8.4 MB), or is refused. A peer speaking another
// protocol version gets "protocol version N, this build speaks M".
DecodeResult decode(std::span<const uint8_t> bytes);

// A TileResult whose pixels stay where they are (the master copies them
// straight from the ZeroMQ frame into its image: protocol/pixels.h).
struct TileResultView {
  TileResult fields;                      // every field but `pixels`, which stays empty
  std::span<const uint8_t> pixel_bytes;   // tile.w * tile.h pixels in fields.pixel_format
  std::vector<uint8_t> storage;           // packed: pixel_bytes unpacked (the view owns them)
  std::span<const uint8_t> surface_bytes; // none, or tile.w * tile.h surfaces (8 bytes each, checked)
  std::vector<uint8_t> surface_storage;   // packed: surface_bytes unpacked

  // Moves keep pixel_bytes and surface_bytes pointing into their storage (a vector's move keeps its
  // buffer); a copy would point into the original's, so there is none.
  TileResultView() = default;
  TileResultView(TileResultView&&) = default;
  TileResultView& operator=(TileResultView&&) = default;
  TileResultView(const TileResultView&) = delete;
  TileResultView& operator=(const TileResultView&) = delete;
};

// The header's type byte says TileResult (nothing else is checked).
bool is_tile_result(std::span<const uint8_t> bytes);
// What a TileResult is looked up by (its frame, job and rectangle), read from
// its header alone, whatever follows: nothing is unpacked, so the master
// finds the job before a result costs it more than these bytes, and a result
// that then fails to decode still sends its job to another worker. nullopt,
// with `error` set, when the header or these fields do not decode.
struct TileResultHead {
  uint64_t frame_id = 0, job_id = 0;
  TileJob tile;
};
std::optional<TileResultHead> tile_result_head(std::span<const uint8_t> bytes, std::string& error);
// Checks everything decode() checks except that the pixels are finite, which
// copy_tile_pixels() checks as it copies them; so a message passes both
// exactly when decode() accepts it, with the same error text otherwise.
// nullopt, with `error` set, when it does not decode (or is not a TileResult).
std::optional<TileResultView> decode_tile_result(std::span<const uint8_t> bytes, std::string& error);

// RenderSettings on the wire: every field once, in its table's order
// (core/settings_table.h), then the one check of them all; the workers' and
// the viewer's messages (master/viewer/display_messages.h) carry them alike.
void write_settings(Writer& w, const RenderSettings& s);
void read_settings(Reader& r, RenderSettings& s);

}  // namespace igi::protocol
