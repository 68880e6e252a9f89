#pragma once
// What the glTF loader tells its caller besides the scene: warnings, each
// reported once per feature, and errors that name the file and the element.
//
// One GltfDiagnostics lives for one load_gltf call; the loader's helpers all
// write into it, so a feature met in a thousand primitives warns once.
#include <set>
#include <string>
#include <vector>

#include "scene/scene.h"

namespace igi {

struct GltfDiagnostics {
  std::string file;                   // the path as the caller gave it
  std::vector<std::string> warnings;  // "file: message", in the order met
  std::vector<std::string> notices;   // what was read as the file allows, nothing lost: "file: message"
  std::set<std::string> reported;     // feature keys already warned about or noted

  // Warns about `feature` unless it has been warned about before.
  void warn_once(const std::string& feature, const std::string& message) {
    if (reported.insert(feature).second) warnings.push_back(file + ": " + message);
  }
  void notice_once(const std::string& feature, const std::string& message) {
    if (reported.insert(feature).second) notices.push_back(file + ": " + message);
  }

  // Throws SceneError "file: element: what".
  [[noreturn]] void fail(const std::string& element, const std::string& what) const {
    throw SceneError(file + ": " + element + ": " + what);
  }
};

// World coordinates (metres) beyond +-kMaxCoordinate are an error: squared
// distances and the scene's diagonal must stay finite in float, and float
// resolution out there is a hundred million metres anyway.
inline constexpr double kMaxCoordinate = 1e15;

// "accessors[3]": how glTF paths name an array element in messages.
inline std::string gltf_element(const std::string& array, size_t index) {
  return array + "[" + std::to_string(index) + "]";
}

}  // namespace igi
