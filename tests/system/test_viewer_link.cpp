// The display link with a real igi-master (--viewer-listen) and the viewer's
// client in this process (viewer/viewer_client.h, what igi-view runs under
// its window): frames come tone-mapped and follow the viewer's camera, a
// viewer that falls silent or vanishes leaves the master rendering, and every
// failure (a wrong key, a second viewer, a master that goes away) ends in an
// error that says what happened. The window itself: tests/master/display/test_window.cpp.
#include <csignal>
#include <fstream>
#include <functional>
#include <memory>
#include <numeric>

#include <gtest/gtest.h>

#include "display/settings_panel.h"
#include "protocol/curve.h"
#include "support/process.h"
#include "support/sanitizers.h"
#include "viewer/video_codec.h"
#include "viewer/viewer_client.h"

namespace igi {
namespace {

namespace fs = std::filesystem;
using std::chrono::milliseconds;

struct Keys {
  fs::path dir;
  protocol::CurveClientKeys viewer, stranger;
};

// DIR/master.key, DIR/viewers/laptop.pub (authorised) and a stranger's pair (not).
Keys make_keys(const std::string& name) {
  Keys k{fs::path(IGI_TEST_OUTPUT_DIR) / name, {}, {}};
  fs::remove_all(k.dir);
  fs::create_directories(k.dir / "viewers");
  const protocol::CurveKeyPair master = protocol::make_curve_keypair();
  protocol::write_key_files((k.dir / "master").string(), master);
  k.viewer = {master.public_key, protocol::make_curve_keypair()};
  protocol::write_key_files((k.dir / "viewers" / "laptop").string(), k.viewer.own);
  k.stranger = {master.public_key, protocol::make_curve_keypair()};
  return k;
}

// Stopped when the test ends, however it ends (a failed ASSERT returns early,
// and a master left running would hold the test's output open).
struct Master {
  std::string endpoint;
  pid_t pid;
  Master(std::string e, pid_t p) : endpoint(std::move(e)), pid(p) {}
  Master(const Master&) = delete;
  Master& operator=(const Master&) = delete;
  ~Master() { test::stop(pid); }
};

std::unique_ptr<Master> start_master(const Keys& k) {
  const std::string endpoint = "tcp://127.0.0.1:" + std::to_string(test::free_port());
  const pid_t pid = test::start(std::string(IGI_MASTER_BINARY) + " --workers 1 --worker-threads 1 --scene cornell "
                                "--size 64x48 --key " + (k.dir / "master.key").string() + " --viewer-listen " +
                                endpoint + " --viewer-keys " + (k.dir / "viewers").string() + " 2>" +
                                (k.dir / "master.log").string());
  return std::make_unique<Master>(endpoint, pid);
}

const auto kPatience = milliseconds(int(20000 * test::kSlowdown));

// A frame and its pixels, as igi-view unpacks them (H.264 frames decoded in order).
struct Shown {
  display::Frame frame;
  std::vector<uint8_t> rgb;
};

struct Viewer {
  ViewerClient client;
  VideoDecoder video;
  Viewer(const std::string& endpoint, const protocol::CurveClientKeys& keys) : client(endpoint, keys) {}

  // The next Frame, acknowledged and unpacked (nullopt after `patience` without one).
  std::optional<Shown> next_frame(milliseconds patience = kPatience) {
    const auto until = std::chrono::steady_clock::now() + patience;
    while (std::chrono::steady_clock::now() < until)
      if (auto m = client.receive(milliseconds(20)))
        if (auto* f = std::get_if<display::Frame>(&*m)) {
          client.send(display::Ack{f->sequence});
          std::string error;
          std::optional<std::vector<uint8_t>> rgb = f->codec == display::FrameCodec::H264
                                                        ? video.decode(f->pixels, f->width, f->height, error)
                                                        : display::unpack_pixels(*f, error);
          EXPECT_TRUE(rgb) << error;
          return Shown{std::move(*f), rgb ? std::move(*rgb) : std::vector<uint8_t>{}};
        }
    return std::nullopt;
  }
};

display::View view_of(const display::Welcome& w, uint64_t camera_generation, uint64_t stamp) {
  return {w.camera, w.settings, camera_generation, 0, {}, -1, {1.0f, ViewTransform::Standard}, false, stamp};
}

std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const ViewerError& e) {
    return e.what();
  }
  return "no error";
}

TEST(ViewerLink, FramesFollowTheViewersCameraAndEchoItsStamp) {
  const Keys k = make_keys("viewer_link_frames");
  const std::unique_ptr<Master> master = start_master(k);
  const Master& m = *master;
  Viewer viewer(m.endpoint, k.viewer);
  const display::Welcome w = viewer.client.join(kPatience);
  EXPECT_EQ(w.width, 64);
  EXPECT_EQ(w.height, 48);
  viewer.client.send(view_of(w, 0, 1000));
  std::optional<Shown> before = viewer.next_frame();
  ASSERT_TRUE(before);
  EXPECT_EQ(before->frame.codec, display::FrameCodec::Zstd) << "a still view's frames are lossless";
  // Turn the camera half a right angle: the frames that show it carry the new
  // stamp, and other pixels; the first ones (moving) come as H.264, and once
  // the view is still (150 ms on, motion_planner.h) lossless again.
  display::View turned = view_of(w, 1, 2000);
  turned.camera.forward = glm::normalize(w.camera.forward + glm::cross(w.camera.forward, w.camera.up));
  viewer.client.send(turned);
  std::optional<Shown> after;
  bool video = false;
  for (int n = 0; n < 400 && (!after || after->frame.stamp_us != 2000 || !video ||
                              after->frame.codec != display::FrameCodec::Zstd); ++n) {
    after = viewer.next_frame();
    video = video || (after && after->frame.codec == display::FrameCodec::H264);
  }
  ASSERT_TRUE(after && after->frame.stamp_us == 2000) << "no frame showed the turned camera";
  EXPECT_TRUE(video) << "no moving frame came as H.264";
  EXPECT_EQ(after->frame.codec, display::FrameCodec::Zstd);
  EXPECT_NE(before->rgb, after->rgb);
}

// The panel's settings reach the session: frames say which of the viewer's
// settings they were rendered with, and show them (direct light only: darker).
TEST(ViewerLink, NewSettingsFromTheViewerReachTheRender) {
  const Keys k = make_keys("viewer_link_settings");
  const std::unique_ptr<Master> master = start_master(k);
  const Master& m = *master;
  Viewer viewer(m.endpoint, k.viewer);
  const display::Welcome w = viewer.client.join(kPatience);
  viewer.client.send(view_of(w, 0, 1));
  std::optional<Shown> f;
  for (int n = 0; n < 400 && (!f || f->frame.accumulated < 4.0f); ++n) f = viewer.next_frame();
  ASSERT_TRUE(f && f->frame.accumulated >= 4.0f);
  display::View pt = view_of(w, 0, 2);
  pt.settings = with_method(w.settings, MethodKind::PathTracer);
  pt.settings.path_depth = 1;
  pt.settings_generation = 1;
  viewer.client.send(pt);
  std::optional<Shown> after;
  for (int n = 0; n < 400 && (!after || after->frame.settings_generation != 1); ++n) after = viewer.next_frame();
  ASSERT_TRUE(after && after->frame.settings_generation == 1) << "no frame of the new settings";
  auto mean = [](const std::vector<uint8_t>& rgb) { return std::accumulate(rgb.begin(), rgb.end(), 0.0) / rgb.size(); };
  EXPECT_LT(mean(after->rgb), 0.9 * mean(f->rgb)) << "the frames of the new settings are not direct light only";
}

TEST(ViewerLink, AViewerWithAWrongKeyIsRefusedSayingWhy) {
  const Keys k = make_keys("viewer_link_wrong_key");
  const std::unique_ptr<Master> master = start_master(k);
  const Master& m = *master;
  ViewerClient stranger(m.endpoint, k.stranger);
  const std::string error = error_of([&] { stranger.join(kPatience); });
  EXPECT_NE(error.find("refused this viewer's key"), std::string::npos) << error;
  EXPECT_NE(error.find("--viewer-keys"), std::string::npos) << error;
  // A wrong master key: no handshake completes, and the viewer says which key to check.
  protocol::CurveClientKeys wrong_master = k.viewer;
  wrong_master.server_key = protocol::make_curve_keypair().public_key;
  ViewerClient lost(m.endpoint, wrong_master);
  const std::string silent = error_of([&] { lost.join(milliseconds(3000)); });
  EXPECT_NE(silent.find("--master-key"), std::string::npos) << silent;
}

TEST(ViewerLink, ASecondViewerIsRefusedAndTheFirstGoesOn) {
  const Keys k = make_keys("viewer_link_second");
  const std::unique_ptr<Master> master = start_master(k);
  const Master& m = *master;
  Viewer first(m.endpoint, k.viewer);
  const display::Welcome w = first.client.join(kPatience);
  first.client.send(view_of(w, 0, 1));
  ASSERT_TRUE(first.next_frame());
  ViewerClient second(m.endpoint, k.viewer);
  const std::string error = error_of([&] { second.join(kPatience); });
  EXPECT_NE(error.find("another viewer ('laptop') is connected"), std::string::npos) << error;
  EXPECT_TRUE(first.next_frame()) << "the first viewer lost its frames";
}

// A viewer that vanishes between frames (its process killed: its connection
// closes, no Bye) leaves the master rendering, and the next viewer is let in
// at once and sees the image accumulate further.
TEST(ViewerLink, AViewerKilledMidFrameLeavesTheMasterRendering) {
  const Keys k = make_keys("viewer_link_killed");
  const std::unique_ptr<Master> master = start_master(k);
  const Master& m = *master;
  float accumulated = 0.0f;
  {
    Viewer doomed(m.endpoint, k.viewer);
    const display::Welcome w = doomed.client.join(kPatience);
    doomed.client.send(view_of(w, 0, 1));
    std::optional<Shown> f = doomed.next_frame();
    ASSERT_TRUE(f);
    accumulated = f->frame.accumulated;
    // Gone without a Bye or an Ack, with a frame in flight.
  }
  Viewer next(m.endpoint, k.viewer);
  const display::Welcome w = next.client.join(kPatience);
  next.client.send(view_of(w, 0, 2));
  std::optional<Shown> f;
  for (int n = 0; n < 200 && (!f || f->frame.accumulated <= accumulated + 2.0f); ++n) f = next.next_frame();
  ASSERT_TRUE(f);
  EXPECT_GT(f->frame.accumulated, accumulated + 2.0f) << "the image did not go on accumulating";
}

TEST(ViewerLink, AMasterThatGoesAwayIsReported) {
  const Keys k = make_keys("viewer_link_master_gone");
  const std::unique_ptr<Master> master = start_master(k);
  const Master& m = *master;
  Viewer viewer(m.endpoint, k.viewer);
  ViewerClient& client = viewer.client;
  const display::Welcome w = client.join(kPatience);
  client.send(view_of(w, 0, 1));
  ASSERT_TRUE(viewer.next_frame());
  ::kill(m.pid, SIGKILL);  // no Bye: the process is gone
  const auto start = std::chrono::steady_clock::now();
  const std::string error = error_of([&] {
    for (;;) client.receive(milliseconds(50));
  });
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_NE(error.find("the master at " + m.endpoint), std::string::npos) << error;
  EXPECT_LT(seconds, 3.5 * test::kSlowdown) << error;
}

}  // namespace
}  // namespace igi
