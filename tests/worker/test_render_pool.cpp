// igi-worker's render pool (worker/render_pool.h) in process: a job's result
// is the tile every node renders (render/frame_job.h), frames at different
// poses each see their own scene, a cancelled frame's queued jobs are
// dropped, and a frame this machine cannot hold is refused.
#include <gtest/gtest.h>

#include <poll.h>

#include "core/parallel.h"
#include "protocol/tile_result.h"
#include "render/frame_job.h"
#include "render/scene_state.h"
#include "render_pool.h"
#include "scene/builtin_scenes.h"
#include "support/render_fixture.h"

namespace igi {
namespace {

// Results until `count` have come, or `seconds` have passed.
std::vector<protocol::TileResult> results(RenderPool& pool, size_t count, double seconds = 60.0) {
  std::vector<protocol::TileResult> all;
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  while (all.size() < count && std::chrono::steady_clock::now() < end) {
    pollfd fd{pool.results_fd(), POLLIN, 0};
    poll(&fd, 1, 20);
    for (protocol::TileResult& r : pool.take_results()) all.push_back(std::move(r));
  }
  return all;
}

// What any node renders for the tile: the frame's job made and begun at its
// pose, on a thread with flush-to-zero on, as every render thread has it.
protocol::TileResult expected(SceneState& state, const FrameSetup& frame, const RenderSettings& settings,
                              const protocol::TileJobMsg& job) {
  FlushToZeroScope flush_to_zero;
  state.set_pose(frame.pose);
  FrameJob f(state.context(), settings);
  f.begin(frame);
  RenderedTile t = f.render(job.tile);
  return protocol::make_tile_result(job.frame_id, job.job_id, job.tile, std::move(t.pixels), std::move(t.surfaces),
                                    t.rays, f.state_hash(), PixelFormat::Float32);
}

TEST(RenderPool, AResultIsTheTileEveryNodeRendersAtItsFramesPose) {
  SceneState state(make_builtin_scene("cornell-blob-moving"));  // animated: frames stand at different poses
  const RenderSettings settings = test::vpl_settings(MethodKind::Igi, 4);
  std::vector<FrameSetup> frames;
  for (int i = 0; i < 2; ++i) {
    FrameSetup f = test::camera_frame(state.scene(), 48, 32, 1 + uint32_t(i));
    f.frame_id = uint64_t(i);
    f.pose.time = 0.5 * i;
    f.want_surfaces = i == 1;
    frames.push_back(f);
  }
  std::vector<protocol::TileJobMsg> jobs;
  for (const FrameSetup& f : frames)
    for (const TileJob& t : make_tiles(f.width, f.height, 16, 16, tile_border(settings)))
      jobs.push_back({f.frame_id, jobs.size(), t});
  std::vector<protocol::TileResult> got;
  {
    RenderPool pool(state, PixelFormat::Float32, 2);
    for (const FrameSetup& f : frames) pool.add_frame(f, settings);
    for (const protocol::TileJobMsg& j : jobs) pool.add_job(j);  // both frames' jobs interleave on two threads
    got = results(pool, jobs.size());
    EXPECT_EQ(pool.failure(), "");
  }
  ASSERT_EQ(got.size(), jobs.size());
  for (const protocol::TileResult& r : got) {
    const protocol::TileJobMsg& job = jobs.at(r.job_id);
    const protocol::TileResult want = expected(state, frames.at(job.frame_id), settings, job);
    EXPECT_EQ(r.frame_state_hash, want.frame_state_hash) << "job " << r.job_id;
    ASSERT_EQ(r.pixels.size(), want.pixels.size());
    EXPECT_TRUE(std::equal(r.pixels.begin(), r.pixels.end(), want.pixels.begin())) << "job " << r.job_id;
    EXPECT_EQ(r.surfaces.size(), job.frame_id == 1 ? r.pixels.size() : 0u);
    EXPECT_GE(r.render_seconds, 0.0f);
  }
  EXPECT_NE(expected(state, frames[0], settings, jobs[0]).frame_state_hash,
            expected(state, frames[1], settings, jobs.back()).frame_state_hash)
      << "two poses, two seeds: the frames' VPL sets differ";
}

TEST(RenderPool, ACancelledFramesQueuedJobsAreDroppedAndJobsOfUnknownFramesIgnored) {
  SceneState state(make_builtin_scene("cornell"));
  const RenderSettings settings = test::vpl_settings(MethodKind::Igi, 32);
  FrameSetup f = test::camera_frame(state.scene(), 64, 64);
  RenderPool pool(state, PixelFormat::Float16, 1);
  pool.add_frame(f, settings);
  const std::vector<TileJob> tiles = make_tiles(64, 64, 8, 8, tile_border(settings));
  for (size_t i = 0; i < tiles.size(); ++i) pool.add_job({0, i, tiles[i]});
  pool.cancel_frame(0);
  pool.add_job({7, 999, tiles[0]});  // a frame it was never told about
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  const std::vector<protocol::TileResult> got = results(pool, tiles.size(), 0.5);
  EXPECT_LE(got.size(), 2u) << "only a tile already rendering when the cancel came, of " << tiles.size();
  for (const protocol::TileResult& r : got) EXPECT_EQ(r.pixel_format, PixelFormat::Float16);
  EXPECT_EQ(pool.failure(), "");
}

TEST(RenderPool, AFrameThisMachineCannotHoldIsRefusedBeforeAnyJob) {
  SceneState state(make_builtin_scene("cornell"));
  RenderPool pool(state, PixelFormat::Float32, 1, /*memory_bytes=*/64 << 10);
  RenderSettings settings = test::vpl_settings(MethodKind::Igi, 4);
  settings.caustics = true;  // a photon map past 64 KiB
  settings.caustic_photons = 1 << 20;
  EXPECT_THROW(pool.add_frame(test::camera_frame(state.scene(), 32, 32), settings), std::invalid_argument);
  settings.caustics = false;
  settings.aa_samples = 8;  // no square: refused by the one check
  EXPECT_THROW(pool.add_frame(test::camera_frame(state.scene(), 32, 32), settings), std::invalid_argument);
}

}  // namespace
}  // namespace igi
