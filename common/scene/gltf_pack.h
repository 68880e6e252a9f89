#pragma once
// A scene as one file for workers: a .gltf whose buffers or images are files
// beside it (what --export-gltf writes) is packed into one .glb in memory, so
// a worker in another folder or on another machine gets the whole scene. The
// packed file holds the same bytes in one BIN chunk: the same accessors, the
// same encoded images, so it loads as the same Scene. Only the images some
// material's texture reads are packed (Sponza names DDS copies of its
// textures that no material reads once the PNGs are, and that are not there);
// every other image becomes an empty placeholder, keeping the indices.
// Extensions the master was told to ignore are left out of the file
// (gltf_json.h strip_extensions), so workers read it as the master does.
#include <cstdint>
#include <string>
#include <vector>

namespace igi {

struct SceneFile {
  std::string name;            // the file name workers are told: the scene's own, or STEM.glb when packed
  std::vector<uint8_t> bytes;  // what they load
  bool packed = false;
};

// The scene file's bytes; packed when it is a .gltf with external buffers or
// images, converted when it is an .obj (scene/obj_loader.h). The external files must lie in the scene's folder, as the loader
// asks. Throws SceneError naming the file that cannot be read.
SceneFile scene_file_for_workers(const std::string& path, const std::vector<std::string>& ignored_extensions = {});

}  // namespace igi
