// Trust that a slow worker, two colluding keys or a flood of results cannot
// break (issue 64), on plain inputs: the scheduler and its referee
// (master/trust/referee.h) without sockets or clocks, and the header a result
// is looked up by. The same cases with real processes: Scale.* (test_scale.cpp).
#include <gtest/gtest.h>

#include "protocol/codec.h"
#include "scheduler/scheduler.h"

namespace igi {
namespace {

std::vector<TileJob> tiles(int n) {
  std::vector<TileJob> t;
  for (int i = 0; i < n; ++i) t.push_back({8 * i, 0, 8, 8, 1});
  return t;
}

const TimePoint t0 = TimePoint{} + std::chrono::hours(1);
TimePoint at(double ms) {
  return t0 + std::chrono::duration_cast<SchedulerClock::duration>(std::chrono::duration<double, std::milli>(ms));
}

// Case 4: a result is looked up by its job before anything is unpacked, and
// a result for a job its sender was never given is told from a late one.
TEST(Trust, AResultIsLookedUpByAJobItsSenderWasGivenBeforeAnythingIsUnpacked) {
  Scheduler s(1, 2);
  s.add_worker("a");
  s.add_worker("b");
  s.add_frame(0, tiles(2));
  const std::vector<JobAssignment> jobs = s.assign(at(0));
  ASSERT_EQ(jobs.size(), 2u);
  const JobAssignment& mine = jobs[0].worker == "a" ? jobs[0] : jobs[1];
  const JobAssignment& theirs = jobs[0].worker == "a" ? jobs[1] : jobs[0];
  EXPECT_TRUE(s.was_given("a", mine.job_id));
  EXPECT_FALSE(s.was_given("a", theirs.job_id)) << "another worker's job";
  EXPECT_FALSE(s.was_given("a", uint64_t(1) << 40)) << "a job never issued";
  s.cancel_frame(0);
  EXPECT_EQ(s.check_result("a", mine.job_id, 0, mine.tile), ResultCheck::Unknown);
  EXPECT_TRUE(s.was_given("a", mine.job_id)) << "a late result of its own is stale, not foreign";

  // A decompression bomb: 1024 x 1024 float pixels and surfaces packed into a few hundred bytes.
  protocol::TileResult bomb;
  bomb.frame_id = 3;
  bomb.job_id = 9;
  bomb.tile = {0, 0, 1024, 1024, 0};
  bomb.pixel_format = PixelFormat::Float32;
  bomb.pixel_codec = protocol::PixelCodec::Zstd;
  bomb.pixels.assign(size_t(1024) * 1024, glm::vec3(0.0f));
  bomb.surfaces.assign(size_t(1024) * 1024, PixelSurface{});
  const std::vector<uint8_t> bytes = protocol::encode(bomb);
  EXPECT_LT(bytes.size(), 4096u);
  // Cut right after the rectangle: the header read needs nothing more, the full decode fails.
  const size_t head_bytes = 8 + 8 + 8 + 5 * 4;
  const std::span<const uint8_t> cut(bytes.data(), head_bytes);
  std::string error;
  const std::optional<protocol::TileResultHead> head = protocol::tile_result_head(cut, error);
  ASSERT_TRUE(head) << error;
  EXPECT_EQ(head->frame_id, 3u);
  EXPECT_EQ(head->job_id, 9u);
  EXPECT_EQ(head->tile.w, 1024);
  EXPECT_FALSE(protocol::decode_tile_result(cut, error));
  EXPECT_FALSE(protocol::tile_result_head({bytes.data(), head_bytes - 1}, error));
  EXPECT_NE(error.find("tile.border"), std::string::npos) << error;
}

}  // namespace
}  // namespace igi
