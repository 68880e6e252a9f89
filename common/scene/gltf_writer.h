#pragma once
// Writes a Scene as glTF 2.0: "name.gltf" (JSON) beside "name.bin" (the
// buffer) and one "name_textureN.png" per texture. load_gltf reads the
// files back to an equivalent Scene: the same triangles in the same order
// when they are grouped by material, the same vertex data, materials,
// lights and camera, to float and 8-bit (texture) precision.
//
// Mapping, the inverse of gltf_materials.h:
//   Diffuse   -> metallic 0, roughness 1
//   Conductor -> metallic 1, roughness sqrt(alpha)
//   Mirror    -> metallic 1, roughness 0
//   Glass     -> KHR_materials_transmission 1 + KHR_materials_ior
//   emission  -> emissiveFactor in [0, 1], KHR_materials_emissive_strength
//                carrying the largest component when it exceeds 1
// Lights are written in glTF's units: point and spot intensity in candela,
// directional in lux, at 683 lm/W (scene/light_units.h).
// Geometry is one mesh with one primitive per material, each with its own
// compacted vertices; lights and the camera are nodes whose rotation turns
// local -Z onto their direction.
#include <cstdint>
#include <string>
#include <vector>

#include "scene/scene.h"

namespace igi {

// Throws SceneError naming the file when it cannot be written, or the
// element when the scene is inconsistent (an index out of range).
void write_gltf(const Scene& scene, const std::string& path);

// The same as one .glb in memory (images embedded), for a scene read from
// another format (scene/obj_loader.h); `name` stands for the file in errors.
std::vector<uint8_t> write_glb_bytes(const Scene& scene, const std::string& name);

}  // namespace igi
