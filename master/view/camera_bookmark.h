#pragma once
// A camera as a small JSON file: the window saves and loads it (bookmarks),
// and igi-render and igi-master --camera FILE start from it.
//   {"position": [x, y, z], "forward": [x, y, z], "up": [x, y, z], "vfov_degrees": 39.3}
#include <string>

#include "scene/scene.h"

namespace igi {

// Throws std::runtime_error naming the file and the field that is wrong.
Camera read_camera_file(const std::string& path);
void write_camera_file(const std::string& path, const Camera& camera);

}  // namespace igi
