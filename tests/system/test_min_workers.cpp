// igi-master --min-workers: the first frame waits until that many workers have
// joined (what the cluster launchers rely on), and no longer than
// --min-workers-wait seconds.
#include <chrono>
#include <thread>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <sys/wait.h>

#include "support/image_compare.h"
#include "support/process.h"
#include "support/stats_file.h"

namespace igi {
namespace {

std::string master(const std::string& endpoint, const std::string& extra) {
  return std::string(IGI_MASTER_BINARY) + " --scene cornell --method igi --vpl-paths 8 --size 96x72 --tile 16 --workers 0 "
         "--quiet --no-write --listen " + endpoint + " " + extra;
}

std::string worker(const std::string& endpoint) {
  return std::string(IGI_WORKER_BINARY) + " --connect " + endpoint + " --threads 1 --quiet";
}

// Without the option the first worker renders the first frames alone (they
// take milliseconds), so a second worker 1 s later would miss frame 0.
TEST(MinWorkers, FirstFrameWaitsForEveryWorker) {
  const std::string endpoint = "tcp://127.0.0.1:" + std::to_string(test::free_port());
  const std::string stats = test::output_path("min-workers.json");
  pid_t m = test::start(master(endpoint, "--frames 3 --min-workers 2 --stats " + stats));
  pid_t first = test::start(worker(endpoint));
  std::this_thread::sleep_for(std::chrono::seconds(1));
  pid_t second = test::start(worker(endpoint));
  EXPECT_EQ(test::wait_exit(m, 60), 0);
  EXPECT_EQ(test::wait_exit(first, 20), 0);
  EXPECT_EQ(test::wait_exit(second, 20), 0);
  const nlohmann::json s = test::read_stats(stats);
  ASSERT_EQ(s["frames"].size(), 3u);
  EXPECT_EQ(s["frames"][0]["workers"].size(), 2u) << "both workers rendered frame 0: " << s["frames"][0]["workers"];
}

TEST(MinWorkers, StartsWithThoseThereAfterTheWait) {
  const std::string endpoint = "tcp://127.0.0.1:" + std::to_string(test::free_port());
  pid_t w = test::start(worker(endpoint));
  const auto start = std::chrono::steady_clock::now();
  auto r = test::run(master(endpoint, "--frames 2 --min-workers 3 --min-workers-wait 1"), 60);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_EQ(test::wait_exit(w, 20), 0);
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("only 1 of 3 workers joined in 1 s"), std::string::npos) << r.output;
  EXPECT_GE(seconds, 1.0) << "it waited for the missing workers";
}

TEST(MinWorkers, BadValueIsNamed) {
  auto r = test::run(std::string(IGI_MASTER_BINARY) + " --min-workers two --frames 1", 30);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.output.find("--min-workers"), std::string::npos) << r.output;
}

}  // namespace
}  // namespace igi
