#pragma once
// Scenes that need no file, selectable by name on every command line.
#include <functional>
#include <string>
#include <vector>

#include "scene/scene.h"

namespace igi {

// The Cornell box with its published geometry, camera and reflectances
// (Cornell University Program of Computer Graphics), converted to metres.
Scene make_cornell_box();
// A closed sphere seen from inside: every surface diffuse with `albedo` and
// emitting `radiance` towards the centre. Exact answer: radiance / (1 - albedo).
Scene make_furnace(float albedo, float radiance);

// The Cornell box with the two blocks replaced by a finely tessellated bumpy
// sphere of about `triangles` triangles (for throughput measurements).
Scene make_cornell_blob(int triangles);

// Animated (scene/animation.h), for dynamic-scene tests and benchmarks:
// cornell-blob with the blob swaying along x (2 s period); and the "large"
// scene of about 10^6 triangles with a small ball (2 300 triangles) swaying
// through it. The static geometry is the same as in their static versions.
Scene make_cornell_blob_moving(int triangles);
Scene make_large_moving(int triangles = 1'050'000);

// Also the accuracy suite of scene/suite_scenes.h: corner, rooms, rooms-N, glossy, large, glass.
std::vector<std::string> builtin_scene_names();
bool is_builtin_scene(const std::string& name);
// Throws SceneError for an unknown name.
Scene make_builtin_scene(const std::string& name);

// Builders shared by the procedural scenes.
uint32_t add_material(Scene& scene, Material material);
// Quad a-b-c-d as two triangles; the front face follows the a->b->c winding.
void add_quad(Scene& scene, glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 d, uint32_t material);
// A sphere of `rings` rings and 2 x rings segments (4 rings (rings - 1)
// triangles, outward-facing), its radius scaled by bump(theta, phi).
void add_bumpy_sphere(Scene& scene, glm::vec3 center, float radius, int rings,
                      const std::function<float(float, float)>& bump, uint32_t material);

}  // namespace igi
