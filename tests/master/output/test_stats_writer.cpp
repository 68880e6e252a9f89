// igi-master's --stats writer (master/output/stats_writer.h): frame lines reach the
// file by count and by time without a totals write, so a killed master leaves
// all but the last second's and a long run holds no growing backlog.
#include <chrono>
#include <thread>

#include <gtest/gtest.h>

#include "output/stats_writer.h"
#include "support/image_compare.h"
#include "support/sanitizers.h"
#include "support/stats_file.h"

namespace igi {
namespace {

using Clock = std::chrono::steady_clock;

size_t frame_lines(const std::string& path) { return test::read_stats(path)["frames"].size(); }

// Polls the file until it holds `count` frame lines or `seconds` pass.
bool wait_for_frames(const std::string& path, size_t count, double seconds) {
  const auto end = Clock::now() + std::chrono::duration<double>(seconds);
  while (Clock::now() < end) {
    if (frame_lines(path) >= count) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  return frame_lines(path) >= count;
}

TEST(StatsWriter, AFewFramesReachTheFileWithinASecondWithoutATotalsWrite) {
  const std::string path = test::output_path("stats-writer-time.jsonl");
  StatsWriter writer(path);
  for (uint64_t i = 0; i < 3; ++i) writer.add(FrameRecord{.frame_id = i, .tiles = 4});
  const auto start = Clock::now();
  ASSERT_TRUE(wait_for_frames(path, 3, 5.0 * test::kSlowdown)) << "the records wait for a totals write";
  const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
  EXPECT_LE(seconds, 3.0 * test::kSlowdown) << "appended about once a second";
  EXPECT_FALSE(test::read_stats(path).contains("complete")) << "no totals line was asked for";
}

TEST(StatsWriter, ManyFramesAreAppendedByCountLongBeforeTheSecondIsUp) {
  const std::string path = test::output_path("stats-writer-count.jsonl");
  StatsWriter writer(path);
  const size_t n = 4 * StatsWriter::kFlushRecords;
  for (uint64_t i = 0; i < n; ++i) writer.add(FrameRecord{.frame_id = i, .tiles = 1});
  // By count: each kFlushRecords wakes the writer; only the last second's timer would write the rest.
  ASSERT_TRUE(wait_for_frames(path, n - StatsWriter::kFlushRecords, 0.5 * test::kSlowdown))
      << frame_lines(path) << " of " << n << " frame lines after 0.5 s";
  RunTotals totals;
  writer.write_final(totals);
  const nlohmann::json stats = test::read_stats(path);
  ASSERT_EQ(stats["frames"].size(), n);
  for (size_t i = 0; i < n; ++i) ASSERT_EQ(stats["frames"][i]["frame"].get<uint64_t>(), i) << "in order";
  EXPECT_EQ(stats["tiles"].get<uint64_t>(), n);
}

// More records than may wait: add() waits for the file instead of holding them all.
TEST(StatsWriter, MoreRecordsThanMayWaitAreAllWrittenInOrder) {
  const std::string path = test::output_path("stats-writer-bound.jsonl");
  StatsWriter writer(path);
  const size_t n = 3 * StatsWriter::kMaxPending + 7;
  for (uint64_t i = 0; i < n; ++i) writer.add(FrameRecord{.frame_id = i, .tiles = 1});
  writer.write_final(RunTotals{});
  const nlohmann::json stats = test::read_stats(path);
  ASSERT_EQ(stats["frames"].size(), n);
  for (size_t i = 0; i < n; ++i) ASSERT_EQ(stats["frames"][i]["frame"].get<uint64_t>(), i);
}

}  // namespace
}  // namespace igi
