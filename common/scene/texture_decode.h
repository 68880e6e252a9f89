#pragma once
// Image files as textures: PNG and JPEG (what glTF's core allows, decoded by
// stb through tinygltf), and DDS files of BC4 blocks (one channel, as
// MSFT_texture_dds carries the single-channel roughness and metal maps of
// AMD_split_roughnessMetallic). Every size is read from the header and
// checked before anything is decoded, so a small file cannot make the
// decoder allocate gigabytes. A file that fails a check or does not decode
// throws SceneError naming `shown`.
#include <cstddef>
#include <string>

#include "scene/gltf_diagnostics.h"
#include "scene/scene.h"

namespace igi {

// A PNG or JPEG file's bytes as a texture: 8-bit images as bytes (decoded at
// lookup), 16-bit ones as floats. `srgb`: colour (base colour, emission),
// its RGB decoded from sRGB; otherwise data (normals, metallic-roughness),
// read linearly. Alpha is always linear.
Texture decode_texture(const unsigned char* bytes, size_t size, const std::string& shown, const GltfDiagnostics& diag,
                       bool srgb = true);

// Whether the bytes are a DDS file ("DDS " magic).
bool is_dds(const unsigned char* bytes, size_t size);
// A DDS file of BC4 blocks (DXGI_FORMAT_BC4_UNORM, or the "ATI1"/"BC4U"
// four-character codes), its first mip level, as a linear texture whose
// R, G and B all hold the channel. Other DDS formats are an error.
Texture decode_dds_bc4(const unsigned char* bytes, size_t size, const std::string& shown, const GltfDiagnostics& diag);

}  // namespace igi
