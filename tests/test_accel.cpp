// The BVH (scene/accel.h) when Embree cannot do what is asked: every failure
// is an exception naming what could not be built, never a write through the
// null buffer Embree returns; a limit Embree stays within changes no hit.
#include <string>
#include <utility>

#include <gtest/gtest.h>

#include "scene/accel.h"
#include "scene/builtin_scenes.h"

namespace igi {
namespace {

// Embree refuses each allocation past the limit (its memory monitor), as it
// fails one when the machine has no more: with no memory at all the vertex
// buffer comes back null (the instancing bomb's crash), with 4 kB the BVH build fails.
TEST(Accel, EmbreeOutOfMemoryIsAnErrorNotACrash) {
  const Scene scene = make_builtin_scene("cornell");
  const std::pair<size_t, std::string> cases[] = {{1, "embree: cannot allocate the vertices of"},
                                                  {4096, "embree: cannot"}};
  for (const auto& [limit, expected] : cases) {
    try {
      const Accel accel(scene, limit);
      ADD_FAILURE() << "built within " << limit << " bytes";
    } catch (const std::runtime_error& e) {
      const std::string message = e.what();
      EXPECT_NE(message.find(expected), std::string::npos) << message;
      EXPECT_NE(message.find("out of memory"), std::string::npos) << message;
    }
  }
}

TEST(Accel, ALimitEmbreeStaysWithinChangesNoHit) {
  const Scene scene = make_builtin_scene("cornell");
  enable_flush_to_zero();
  const Accel unlimited(scene), limited(scene, size_t(1) << 30);
  Ray ray;
  ray.origin = scene.camera_or_auto().position;
  for (int i = 0; i < 64; ++i) {
    ray.direction = glm::normalize(scene.bounds().center() + glm::vec3(0.01f * float(i - 32), 0.0f, 0.0f) -
                                   ray.origin);
    Hit a, b;
    ASSERT_EQ(unlimited.intersect(ray, a), limited.intersect(ray, b));
    EXPECT_EQ(a.triangle, b.triangle);
    EXPECT_EQ(a.t, b.t);
  }
}

}  // namespace
}  // namespace igi
