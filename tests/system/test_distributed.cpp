// Headless tile-result tests: a master with local or extra workers gives the
// very image the single-process renderer gives, whatever happens to workers.
#include <algorithm>
#include <atomic>
#include <cstring>
#include <limits>
#include <chrono>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <optional>
#include <sstream>
#include <thread>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <sys/wait.h>
#include <zmq.hpp>

#include "image/rgb9e5.h"
#include "photons/caustic_settings.h"
#include "protocol/codec.h"
#include "protocol/socket.h"
#include "scene/builtin_scenes.h"
#include "scene/gltf_writer.h"
#include "scene/load_scene.h"
#include "support/image_compare.h"
#include "support/process.h"
#include "support/render_fixture.h"
#include "support/sanitizers.h"
#include "support/stats_file.h"

namespace igi {
namespace {

namespace fs = std::filesystem;
constexpr int kWidth = 160, kHeight = 120;

std::string master(const std::string& extra, const std::string& scene = "cornell") {
  return std::string(IGI_MASTER_BINARY) + " --scene " + scene + " --method igi --vpl-paths 8 --size " +
         std::to_string(kWidth) + "x" + std::to_string(kHeight) + " --tile 16 --worker-threads 1 " + extra;
}

// The single-process render of the same scene and settings.
Image single_process(const std::string& scene = "cornell") {
  static std::map<std::string, Image> cache;
  if (!cache.count(scene)) {
    test::Prepared p(load_scene(scene));
    RenderSettings s;
    s.method = MethodKind::Igi;
    s.paths_per_set = 8;
    cache[scene] = p.render(s, kWidth, kHeight, 1, 1);
  }
  return cache[scene];
}

// Master and two workers with `options` on `scene` give, bit for bit, the
// one-process render with igi's settings (8 light paths) as `edit` changes them.
void expect_workers_match_one_process(const std::string& name, const std::string& options, const std::string& scene,
                                      const std::function<void(RenderSettings&)>& edit,
                                      const SceneOptions& read_as = {}, std::string* output = nullptr) {
  const std::string out = test::output_path(name + ".exr");
  auto r = test::run(master("--workers 2 --frames 1 " + options + " -o " + out, scene));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  if (output) *output = r.output;
  test::Prepared p(load_scene(scene, read_as));
  RenderSettings s;
  s.method = MethodKind::Igi;
  s.paths_per_set = 8;
  edit(s);
  EXPECT_TRUE(test::images_identical(name, read_image(out), p.render(s, kWidth, kHeight, 1, 1)));
}

// The red channel's mean as a PNG at exposure 1 shows it (clipped at white).
float tonemapped_mean(const Image& image) {
  double sum = 0.0;
  for (const glm::vec3& p : image.pixels) sum += std::min(p.x, 1.0f);
  return float(sum / double(image.pixels.size()));
}

TEST(Distributed, TwoWorkersMatchTheSingleProcessRenderBitForBit) {
  const std::string out = test::output_path("dist-two.exr");
  auto r = test::run(master("--workers 2 --frames 1 -o " + out));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_TRUE(test::images_identical("dist-two", read_image(out), single_process()));
}

// --exposure auto meters the final image, never a tile: one process with
// tiles of 16 or 64 pixels and a master of two workers (floats on the wire)
// write the same PNG, byte for byte, at the same exposure.
TEST(Distributed, AutoExposureIsTheSameWholeTiledAndDistributed) {
  const std::string render = std::string(IGI_RENDER_BINARY) + " --scene cornell --method igi --vpl-paths 8 --size " +
                             std::to_string(kWidth) + "x" + std::to_string(kHeight) + " --exposure auto";
  const std::string tiled = test::output_path("auto-tiled.png"), whole = test::output_path("auto-whole.png"),
                    distributed = test::output_path("auto-distributed.png");
  const test::RunResult a = test::run(render + " --tile 16 -o " + tiled + " 2>&1");
  const test::RunResult b = test::run(render + " --tile 160 --threads 1 -o " + whole + " 2>&1");
  const test::RunResult c = test::run(master("--workers 2 --frames 1 --pixels float --exposure auto -o " + distributed));
  ASSERT_EQ(a.exit_code + b.exit_code + c.exit_code, 0) << a.output << b.output << c.output;
  auto said = [](const std::string& output) {  // "exposure metered: +1.78 EV (x 3.437)"
    const size_t at = output.find("exposure metered: ");
    return at == std::string::npos ? std::string() : output.substr(at, output.find('\n', at) - at);
  };
  ASSERT_FALSE(said(a.output).empty()) << a.output;
  EXPECT_EQ(said(a.output), said(b.output));
  EXPECT_EQ(said(c.output).substr(0, 27), said(a.output).substr(0, 27)) << c.output;  // "... +1.78 EV"
  const Image first = read_image(tiled);
  EXPECT_TRUE(test::images_identical("auto-whole", read_image(whole), first));
  EXPECT_TRUE(test::images_identical("auto-distributed", read_image(distributed), first));
  EXPECT_GT(first.mean().x, 1.5f * tonemapped_mean(single_process())) << "metered, not at exposure 1";
}

// Anti-aliasing by VPL groups, the glossy gather and its light samples
// (glossy, where the master turns caustics on for the sharp floor), the
// glossy receiver's clamp (glossy-rough) and exact spot light (corner), with
// compensation: workers give the one-process image.
TEST(Distributed, AntialiasingGlossyGatherAndExactLightsMatchOneProcess) {
  for (const std::string scene : {"glossy", "glossy-rough", "corner"}) {
    const std::string out = test::output_path("dist-quality-" + scene + ".exr");
    auto r = test::run(master("--workers 2 --frames 1 --aa 4 --clamp 0.05 --compensate 2 -o " + out, scene));
    ASSERT_EQ(r.exit_code, 0) << r.output;
    test::Prepared p(load_scene(scene));
    RenderSettings s;
    s.method = MethodKind::Igi;
    s.paths_per_set = 8;
    s.aa_samples = 4;
    s.clamp = 0.05f;
    s.compensation_samples = 2;
    s.caustics = photons::has_specular_surfaces(p.scene, s.glossy_threshold);
    EXPECT_EQ(s.caustics, scene == "glossy");
    EXPECT_TRUE(test::images_identical("dist-quality-" + scene, read_image(out), p.render(s, kWidth, kHeight, 1, 1)));
  }
}

// The caustic photon map is traced by every worker from the frame seed (its
// hash joins the VPLs'), and glass branches split the G-buffer: workers give
// the one-process image.
// No caustic option: the master turns caustics on for a scene with glass,
// and its workers render the frame one process renders with them on.
TEST(Distributed, CausticsTheSceneChoseMatchOneProcess) {
  expect_workers_match_one_process("dist-caustics-default", "", "glass",
                                   [](RenderSettings& s) { s.caustics = true; });
}

// The sun's light paths start where pilots found they reach the view
// (importance/view_guide.h): every worker builds the same guide from the
// frame setup, and the master's judge too.
TEST(Distributed, LightPathsThatFindTheViewMatchOneProcess) {
  expect_workers_match_one_process("dist-light-guide", "", "sunroom", [](RenderSettings& s) { s.light_guide = true; });
}

// No --bidir option: in the corridor the view probe turns bidirectional IR
// on (2 M light paths, 2 M VPLs kept), on the master's judge and on every
// worker alike: the one-process frame of --vpl-paths 16 --bidir 16.
TEST(Distributed, BidirectionalIrTheViewChoseMatchesOneProcess) {
  expect_workers_match_one_process("dist-bidir-auto", "", "corridor", [](RenderSettings& s) {
    s.paths_per_set = 16;
    s.bidir_vpls = 16;
  });
}

TEST(Distributed, CausticsAndGlassBranchesMatchOneProcess) {
  expect_workers_match_one_process("dist-caustics", "--caustic-photons 4000 --glass-branches 3", "glass",
                                   [](RenderSettings& s) {
                                     s.glass_branches = 3;
                                     s.caustics = true;
                                     s.caustic_photons = 4000;
                                   });
}

// The wavelet filter's wider border through master and workers (tiles of 16,
// border 1 + 8): workers give the one-process image.
TEST(Distributed, WaveletFilterMatchesOneProcess) {
  expect_workers_match_one_process("dist-wavelet", "--wavelet 2", "cornell",
                                   [](RenderSettings& s) { s.wavelet_levels = 2; });
}

// The environment travels in the Welcome: workers light the scene with the
// master's sky (the Cornell box's open front shows it), not the file's none.
TEST(Distributed, EnvironmentLightMatchesOneProcess) {
  expect_workers_match_one_process("dist-environment", "--environment 0.2,0.3,0.4", "cornell",
                                   [](RenderSettings&) {},
                                   SceneOptions{SkyChoice{glm::vec3(0.2f, 0.3f, 0.4f)}, LightUnits::Photometric, false});
}

// --light-units travels in the Welcome: workers read a glTF file's lamps in
// the master's units (a spot lamp's candela here read as W/sr, 683 times
// brighter), and their frame is the one-process frame read so.
TEST(Distributed, LampsReadInTheMastersUnitsMatchOneProcess) {
  const std::string scene = test::output_path("dist-units-corner.glb");
  write_gltf(make_builtin_scene("corner"), scene);
  expect_workers_match_one_process("dist-light-units", "--light-units radiometric", scene,
                                   [](RenderSettings&) {},
                                   SceneOptions{std::nullopt, LightUnits::Radiometric, false});
}

// An environment map, scaled and turned: the workers have no copy and ask the
// master for it by hash, as for a scene; their frame is the one-process frame.
TEST(Distributed, EnvironmentMapTravelsToWorkersAndMatchesOneProcess) {
  Image map(32, 16);
  for (int y = 0; y < map.height; ++y)
    for (int x = 0; x < map.width; ++x) map.at(x, y) = glm::vec3(0.2f + 0.05f * float(x % 7), 0.3f, 0.2f + 0.1f * float(y));
  map.at(20, 4) = glm::vec3(400.0f, 350.0f, 300.0f);  // a sun
  const std::string path = test::output_path("dist-sky-map.exr");
  write_image(map, path);
  std::error_code error;  // the workers' cache (igi-worker-cache here) must not hold it from an earlier run
  for (const auto& entry : std::filesystem::directory_iterator("igi-worker-cache", error))
    if (entry.path().filename().string().ends_with("-dist-sky-map.exr")) std::filesystem::remove(entry.path(), error);
  std::string output;
  expect_workers_match_one_process("dist-environment-map",
                                   "--environment " + path + " --environment-scale 0.5 --environment-rotation 30",
                                   "corner", [](RenderSettings&) {},
                                   SceneOptions{SkyChoice{glm::vec3(0.5f), path, 30.0f}, LightUnits::Photometric, false},
                                   &output);
  EXPECT_NE(output.find("has no copy of dist-sky-map.exr"), std::string::npos) << output;
}

// Lightcuts' light tree and reconstruction grid through master and workers:
// settings over the wire, tiles of 16 with the sample grid's cells across them.
TEST(Distributed, LightcutsWithReconstructionCutsMatchTheSingleProcessRenderBitForBit) {
  expect_workers_match_one_process("dist-lightcuts", "--method lightcuts --vpl-paths 20 --lightcuts-spacing 6",
                                   "cornell", [](RenderSettings& s) {
                                     s.method = MethodKind::Lightcuts;
                                     s.paths_per_set = 20;
                                     s.lightcuts_spacing = 6;
                                   });
}

// VPLs drawn from the light tree (--vpl-draws) under the wavelet filter:
// the tree is built on every worker from the same VPLs, the draws follow
// the pixel, never the worker.
TEST(Distributed, VplDrawsMatchTheSingleProcessRenderBitForBit) {
  expect_workers_match_one_process("dist-vpl-draws", "--vpl-draws 2 --wavelet 2", "cornell", [](RenderSettings& s) {
    s.vpl_draws = 2;
    s.wavelet_levels = 2;
  });
}

// Forced copies go to the other worker as each job goes out. The run waits
// for both workers (--min-workers): under load the second one could join
// after a short run had ended, and no copy would go out (seen in CI).
TEST(Distributed, DuplicatedTilesGiveTheSameImage) {
  const std::string out = test::output_path("dist-dup.exr"), stats = test::output_path("dist-dup.json");
  auto r = test::run(master("--workers 2 --min-workers 2 --frames 4 --credits 1 --test-force-duplicates 40 -o " + out +
                            " --stats " + stats));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  for (int f = 0; f < 4; ++f) {
    const std::string name = "dist-dup-000" + std::to_string(f);
    EXPECT_TRUE(test::images_identical(name, read_image(test::output_path(name + ".exr")), single_process()));
  }
  const nlohmann::json s = test::read_stats(stats);
  EXPECT_GE(s["frames"][3]["duplicated_total"].get<int>(), 40);
  EXPECT_EQ(s["master_hash_frames"].get<int>(), 4) << "each frame's VPL-set hash once, though asked for ahead";
  // Each frame's completion time since the session began (benchmarks take
  // rates from them): in order, and no earlier than its own latency allows.
  double previous = 0.0;
  for (const auto& f : s["frames"]) {
    const double at = f["completed_at"].get<double>();
    EXPECT_GE(at, previous);
    EXPECT_GE(at, f["seconds"].get<double>());
    previous = at;
  }
}

// --pixel-codec zstd: the workers pack their pixels, the master unpacks the
// very bytes (the same image bit for bit) from fewer of them.
TEST(Distributed, PackedPixelsGiveTheSameImageFromFewerBytes) {
  auto bytes_in = [](const nlohmann::json& s) {
    uint64_t sum = 0;
    for (const auto& f : s["frames"])
      for (const auto& [name, w] : f["workers"].items()) sum += w["bytes_in"].get<uint64_t>();
    return sum;
  };
  // Shared-exponent pixels (--pixels rgb9e5) are the one-process image, each
  // pixel rounded as image/rgb9e5.h rounds it, in fewer bytes again.
  Image rounded = single_process();
  for (glm::vec3& p : rounded.pixels) p = from_rgb9e5(to_rgb9e5(p));
  uint64_t bytes[4];
  int run = 0;
  for (const char* wire : {"--pixel-codec raw", "--pixel-codec zstd", "--pixel-codec zstd --pixels rgb9e5",
                           "--pixel-codec lz4 --pixels rgb9e5"}) {
    const std::string tag = "dist-wire-" + std::to_string(run), out = test::output_path(tag + ".exr"),
                      stats = test::output_path(tag + ".json");
    auto r = test::run(master("--workers 2 --frames 2 " + std::string(wire) + " -o " + out + " --stats " + stats));
    ASSERT_EQ(r.exit_code, 0) << r.output;
    for (int f = 0; f < 2; ++f) {
      const std::string name = tag + "-000" + std::to_string(f);
      EXPECT_TRUE(test::images_identical(name, read_image(test::output_path(name + ".exr")),
                                         run >= 2 ? rounded : single_process())) << wire;
    }
    const nlohmann::json s = test::read_stats(stats);
    EXPECT_EQ(s["pixel_codec"].get<std::string>(), run == 0 ? "raw" : run == 3 ? "lz4" : "zstd");
    EXPECT_EQ(s["pixel_format"].get<std::string>(), run >= 2 ? "rgb9e5" : "float");
    bytes[run++] = bytes_in(s);
  }
  EXPECT_LT(bytes[1], bytes[0]) << "zstd-packed float pixels of the Cornell box";
  EXPECT_LT(bytes[2], bytes[1] / 2) << "zstd-packed rgb9e5 pixels";
  EXPECT_LT(bytes[3], bytes[0] / 3) << "lz4-packed rgb9e5 pixels: fewer than raw rgb9e5 (4 bytes of 12)";
}

TEST(Distributed, WorkerKilledMidFrameLosesNothing) {
  const std::string out = test::output_path("dist-kill.exr"), stats = test::output_path("dist-kill.json");
  // The kill comes after 30 results, in the first frame (80 tiles); under a
  // sanitizer the frames after it are fewer, as each takes 5-10x longer.
  const int frames = test::kSlowdown > 1 ? 16 : 40;
  auto r = test::run(master("--workers 2 --min-workers 2 --frames " + std::to_string(frames) +
                            " --heartbeat-ms 50 --timeout-ms 300 --test-kill-worker-after 30 -o " + out + " --stats " + stats));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  for (int f = 0; f < frames; f += 3) {
    char name[64];
    std::snprintf(name, sizeof name, "dist-kill-%04d.exr", f);
    EXPECT_TRUE(test::images_identical(std::string("dist-kill-") + std::to_string(f),
                                       read_image(test::output_path(name)), single_process()));
  }
  nlohmann::json s = test::read_stats(stats);
  // Its jobs come back either as straggler copies (often first, near a
  // frame's end) or reissued once it is declared dead.
  const auto& last = s["frames"][frames - 1];
  EXPECT_GT(last["reissued_total"].get<int>() + last["duplicated_total"].get<int>(), 0);
  EXPECT_NE(r.output.find("declared dead"), std::string::npos) << r.output;
  std::vector<double> seconds;
  for (auto& f : s["frames"]) seconds.push_back(f["seconds"].get<double>());
  std::sort(seconds.begin(), seconds.end());
  const double slowest = seconds.back(), median = seconds[seconds.size() / 2];
  std::printf("slowest frame with a worker killed: %.0f ms (timeout 300 ms, median frame %.0f ms)\n", 1e3 * slowest,
              1e3 * median);
  // A load that slows every frame slows this one too: the slack is 5 median
  // frames, plus 1 s (5 s under a sanitizer; 2.4 s seen under ASan with ctest -j2).
  EXPECT_LT(slowest, 2 * 0.3 + 5 * median + 1.0 * test::kSlowdown) << "a kill delays a frame by about a timeout, not more";
}

// Light importance and bidirectional IR: every worker computes the light
// probabilities and resampled sets itself, so no frame setup carries them,
// and a tile reissued after a worker's death comes out the same.
TEST(Distributed, LightImportanceAndBidirectionalMatchOneProcessWithAWorkerKilled) {
  const std::string out = test::output_path("dist-importance.exr"), stats = test::output_path("dist-importance.json");
  const std::string options = "--aa 4 --clamp 0.05 --compensate 0 --importance 256 --bidir 12 ";
  const int frames = 6;
  auto r = test::run(master("--workers 2 --min-workers 2 --frames " + std::to_string(frames) +
                            " --heartbeat-ms 50 --timeout-ms 300 --test-kill-worker-after 20 " + options + "-o " + out +
                            " --stats " + stats, "rooms"));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  // The kill comes after 20 results once both workers have joined (80 tiles a frame).
  const nlohmann::json last = test::read_stats(stats)["frames"][frames - 1];
  // The killed worker may still be listed (with no tiles) when the run ends
  // within the timeout of the kill: the frames are short.
  int rendering = 0;
  for (const auto& [name, w] : last["workers"].items()) rendering += w["tiles"].get<int>() > 0;
  EXPECT_EQ(rendering, 1) << "one worker was killed";
  EXPECT_GT(last["reissued_total"].get<int>() + last["duplicated_total"].get<int>(), 0)
      << "its tiles came back from the other";
  test::Prepared p(load_scene("rooms"));
  RenderSettings s = test::vpl_settings(MethodKind::Igi, 8, 0.05f, true, 0, 4);
  s.interleave = RenderSettings{}.interleave;  // the master's, which `options` leaves at its default
  s.importance_paths = 256;
  s.bidir_vpls = 12;
  const Image one = p.render(s, kWidth, kHeight, 1, 1);
  for (int f = 0; f < frames; ++f) {
    char name[64];
    std::snprintf(name, sizeof name, "dist-importance-%04d.exr", f);
    EXPECT_TRUE(test::images_identical(name, read_image(test::output_path(name)), one));
  }
}

// A ZeroMQ proxy between workers and the master that puts a NaN into every
// result for one tile of one frame, however often the tile is rendered: as a
// faulty switch or a hostile hop would. Each worker connection gets a DEALER
// of its own towards the master, so the master sees the workers as they are.
class SpoilingProxy {
 public:
  SpoilingProxy(const std::string& master, uint64_t frame_id, int tile_x, int tile_y)
      : master_(master), frame_id_(frame_id), tile_x_(tile_x), tile_y_(tile_y) {
    front_.bind("tcp://127.0.0.1:0");
    endpoint_ = front_.get(zmq::sockopt::last_endpoint);
    thread_ = std::thread([this] { run(); });
  }
  ~SpoilingProxy() {
    stop_ = true;
    thread_.join();
  }
  const std::string& endpoint() const { return endpoint_; }
  int spoiled() const { return spoiled_; }

 private:
  void run() {
    std::map<std::string, zmq::socket_t> back;  // worker identity -> its DEALER to the master
    while (!stop_) {
      std::vector<zmq::pollitem_t> items{{front_.handle(), 0, ZMQ_POLLIN, 0}};
      std::vector<const std::string*> ids;
      for (auto& [id, socket] : back) {
        items.push_back({socket.handle(), 0, ZMQ_POLLIN, 0});
        ids.push_back(&id);
      }
      zmq::poll(items, std::chrono::milliseconds(20));
      if (items[0].revents & ZMQ_POLLIN) {
        zmq::message_t id, payload;
        (void)front_.recv(id);
        (void)front_.recv(payload);
        auto it = back.find(id.to_string());
        if (it == back.end()) {
          it = back.emplace(id.to_string(), zmq::socket_t(context_, zmq::socket_type::dealer)).first;
          it->second.set(zmq::sockopt::linger, 0);
          it->second.connect(master_);
        }
        spoil(payload);
        it->second.send(payload, zmq::send_flags::none);
      }
      for (size_t i = 1; i < items.size(); ++i) {
        if (!(items[i].revents & ZMQ_POLLIN)) continue;
        zmq::message_t payload;
        (void)back.at(*ids[i - 1]).recv(payload);
        front_.send(zmq::buffer(*ids[i - 1]), zmq::send_flags::sndmore);
        front_.send(payload, zmq::send_flags::none);
      }
    }
    for (auto& [id, socket] : back) socket.close();
  }
  void spoil(zmq::message_t& payload) {
    std::span<const uint8_t> bytes(payload.data<uint8_t>(), payload.size());
    if (!protocol::is_tile_result(bytes)) return;
    std::string error;
    std::optional<protocol::TileResultView> view = protocol::decode_tile_result(bytes, error);
    if (!view || view->fields.frame_id != frame_id_ || view->fields.tile.x != tile_x_ || view->fields.tile.y != tile_y_)
      return;
    uint8_t* pixel = payload.data<uint8_t>() + (view->pixel_bytes.data() - bytes.data());
    if (view->fields.pixel_format == PixelFormat::Float16) {
      pixel[0] = 0x00, pixel[1] = 0x7e;  // a half NaN
    } else {
      const float nan = std::numeric_limits<float>::quiet_NaN();
      std::memcpy(pixel, &nan, sizeof nan);
    }
    ++spoiled_;
  }

  zmq::context_t context_;
  zmq::socket_t front_{context_, zmq::socket_type::router};
  std::string endpoint_, master_;
  uint64_t frame_id_;
  int tile_x_, tile_y_;
  std::atomic<bool> stop_{false};
  std::atomic<int> spoiled_{0};
  std::thread thread_;
};

// Honest workers behind that proxy: the tile fails validation on one, goes to
// the other (never back), fails there too, and the master renders it itself.
// Every frame is written, each the one-process image; no worker is
// quarantined, and the log and the totals agree on what happened.
TEST(Distributed, AProxyThatSpoilsOneTileCostsNoFrame) {
  const int port = test::free_port();
  const std::string endpoint = "tcp://127.0.0.1:" + std::to_string(port);
  const std::string out = test::output_path("dist-spoiled.exr"), stats = test::output_path("dist-spoiled.json");
  SpoilingProxy proxy(endpoint, 1, 16, 32);
  pid_t m = test::start(master("--workers 0 --min-workers 2 --frames 4 --listen " + endpoint + " -o " + out +
                               " --stats " + stats + " > " + out + ".log 2>&1"));
  std::vector<pid_t> workers;
  for (int i = 0; i < 2; ++i)
    workers.push_back(test::start(std::string(IGI_WORKER_BINARY) + " --connect " + proxy.endpoint() +
                                  " --threads 1 --quiet"));
  EXPECT_EQ(test::wait_exit(m, 120), 0);
  for (pid_t w : workers) EXPECT_EQ(test::wait_exit(w, 20), 0) << "no worker was quarantined (that is exit 5)";
  std::ifstream log_file(out + ".log");
  const std::string log((std::istreambuf_iterator<char>(log_file)), std::istreambuf_iterator<char>());
  EXPECT_EQ(proxy.spoiled(), 2) << "once on each worker, then never again: " << log;
  EXPECT_NE(log.find("failed validation on worker-"), std::string::npos) << log;
  EXPECT_NE(log.find("the master renders it itself"), std::string::npos) << log;
  EXPECT_NE(log.find("tiles the master rendered 1, hoarders benched 0, workers quarantined 0"), std::string::npos) << log;
  for (int f = 0; f < 4; ++f) {
    const std::string name = "dist-spoiled-000" + std::to_string(f);
    EXPECT_TRUE(test::images_identical(name, read_image(test::output_path(name + ".exr")), single_process()));
  }
  nlohmann::json s = test::read_stats(stats);
  EXPECT_EQ(s["outcome"], "done");
  EXPECT_EQ(s["own_tiles"].get<int>(), 1);
  EXPECT_EQ(s["frames"][3]["failed_results_total"].get<int>(), 2);
  EXPECT_EQ(s["frames"][3]["quarantined_total"].get<int>(), 0);
}

TEST(Distributed, WorkerJoiningMidSessionGetsWork) {
  const int port = test::free_port();
  const std::string endpoint = "tcp://127.0.0.1:" + std::to_string(port);
  const std::string out = test::output_path("dist-join.exr"), stats = test::output_path("dist-join.json");
  // The second worker comes about 1 s in (a few frames); under a sanitizer
  // frames take 5-10x longer, so fewer of them leave it as much time.
  const int frames = test::kSlowdown > 1 ? 20 : 60;
  pid_t m = test::start(master("--workers 1 --frames " + std::to_string(frames) + " --listen " + endpoint + " --quiet -o " +
                               out + " --stats " + stats));
  std::this_thread::sleep_for(std::chrono::milliseconds(800));
  pid_t w = test::start(std::string(IGI_WORKER_BINARY) + " --connect " + endpoint + " --threads 1 --quiet");
  EXPECT_EQ(test::wait_exit(m, 120), 0);
  EXPECT_EQ(test::wait_exit(w, 20), 0) << "the joined worker leaves cleanly on the master's bye";
  nlohmann::json s = test::read_stats(stats);
  EXPECT_EQ(s["frames"].back()["workers"].size(), 2u) << "both workers rendered the last frame";
}

TEST(Distributed, WorkerOfAnotherBuildIsRefusedWithItsReason) {
  const std::string endpoint = "tcp://127.0.0.1:" + std::to_string(test::free_port());
  pid_t m = test::start(master("--workers 0 --frames 1 --quiet --listen " + endpoint + " -o " + test::output_path("dist-refuse.exr")));
  auto r = test::run(std::string(IGI_WORKER_BINARY) + " --connect " + endpoint + " --build-id other-build", 30);
  test::stop(m);
  EXPECT_EQ(r.exit_code, 3) << r.output;
  EXPECT_NE(r.output.find("refused by master"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("other-build"), std::string::npos) << r.output;
}

TEST(Distributed, PeerOfAnotherProtocolVersionIsToldWhy) {
  const std::string endpoint = "tcp://127.0.0.1:" + std::to_string(test::free_port());
  pid_t m = test::start(master("--workers 0 --frames 1 --quiet --listen " + endpoint + " -o " + test::output_path("dist-version.exr")));
  zmq::context_t context;
  zmq::socket_t dealer(context, zmq::socket_type::dealer);
  dealer.set(zmq::sockopt::linger, 0);
  dealer.set(zmq::sockopt::rcvtimeo, int(10000 * test::kSlowdown));  // the master may take seconds to start
  dealer.connect(endpoint);
  std::vector<uint8_t> hello = protocol::encode(protocol::Hello{"x", "sse", 1});
  hello[4] = uint8_t(protocol::kVersion + 1);  // the u16 version after the magic
  dealer.send(zmq::buffer(hello), zmq::send_flags::none);
  zmq::message_t reply;
  auto got = dealer.recv(reply, zmq::recv_flags::none);
  test::stop(m);
  ASSERT_TRUE(got) << "the master answers";
  auto decoded = protocol::decode({static_cast<const uint8_t*>(reply.data()), reply.size()});
  ASSERT_TRUE(decoded.message) << decoded.error;
  auto* refuse = std::get_if<protocol::Refuse>(&*decoded.message);
  ASSERT_NE(refuse, nullptr);
  EXPECT_NE(refuse->reason.find("version"), std::string::npos) << refuse->reason;
}

TEST(Distributed, WorkerWithoutTheSceneFileReceivesItFromTheMaster) {
  const fs::path dir = fs::path(test::output_path("dist-scene"));
  fs::remove_all(dir);
  fs::create_directories(dir / "master");
  const std::string scene = (dir / "master" / "box.glb").string();
  write_gltf(make_cornell_box(), scene);
  const std::string endpoint = "tcp://127.0.0.1:" + std::to_string(test::free_port());
  const std::string out = (dir / "out.exr").string();
  pid_t m = test::start(master("--workers 0 --frames 1 --quiet --listen " + endpoint + " -o " + out, scene));
  auto r = test::run(std::string(IGI_WORKER_BINARY) + " --connect " + endpoint + " --threads 1 --scene-dir " +
                     (dir / "nowhere").string() + " --cache " + (dir / "cache").string(), 60);
  EXPECT_EQ(test::wait_exit(m, 60), 0);
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("asking the master"), std::string::npos) << r.output;
  ASSERT_TRUE(fs::exists(dir / "cache"));
  EXPECT_EQ(std::distance(fs::directory_iterator(dir / "cache"), fs::directory_iterator{}), 1) << "one file, named by hash";
  EXPECT_TRUE(test::images_identical("dist-scene", read_image(out), single_process(scene)));
}

// A master in DIR/master serving SCENE (made there by the caller) to one worker
// in DIR/worker that has no copy: both exit 0, the master says it sent
// box.glb, and the frame (returned) is the one-process frame.
Image serve_to_a_worker_elsewhere(const fs::path& dir, const std::string& scene) {
  const std::string endpoint = "tcp://127.0.0.1:" + std::to_string(test::free_port());
  const std::string out = (dir / "out.exr").string(), log = (dir / "master.log").string();
  pid_t m = test::start(master("--workers 0 --frames 1 --quiet --listen " + endpoint + " -o " + out, scene) + " 2>" + log);
  auto r = test::run(std::string(IGI_WORKER_BINARY) + " --connect " + endpoint + " --threads 1 --scene-dir " +
                     (dir / "worker").string() + " --cache " + (dir / "worker" / "cache").string(), 60);
  EXPECT_EQ(test::wait_exit(m, 60), 0);
  EXPECT_EQ(r.exit_code, 0) << r.output;
  std::ifstream text(log);
  const std::string said((std::istreambuf_iterator<char>(text)), std::istreambuf_iterator<char>());
  EXPECT_NE(said.find("goes to workers as box.glb"), std::string::npos) << said;
  EXPECT_EQ(std::distance(fs::directory_iterator(dir / "worker" / "cache"), fs::directory_iterator{}), 1);
  const Image image = read_image(out);
  EXPECT_TRUE(test::images_identical(dir.filename().string(), image, single_process(scene)));
  return image;
}

fs::path fresh_master_and_worker_dirs(const std::string& name) {
  const fs::path dir = fs::path(test::output_path(name));
  fs::remove_all(dir);
  fs::create_directories(dir / "master");
  fs::create_directories(dir / "worker");
  return dir;
}

// What --export-gltf writes (box.gltf and box.bin beside it) reaches a worker in another folder whole:
// the master packs it into one .glb (it used to send the .gltf alone; the worker exited 6, "box.bin not found").
TEST(Distributed, AGltfWithItsBufferBesideItTravelsWhole) {
  const fs::path dir = fresh_master_and_worker_dirs("dist-gltf");
  const std::string scene = (dir / "master" / "box.gltf").string();
  write_gltf(make_cornell_box(), scene);
  ASSERT_TRUE(fs::exists(dir / "master" / "box.bin"));
  serve_to_a_worker_elsewhere(dir, scene);
}

// An OBJ scene (its MTL and texture beside it) reaches a worker in another
// folder as the .glb the master made of it, and the frame is igi-render's.
TEST(Distributed, AnObjSceneTravelsAsAGlbAndMatchesOneProcess) {
  const fs::path dir = fresh_master_and_worker_dirs("dist-obj");
  Image boards(4, 4);
  for (int i = 0; i < 16; ++i) boards.pixels[size_t(i)] = glm::vec3(0.2f + 0.1f * float(i % 4), 0.3f, 0.2f);
  write_image(boards, (dir / "master" / "boards.png").string());
  std::ofstream(dir / "master" / "box.mtl") << "newmtl wall\nKd 0.7 0.6 0.5\nnewmtl floor\nKd 1 1 1\nmap_Kd boards.png\n"
                                               "newmtl lamp\nKd 0 0 0\nKe 12 11 10\n";
  // An open box seen from +z: floor, back, left, right, ceiling, and a lamp under the ceiling facing down.
  std::ofstream(dir / "master" / "box.obj")
      << "mtllib box.mtl\nv -1 0 -1\nv 1 0 -1\nv 1 0 1\nv -1 0 1\nv -1 2 -1\nv 1 2 -1\nv 1 2 1\nv -1 2 1\n"
         "v -0.3 1.99 -0.3\nv 0.3 1.99 -0.3\nv 0.3 1.99 0.3\nv -0.3 1.99 0.3\nvt 0 0\nvt 2 0\nvt 2 2\nvt 0 2\n"
         "usemtl floor\nf 4/1 3/2 2/3 1/4\nusemtl wall\nf 1 2 6 5\nf 4 1 5 8\nf 2 3 7 6\nf 5 6 7 8\n"
         "usemtl lamp\nf 9 10 11 12\n";
  const Image image = serve_to_a_worker_elsewhere(dir, (dir / "master" / "box.obj").string());
  EXPECT_GT(image.mean().x, 0.01f) << "lit by its Ke lamp";
}

}  // namespace
}  // namespace igi

namespace igi {
namespace {

// Running means a state other than Z (zombie: dead, waiting to be reaped) or gone.
bool running(int pid) {
  std::ifstream stat("/proc/" + std::to_string(pid) + "/stat");
  std::string line;
  if (!std::getline(stat, line)) return false;
  const size_t close = line.rfind(')');
  return close != std::string::npos && line.size() > close + 2 && line[close + 2] != 'Z';
}

TEST(Distributed, LocalWorkersDieWithAKilledMaster) {
  pid_t m = test::start(master("--workers 2 --frames 100000 --no-write --quiet -o " + test::output_path("orphans.exr")));
  std::vector<int> workers;
  // Whatever fails, nothing this test started outlives it: a master or a
  // worker left running holds ctest's output pipe open until the test's
  // timeout (600 s once, under ThreadSanitizer on a loaded machine).
  struct Cleanup {
    pid_t& master;
    std::vector<int>& workers;
    ~Cleanup() {
      test::stop(master);
      for (int w : workers)
        if (running(w)) kill(w, SIGKILL);
    }
  } cleanup{m, workers};
  // Sanitized builds start slowly: up to 30 s for both workers. Only
  // children that run igi-worker count: under ThreadSanitizer the master once
  // showed a third child (a fork not yet become a worker, or the
  // sanitizer's own), and the test failed on it.
  std::string children;
  for (int i = 0; i < 300 && workers.size() != 2; ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
    workers.clear();
    auto r = test::run("pgrep -P " + std::to_string(m) + " -f igi-worker", 5);
    std::istringstream pids(r.output);
    for (int pid; pids >> pid;) workers.push_back(pid);
    children = test::run("pgrep -a -P " + std::to_string(m), 5).output;
  }
  ASSERT_EQ(workers.size(), 2u) << "the master started its workers; its children:\n" << children;
  test::stop(m);  // SIGKILL: no chance to clean up
  m = 0;
  // They go at once (the kernel signals them when their parent dies); allow a loaded machine 5 s.
  for (int i = 0; i < 50 && std::any_of(workers.begin(), workers.end(), running); ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  for (int w : workers) EXPECT_FALSE(running(w)) << "worker " << w << " outlived its master";
}

// CancelFrame (the window's camera moved on): the worker drops the frame's
// jobs it has not started, whether they wait for the scene to load or for a
// render thread, and renders the next frame's as before. The test is the master.
TEST(Distributed, ACancelledFramesQueuedJobsAreNeverRendered) {
  zmq::context_t context;
  zmq::socket_t router(context, zmq::socket_type::router);
  router.set(zmq::sockopt::linger, 0);
  const std::string endpoint = "tcp://127.0.0.1:" + std::to_string(test::free_port());
  router.bind(endpoint);
  const pid_t worker = test::start(std::string(IGI_WORKER_BINARY) + " --connect " + endpoint + " --threads 1 --quiet");
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(60 * test::kSlowdown);
  std::string identity;
  while (identity.empty() && std::chrono::steady_clock::now() < end)
    if (auto r = protocol::receive(router, 100, true); r && r->message && std::holds_alternative<protocol::Hello>(*r->message))
      identity = r->identity;
  ASSERT_FALSE(identity.empty()) << "the worker says hello";
  protocol::Welcome welcome;
  welcome.session = 1;
  welcome.scene_name = "cornell";
  // Tiles slow enough (32 paths a set) that the cancel, sent just after the
  // jobs, reaches a loaded worker before it renders many: with 8 paths and
  // shadow packets a tile took about a millisecond, and under a full test
  // run the bound below failed once.
  welcome.settings = test::vpl_settings(MethodKind::Igi, 32);
  welcome.credits = protocol::kMaxCredits;
  welcome.timeout_ms = 60000;
  protocol::send_to(router, identity, welcome);

  constexpr int kTile = 16, kFrameHeight = 64, kJobs = (kWidth / kTile) * (kFrameHeight / kTile);
  FrameSetup frame = test::camera_frame(make_cornell_box(), kWidth, kFrameHeight);
  frame.want_surfaces = true;
  uint64_t job_id = 0;
  auto send_frame = [&](uint64_t id) {
    frame.frame_id = id;
    protocol::send_to(router, identity, protocol::FrameSetupMsg{frame, welcome.settings});
    for (int i = 0; i < kJobs; ++i)
      protocol::send_to(router, identity,
                        protocol::TileJobMsg{id, job_id++, {(i % (kWidth / kTile)) * kTile, (i / (kWidth / kTile)) * kTile,
                                                            kTile, kTile, 2}});
  };
  std::map<uint64_t, int> results;
  auto receive_frame = [&](uint64_t id) {
    while (results[id] < kJobs && std::chrono::steady_clock::now() < end)
      if (auto r = protocol::receive(router, 100, true); r && r->message)
        if (auto* t = std::get_if<protocol::TileResult>(&*r->message)) {
          ++results[t->frame_id];
          EXPECT_EQ(t->surfaces.size(), size_t(kTile) * kTile) << "the tile's interior, not its border";
        }
  };
  send_frame(0);
  protocol::send_to(router, identity, protocol::CancelFrame{0});  // the scene is still loading
  send_frame(1);
  receive_frame(1);
  send_frame(2);
  protocol::send_to(router, identity, protocol::CancelFrame{2});  // the render thread holds one of its jobs
  send_frame(3);
  receive_frame(3);
  test::stop(worker);
  EXPECT_EQ(results[1], kJobs);
  EXPECT_EQ(results[3], kJobs);
  EXPECT_LE(results[0] + results[2], 4) << "only tiles already rendering when the cancel came";
}

}  // namespace
}  // namespace igi
