// igi-worker's session (worker/worker_session.h) in process, against a
// master played by a ROUTER socket: it says hello, renders the jobs it is
// given as every node renders them, and ends with the status each ending asks for.
#include <gtest/gtest.h>

#include <future>

#include "build_id.h"
#include "core/parallel.h"
#include "protocol/socket.h"
#include "render/frame_job.h"
#include "render/scene_state.h"
#include "scene/builtin_scenes.h"
#include "support/image_compare.h"
#include "support/process.h"
#include "support/sanitizers.h"
#include "support/render_fixture.h"
#include "worker_session.h"

namespace igi {
namespace {

using Clock = std::chrono::steady_clock;

// A master's socket on a free loopback port, and a worker session dialling it on a thread of its own.
struct Rig {
  zmq::context_t context;
  zmq::socket_t router{context, zmq::socket_type::router};
  std::string endpoint = "tcp://127.0.0.1:" + std::to_string(test::free_port());
  std::future<WorkerExit> exit;
  std::string identity;

  explicit Rig(double give_up_seconds = 30.0, bool bind = true) {
    router.set(zmq::sockopt::linger, 0);
    if (bind) router.bind(endpoint);
    WorkerOptions o;
    o.endpoint = endpoint;
    o.threads = 1;
    o.quiet = true;
    o.give_up_seconds = give_up_seconds;
    o.cache_dir = test::output_path("worker-session-cache");
    exit = std::async(std::launch::async, [o] { return WorkerSession(o).run(); });
  }
  // The next message of the kind T from the worker (heartbeats and others skipped), or nullopt after `seconds`.
  template <class T>
  std::optional<T> next(double seconds = 30.0) {
    const auto end = Clock::now() + std::chrono::duration<double>(seconds * test::kSlowdown);
    while (Clock::now() < end)
      if (auto r = protocol::receive(router, 50, true); r && r->message)
        if (auto* m = std::get_if<T>(&*r->message)) {
          identity = r->identity;
          return *m;
        }
    return std::nullopt;
  }
  void send(const protocol::Message& m) { protocol::send_to(router, identity, m); }
  // The session's end, within `seconds`.
  std::optional<WorkerExit> ended(double seconds = 30.0) {
    if (exit.wait_for(std::chrono::duration<double>(seconds * test::kSlowdown)) != std::future_status::ready)
      return std::nullopt;
    return exit.get();
  }
};

protocol::Welcome welcome(const RenderSettings& settings) {
  protocol::Welcome w;
  w.session = 1;
  w.scene_name = "cornell";
  w.settings = settings;
  w.credits = 4;
  w.heartbeat_ms = 100;
  w.timeout_ms = 5000;
  w.pixel_format = PixelFormat::Float32;
  return w;
}

TEST(WorkerSession, SaysHelloRendersItsJobsAsEveryNodeDoesAndLeavesOnBye) {
  Rig rig;
  const std::optional<protocol::Hello> hello = rig.next<protocol::Hello>();
  ASSERT_TRUE(hello) << "the worker says hello";
  EXPECT_EQ(hello->build_id, build_id());
  EXPECT_EQ(hello->threads, 1u);
  const RenderSettings settings = test::vpl_settings(MethodKind::Igi, 4);
  rig.send(welcome(settings));
  SceneState state(make_builtin_scene("cornell"));
  FrameSetup frame = test::camera_frame(state.scene(), 32, 32);
  frame.frame_id = 3;
  const TileJob tile{8, 16, 16, 8, tile_border(settings)};
  rig.send(protocol::FrameSetupMsg{frame, settings});
  rig.send(protocol::TileJobMsg{3, 42, tile});
  const std::optional<protocol::TileResult> result = rig.next<protocol::TileResult>();
  ASSERT_TRUE(result) << "the job's result";
  EXPECT_EQ(result->job_id, 42u);
  EXPECT_EQ(result->pixel_format, PixelFormat::Float32);
  FlushToZeroScope flush_to_zero;  // as on every render thread
  FrameJob job(state.context(), settings);
  job.begin(frame);
  const RenderedTile want = job.render(tile);
  EXPECT_EQ(result->frame_state_hash, job.state_hash());
  ASSERT_EQ(result->pixels.size(), want.pixels.size());
  EXPECT_TRUE(std::equal(want.pixels.begin(), want.pixels.end(), result->pixels.begin()))
      << "the worker's tile is the one any node renders";
  rig.send(protocol::Bye{"done"});
  EXPECT_EQ(rig.ended(), WorkerExit::Bye);
}

TEST(WorkerSession, ARefusalAndAQuarantineEndItWithTheirStatus) {
  {
    Rig rig;
    ASSERT_TRUE(rig.next<protocol::Hello>());
    rig.send(protocol::Refuse{"build 'x' differs from the master's"});
    EXPECT_EQ(rig.ended(), WorkerExit::Refused);
  }
  {
    Rig rig;
    ASSERT_TRUE(rig.next<protocol::Hello>());
    rig.send(welcome(test::vpl_settings(MethodKind::Igi, 4)));
    rig.send(protocol::Bye{"quarantined by the master: its VPL-set hash differs", protocol::ByeKind::Quarantined});
    EXPECT_EQ(rig.ended(), WorkerExit::Quarantined);
  }
}

TEST(WorkerSession, WithoutAMasterItGivesUp) {
  const auto start = Clock::now();
  Rig rig(/*give_up_seconds=*/0.5, /*bind=*/false);
  EXPECT_EQ(rig.ended(), WorkerExit::GaveUp);
  EXPECT_LT(std::chrono::duration<double>(Clock::now() - start).count(), 10.0 * test::kSlowdown);
}

}  // namespace
}  // namespace igi
