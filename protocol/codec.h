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

namespace igi::protocol {

std::vector<uint8_t> encode(const Message& message);

struct DecodeResult {
  std::optional<Message> message;
  std::string error;  // empty on success; otherwise names the message type and field
};

// Never throws on bad bytes, never reads out of bounds, never allocates more
// than the bytes could justify. A peer speaking another protocol version gets
// "protocol version N, this build speaks M".
DecodeResult decode(std::span<const uint8_t> bytes);

}  // namespace igi::protocol
