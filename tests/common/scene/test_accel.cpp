// The BVH (scene/accel.h) when Embree cannot do what is asked: every failure
// is an exception naming what could not be built, never a write through the
// null buffer Embree returns; a limit Embree stays within changes no hit.
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

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

// Which faces each kind of ray finds (scene/accel.h): three sheets across the
// x axis, a double-sided one, a single-sided one facing away from the rays
// and an alpha-masked one whose alpha is below its cutoff, each met from
// behind. Camera rays skip the single-sided back face; shadow rays stop there
// whatever their mask (its geometry has no occluded callback); the masked
// sheet lets every ray through.
TEST(Accel, SingleSidedFacesStopShadowRaysOfAnyMaskAndAlphaMasksNone) {
  Scene scene;
  Material plain;
  add_material(scene, plain);
  Material single = plain;
  single.double_sided = false;
  add_material(scene, single);
  Material cut_out = plain;
  cut_out.alpha_mask = true;
  cut_out.base_alpha = 0.0f;
  add_material(scene, cut_out);
  auto sheet = [&](float x, uint32_t material) {  // front face towards -x
    add_quad(scene, {x, -1, -1}, {x, -1, 1}, {x, 1, 1}, {x, 1, -1}, material);
  };
  sheet(3.0f, 1);  // single-sided: the rays (along -x) meet its back
  sheet(2.0f, 2);  // alpha-masked out
  sheet(1.0f, 0);  // double-sided
  enable_flush_to_zero();
  const Accel accel(scene);
  auto ray = [](float from, float to, unsigned mask) {
    return Ray{{from, 0.1f, 0.2f}, {-1.0f, 0.0f, 0.0f}, 0.0f, from - to, mask};
  };
  Hit hit;
  ASSERT_TRUE(accel.intersect(ray(4.0f, -1.0f, kCameraRayMask), hit));
  EXPECT_FLOAT_EQ(hit.t, 3.0f) << "a camera ray passes the single-sided back and the masked sheet";
  ASSERT_TRUE(accel.intersect(ray(4.0f, -1.0f, kOpaqueRayMask), hit));
  EXPECT_FLOAT_EQ(hit.t, 1.0f) << "any other ray stops at the single-sided back";
  for (unsigned mask : {kCameraRayMask, kOpaqueRayMask}) {
    EXPECT_TRUE(accel.occluded(ray(4.0f, 2.5f, mask))) << "mask " << mask;
    EXPECT_FALSE(accel.occluded(ray(2.5f, 1.5f, mask))) << "mask " << mask << ": the alpha-masked sheet";
    EXPECT_TRUE(accel.occluded(ray(1.5f, 0.5f, mask))) << "mask " << mask;
    bool occluded[1];
    const Ray rays[1] = {ray(4.0f, 2.5f, mask)};
    accel.occluded16(rays, occluded);
    EXPECT_TRUE(occluded[0]) << "mask " << mask << ", as a packet";
  }
}

// Shadow rays in a packet (lightcuts' block cuts) answer as one at a time:
// rays from points over the Cornell box's floor to points near its ceiling,
// some through the tall block, in packets of 1 to 16 (lanes left unused).
TEST(Accel, ShadowRaysInAPacketAnswerAsOneAtATime) {
  const Scene scene = make_builtin_scene("cornell");
  enable_flush_to_zero();
  const Accel accel(scene);
  const Bounds box = scene.bounds();
  const glm::vec3 extent = box.upper - box.lower;
  std::vector<Ray> rays;
  for (int i = 0; i < 16 * 9; ++i) {
    // A fixed scatter over the floor and under the ceiling (golden-ratio steps).
    const float u = std::fmod(0.618034f * float(i), 1.0f), v = std::fmod(0.754878f * float(i), 1.0f);
    const glm::vec3 from = box.lower + extent * glm::vec3(0.05f + 0.9f * u, 0.02f, 0.05f + 0.9f * v);
    const glm::vec3 to = box.lower + extent * glm::vec3(0.05f + 0.9f * v, 0.95f, 0.05f + 0.9f * u);
    Ray r;
    r.origin = from;
    r.direction = glm::normalize(to - from);
    r.tnear = 1e-3f;
    r.tfar = glm::length(to - from) * 0.999f;
    rays.push_back(r);
  }
  size_t blocked = 0, at = 0;
  for (size_t size = 1; at < rays.size(); size = size % 16 + 1) {
    const size_t n = std::min(size, rays.size() - at);
    bool packet[16] = {};
    accel.occluded16({rays.data() + at, n}, {packet, n});
    for (size_t i = 0; i < n; ++i) {
      EXPECT_EQ(packet[i], accel.occluded(rays[at + i])) << "ray " << at + i << " in a packet of " << n;
      blocked += packet[i];
    }
    at += n;
  }
  EXPECT_GT(blocked, 0u) << "some rays pass through the blocks";
  EXPECT_LT(blocked, rays.size()) << "some rays are free";
  bool none[1];
  accel.occluded16({}, {none, 0});  // an empty packet traces nothing
  EXPECT_THROW(accel.occluded16({rays.data(), 17}, {none, 1}), std::invalid_argument);
}

}  // namespace
}  // namespace igi
