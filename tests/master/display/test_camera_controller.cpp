// The window's camera: looking turns, moving translates, reset returns home,
// and every change marks accumulated frames stale.
#include <gtest/gtest.h>

#include "display/camera_controller.h"

namespace igi {
namespace {

Camera home() {
  Camera c;
  c.position = {0, 1, 5};
  c.forward = {0, 0, -1};
  c.up = {0, 1, 0};
  return c;
}

TEST(CameraController, MovingForwardFollowsTheViewDirection) {
  CameraController c(home(), 2.0f);
  const uint64_t g = c.generation();
  c.move(1, 0, 0, 0.5f);
  EXPECT_NEAR(c.camera().position.z, 4.0f, 1e-5f);
  EXPECT_NE(c.generation(), g);
  c.move(0, 1, 0, 0.5f);  // right of -z with +y up is +x
  EXPECT_NEAR(c.camera().position.x, 1.0f, 1e-5f);
}

TEST(CameraController, LookingTurnsAndResetReturnsHome) {
  CameraController c(home(), 1.0f);
  c.look(100.0f, 0.0f);  // drag right: turn right
  EXPECT_GT(c.camera().forward.x, 0.1f);
  EXPECT_NEAR(glm::length(c.camera().forward), 1.0f, 1e-5f);
  c.look(0.0f, 10000.0f);  // pitch is limited short of straight down
  EXPECT_GT(c.camera().forward.y, -1.0f);
  c.reset();
  EXPECT_EQ(c.camera().position, home().position);
  EXPECT_NEAR(c.camera().forward.z, -1.0f, 1e-6f);
}

// An animated camera: followed until the user moves it, from where it was
// shown; reset goes back to following, lights moved do not stop it.
TEST(CameraController, FollowsAnAnimatedCameraUntilTheUserPlacesIt) {
  CameraController c(home(), 1.0f);
  Camera flying = home();
  flying.position = glm::vec3(2.0f, 1.0f, 4.0f);
  const uint64_t g = c.generation();
  c.move_lights(1, 0, 0, 0.5f);
  c.follow(flying);
  EXPECT_EQ(c.camera().position, flying.position);
  EXPECT_FALSE(c.placed());
  EXPECT_NE(c.generation(), g) << "the lights moved";
  const uint64_t followed = c.generation();
  c.follow(home());
  EXPECT_EQ(c.generation(), followed) << "following is not a change: the frames carry the animation's camera";
  c.follow(flying);
  c.move(1, 0, 0, 0.5f);  // from the view shown
  EXPECT_TRUE(c.placed());
  EXPECT_NEAR(c.camera().position.z, 3.5f, 1e-5f);
  c.follow(home());
  EXPECT_NEAR(c.camera().position.z, 3.5f, 1e-5f) << "placed: no longer follows";
  c.reset();
  EXPECT_FALSE(c.placed());
  EXPECT_EQ(c.camera().position, flying.position) << "home is where it last followed to";
  c.hold();
  EXPECT_TRUE(c.placed());
}

TEST(CameraController, NoInputChangesNothing) {
  CameraController c(home(), 1.0f);
  const uint64_t g = c.generation();
  c.move(0, 0, 0, 1.0f);
  c.look(0, 0);
  EXPECT_EQ(c.generation(), g);
}

}  // namespace
}  // namespace igi
