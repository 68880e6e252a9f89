#pragma once
// Reads a Wavefront OBJ file and its MTL materials (tinyobjloader) and hands
// it on as glTF: the scene becomes one .glb in memory (gltf_writer.h), which
// igi-render, the master and every worker then load alike, so that an OBJ
// scene is rendered bit for bit the same in one process or on a cluster.
//
// MTL mapping, onto the renderer's four models:
//   d < 1, Tr > 0 or illum 4, 6, 7, 9   -> Glass, ior Ni (1.5 when Ni <= 1),
//                                          tinted by Tf when it is not black
//   Ks brighter than Kd                 -> Conductor, colour Ks, GGX alpha
//                                          sqrt(2 / (Ns + 2)) (Walter et al.'s
//                                          Phong exponent to roughness); a
//                                          Mirror when that is under 0.001
//   otherwise                           -> Diffuse, albedo Kd (Ks beside Kd
//                                          is dropped: no layered material)
//   Ke                                  -> emission, W/(m^2 sr), front face
//   map_Kd                              -> base colour texture (PNG or JPEG,
//                                          sRGB), v flipped to glTF's
// Faces without a material get white Lambertian 0.8. Anything else an MTL
// says (Ka, map_Ks, bump maps, map_d, ...) is reported once by name.
// Textures and MTL files are read only from the OBJ's own folder.
#include <cstdint>
#include <string>
#include <vector>

namespace igi {

// Whether `path` names an OBJ file (.obj, any case).
bool is_obj_file(const std::string& path);

// The OBJ at `path` as .glb bytes. Warnings (features left out) go to
// `warnings`. Throws SceneError naming the file and the reason.
std::vector<uint8_t> obj_as_glb(const std::string& path, std::vector<std::string>* warnings = nullptr);

}  // namespace igi
