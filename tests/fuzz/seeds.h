#pragma once
// Seed inputs of the fuzz targets, made from code rather than checked in, so
// they follow the wire format and the glTF writer as those change.
//   decode: one encoded message of every MessageType, and of every display link message type.
//   scene:  the Cornell box and small hand-made scenes (a textured quad, a
//           spot light with a camera, a directional light), each as .glb and
//           as a self-contained .gltf (buffers and images as data URIs).
// scripts/fuzz.sh writes them with igi-fuzz-seeds; the replay test runs them.
#include <cstdint>
#include <string>
#include <vector>

namespace igi::fuzz {

struct Seed {
  std::string name;  // a file name, e.g. "TileResult.bin", "cornell.glb"
  std::vector<uint8_t> bytes;
};

std::vector<Seed> decode_seeds();
// The display link's messages (master/viewer/display_messages.h), one of every
// type: seeds of the decode target too, which runs both decoders.
std::vector<Seed> display_seeds();
// Writes the scenes through write_gltf under `scratch_dir` (created) and
// returns them packed into single files.
std::vector<Seed> scene_seeds(const std::string& scratch_dir);

}  // namespace igi::fuzz
