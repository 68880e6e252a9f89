// The surfaces a frame's pixels show (core/pixel_surface.h), which the
// master's reprojection carries a pixel's history by: the first hit of the
// ray through the pixel's centre, its normal towards the camera, and whether
// its colour changes with the view.
#include <gtest/gtest.h>

#include "core/camera_front_end.h"
#include "core/parallel.h"
#include "core/pixel_surface.h"
#include "core/tiling.h"
#include "render/frame_job.h"
#include "scene/builtin_scenes.h"
#include "support/render_fixture.h"

namespace igi {
namespace {

constexpr int kWidth = 32, kHeight = 24;

std::vector<PixelSurface> trace(const test::Prepared& scene, const FrameSetup& frame, const TileJob& tile) {
  std::vector<PixelSurface> out(size_t(tile.w) * size_t(tile.h));
  EXPECT_EQ(trace_pixel_surfaces(*scene.accel, frame, 1, tile, out), out.size()) << "one ray a pixel";
  return out;
}

std::vector<PixelSurface> trace_image(const test::Prepared& scene, const FrameSetup& frame) {
  return trace(scene, frame, TileJob{0, 0, frame.width, frame.height, 0});
}

size_t view_dependent(const std::vector<PixelSurface>& surfaces) {
  return size_t(std::count_if(surfaces.begin(), surfaces.end(),
                              [](const PixelSurface& s) { return s.flags == PixelSurface::kViewDependent; }));
}

TEST(PixelSurface, TheCentrePixelSeesTheFirstHitWithItsNormalTowardsTheCamera) {
  const test::Prepared scene(make_builtin_scene("cornell"));
  const FrameSetup frame = scene.frame(kWidth, kHeight);
  const std::vector<PixelSurface> surfaces = trace_image(scene, frame);
  const PixelSurface& centre = surfaces[size_t(kHeight / 2) * kWidth + kWidth / 2];
  const Ray ray = CameraFrontEnd(frame).ray(kWidth / 2 + 0.5f, kHeight / 2 + 0.5f);
  Hit hit;
  ASSERT_TRUE(scene.accel->intersect(ray, hit));
  EXPECT_GT(centre.depth, 0.0f);
  EXPECT_EQ(centre.depth, hit.t);
  const glm::vec3 normal = glm::vec3(centre.normal[0], centre.normal[1], centre.normal[2]) / 127.0f;
  EXPECT_NEAR(glm::length(normal), 1.0f, 0.02f);
  EXPECT_GT(glm::dot(normal, -ray.direction), 0.0f) << "the normal faces the camera";
  EXPECT_EQ(view_dependent(surfaces), 0u) << "the Cornell box is diffuse throughout";
  for (const PixelSurface& s : surfaces)  // the box, or past its open side's edge: nothing at all
    EXPECT_TRUE(s.depth > 0.0f ? s.normal[0] || s.normal[1] || s.normal[2] : s == PixelSurface{});
}

// A tile's surfaces are its interior's, at its place in the image.
TEST(PixelSurface, ATileTracesItsOwnPixels) {
  const test::Prepared scene(make_builtin_scene("cornell"));
  const FrameSetup frame = scene.frame(kWidth, kHeight);
  const std::vector<PixelSurface> image = trace_image(scene, frame);
  const TileJob tile{8, 4, 16, 12, 2};
  const std::vector<PixelSurface> surfaces = trace(scene, frame, tile);
  for (int y = 0; y < tile.h; ++y)
    for (int x = 0; x < tile.w; ++x)
      ASSERT_EQ(surfaces[size_t(y) * tile.w + x], image[size_t(tile.y + y) * kWidth + tile.x + x]) << x << ", " << y;
  std::vector<PixelSurface> wrong(10);
  EXPECT_THROW(trace_pixel_surfaces(*scene.accel, frame, 1, tile, wrong), std::invalid_argument);
}

// The glossy floor (GGX metal, alpha 0.2) and the mirror and glass are view-dependent, the walls are not.
TEST(PixelSurface, GlossyMirrorAndGlassPixelsAreViewDependent) {
  for (const char* name : {"glossy", "glass"}) {
    const test::Prepared scene(make_builtin_scene(name));
    const std::vector<PixelSurface> surfaces = trace_image(scene, scene.frame(kWidth, kHeight));
    EXPECT_GT(view_dependent(surfaces), 0u) << name;
    EXPECT_LT(view_dependent(surfaces), surfaces.size()) << name;
  }
}

// glTF's metallic-roughness material: a rough one (alpha = roughness^2 at
// least kViewDependentAlpha: Sponza's stone) carries its history as Lambert
// does, a smoother one, dielectric or metal, does not.
TEST(PixelSurface, RoughMetallicRoughnessCarriesItsHistorySmoothDoesNot) {
  for (const float metallic : {0.0f, 1.0f})
    for (const float roughness : {1.0f, 0.75f, 0.6f, 0.3f}) {
      Scene cornell = make_builtin_scene("cornell");
      for (Material& m : cornell.materials) {
        m.type = MaterialType::MetallicRoughness;
        m.metallic = metallic;
        m.roughness = roughness;
        m.alpha = roughness * roughness;
      }
      const test::Prepared scene(std::move(cornell));
      const std::vector<PixelSurface> surfaces = trace_image(scene, scene.frame(kWidth, kHeight));
      const size_t seen = size_t(std::count_if(surfaces.begin(), surfaces.end(),
                                               [](const PixelSurface& s) { return s.depth > 0.0f; }));
      ASSERT_GT(seen, surfaces.size() / 2);
      EXPECT_EQ(view_dependent(surfaces), roughness * roughness < kViewDependentAlpha ? seen : 0u)
          << "metallic " << metallic << ", roughness " << roughness;
    }
}

// IR and IGI give a frame's surfaces from their G-buffer's sub-sample 0
// (core/gbuffer.h): the rays a pass of their own would trace, so the same
// surfaces bit for bit, with and without anti-aliasing (sub-sample 0 off the
// pixel's centre), with light on a lattice (the window's sharp previews),
// through glass (the first hit, not the chain's end), in tiles of any size
// with their filter border; and the pixels are those of a frame without them.
TEST(PixelSurface, IgisOwnCameraRaysGiveTheSurfacesAPassOfTheirOwnWould) {
  FlushToZeroScope flush_to_zero;  // as on every render thread
  for (const char* name : {"cornell", "glass"}) {
    const test::Prepared scene(make_builtin_scene(name));
    for (const int aa : {1, 4})
      for (const int divisor : {1, 3}) {
        RenderSettings settings = test::vpl_settings(MethodKind::Igi, 4, 0.1f, true, 0, aa);
        settings.light_divisor = divisor;
        FrameSetup frame = scene.frame(kWidth, kHeight, 5);
        frame.jitter_x = 0.3f, frame.jitter_y = 0.8f;  // a progressive pass's
        FrameJob plain(scene.context(), settings), with(scene.context(), settings);
        plain.begin(frame);
        frame.want_surfaces = true;
        with.begin(frame);
        for (const int size : {8, 13})
          for (const TileJob& tile : make_tiles(kWidth, kHeight, size, size, plain.border())) {
            const RenderedTile got = with.render(tile);
            std::vector<PixelSurface> own(size_t(tile.w) * size_t(tile.h));
            trace_pixel_surfaces(*scene.accel, frame, aa, tile, own);
            const std::string what = std::string(name) + ", aa " + std::to_string(aa) + ", light 1/" +
                                     std::to_string(divisor) + ", tile at " + std::to_string(tile.x) + ", " +
                                     std::to_string(tile.y);
            ASSERT_TRUE(got.surfaces == own) << what;
            EXPECT_TRUE(got.pixels == plain.render(tile).pixels) << what;
          }
        if (aa == 4) {  // sub-sample 0 is not the centre: the surfaces' offset says where it is
          const glm::vec2 offset = surface_film_offset(frame, aa);
          EXPECT_EQ(offset, glm::vec2(0.15f, 0.4f)) << "cell (0, 0) of the 2 x 2 grid at the jitter";
        }
      }
  }
}

TEST(PixelSurface, ARayThatLeavesTheSceneHasNoSurface) {
  const test::Prepared scene(make_builtin_scene("cornell"));
  FrameSetup frame = scene.frame(kWidth, kHeight);
  frame.camera.forward = -frame.camera.forward;  // out of the box's open side
  for (const PixelSurface& s : trace_image(scene, frame)) ASSERT_EQ(s, PixelSurface{});
}

}  // namespace
}  // namespace igi
