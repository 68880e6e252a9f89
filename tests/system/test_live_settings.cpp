// Settings that change between frames (issue 18): each FrameSetup carries its
// frame's settings, so one session with the same workers renders frame 0 with
// one method and frame 1 with another, each bit for bit as one process would,
// and the window's per-tile sources agree with the per-worker tile counts.
#include <chrono>

#include <gtest/gtest.h>

#include "core/pixel_surface.h"
#include "image/metrics.h"
#include "options/master_options.h"
#include "session/master_session.h"
#include "scene/builtin_scenes.h"
#include "scene/load_scene.h"
#include "support/image_compare.h"
#include "support/process.h"
#include "support/render_fixture.h"
#include "support/sanitizers.h"

namespace igi {
namespace {

using Clock = std::chrono::steady_clock;

std::vector<CompletedFrame> render_frames(MasterSession& session, const std::vector<RenderSettings>& settings,
                                          const FrameSetup& frame) {
  for (size_t i = 0; i < settings.size(); ++i) {
    FrameSetup f = frame;
    f.frame_id = i;
    session.add_frame(f, settings[i]);
  }
  std::vector<CompletedFrame> done;
  const auto end = Clock::now() + std::chrono::duration<double>(60 * test::kSlowdown);
  while (done.size() < settings.size() && Clock::now() < end)
    for (CompletedFrame& f : session.pump(20)) done.push_back(std::move(f));
  return done;
}

// One frame in this process, exactly as a worker renders its tiles.
Image render_here(const test::Prepared& scene, const RenderSettings& settings, const FrameSetup& frame) {
  std::unique_ptr<Method> method = make_method(scene.context(), settings);
  method->begin_frame(frame);
  FrameOptions options;
  options.threads = 1;
  options.tile_size = 13;
  RayCounts rays;
  return render_frame(*method, frame, tile_border(settings), options, rays);
}

// A master session on a free port of this host and one igi-worker of 2
// threads; 48x36 frames in 13-pixel tiles, floats on the wire.
struct Cluster {
  const std::string endpoint = "tcp://127.0.0.1:" + std::to_string(test::free_port());
  zmq::context_t context;
  MasterSession session{session_settings(parse_master_options({"--workers", "0", "--listen", endpoint, "--frames",
                                                               "2", "--quiet", "--no-write", "--size", "48x36",
                                                               "--tile", "13", "--pixels", "float"})),
                        make_scene_source("cornell"), context};
  const pid_t worker =
      test::start(std::string(IGI_WORKER_BINARY) + " --connect " + endpoint + " --threads 2 --quiet");
  ~Cluster() { test::stop(worker); }
  // Waits for the worker to join.
  bool joined() {
    const auto end = Clock::now() + std::chrono::duration<double>(30 * test::kSlowdown);
    while (session.worker_count() == 0 && Clock::now() < end) session.pump(20);
    return session.worker_count() == 1;
  }
};

TEST(LiveSettings, EachFrameIsRenderedWithItsOwnSettingsBySameWorkers) {
  Cluster cluster;
  MasterSession& session = cluster.session;
  session.set_detailed_stats(true);
  session.record_tile_sources(true);
  ASSERT_TRUE(cluster.joined());

  // Filter on (tiles with a border) then off, another method and path count: tiles are cut again.
  const RenderSettings a = test::vpl_settings(MethodKind::Igi, 4, 0.1f, true);
  const RenderSettings b = test::vpl_settings(MethodKind::InstantRadiosity, 2, 0.0f, false);
  const test::Prepared scene(load_scene("cornell"));
  const FrameSetup frame = scene.frame(48, 36, 5);
  std::vector<CompletedFrame> done = render_frames(session, {a, b}, frame);
  session.close("test done");
  ASSERT_EQ(done.size(), 2u);

  for (int i = 0; i < 2; ++i) {
    const Image distributed = done[size_t(i)].pixels->to_image();
    const Image local = render_here(scene, i == 0 ? a : b, frame);
    EXPECT_EQ(max_abs_error(distributed, local), 0.0f) << "frame " << i << " differs from its own settings' render";
  }
  EXPECT_GT(max_abs_error(done[0].pixels->to_image(), done[1].pixels->to_image()), 0.01f)
      << "the second frame's settings changed nothing";

  // Every used tile has a source, and the sources count what the per-worker figures count.
  const FrameRecord& r = done[1].record;
  EXPECT_EQ(r.tile_sources.size(), r.tiles);
  ASSERT_EQ(r.workers.size(), 1u);
  EXPECT_EQ(r.workers.begin()->second.tiles, r.tiles);
  const std::vector<PeerView> peers = session.peer_views();
  EXPECT_TRUE(peers.empty()) << "closed: no peers left";
}

// The window's frames while the camera moves (issue 45): a frame the view
// left behind is cancelled and never comes; frames that carry their pixels'
// surfaces have the very pixels of one process, and the surfaces one process traces.
TEST(LiveSettings, ACancelledFrameNeverComesAndSurfacesLeaveThePixelsAlone) {
  Cluster cluster;
  MasterSession& session = cluster.session;
  ASSERT_TRUE(cluster.joined());

  const RenderSettings settings = test::vpl_settings(MethodKind::Igi, 4, 0.1f, true);
  const test::Prepared scene(load_scene("cornell"));
  FrameSetup moving = scene.frame(48, 36, 5), still = scene.frame(48, 36, 6);
  moving.frame_id = 0;
  moving.want_surfaces = true;
  still.frame_id = 1;
  still.want_surfaces = true;
  still.camera.position.x += 0.05f;
  session.add_frame(moving, settings);
  session.pump(0);  // its jobs go out
  session.cancel_frame(0);
  EXPECT_EQ(session.open_frames(), std::vector<uint64_t>{});
  session.add_frame(still, settings);
  std::vector<CompletedFrame> done;
  const auto end = Clock::now() + std::chrono::duration<double>(30 * test::kSlowdown);
  while (done.empty() && Clock::now() < end)
    for (CompletedFrame& f : session.pump(20)) done.push_back(std::move(f));
  session.close("test done");
  ASSERT_EQ(done.size(), 1u);
  EXPECT_EQ(done[0].setup.frame_id, 1u) << "the cancelled frame came after all";
  EXPECT_EQ(max_abs_error(done[0].pixels->to_image(), render_here(scene, settings, still)), 0.0f);
  std::vector<PixelSurface> here(size_t(48) * 36);
  trace_pixel_surfaces(*scene.accel, still, settings.aa_samples, TileJob{0, 0, 48, 36, 0}, here);
  ASSERT_EQ(done[0].surfaces.size(), here.size());
  EXPECT_TRUE(done[0].surfaces == here) << "the surfaces the worker traced differ from this process's";
}

}  // namespace
}  // namespace igi
