// The master's scheduling rules, one test each, without sockets.
#include <gtest/gtest.h>

#include "scheduler.h"

namespace igi {
namespace {

std::vector<TileJob> tiles(int n) {
  std::vector<TileJob> t;
  for (int i = 0; i < n; ++i) t.push_back({8 * i, 0, 8, 8, 1});
  return t;
}

TEST(Scheduler, WorkersHoldAtMostTheirCredits) {
  Scheduler s(2, 2);
  s.add_worker("a");
  s.add_frame(0, tiles(5));
  EXPECT_TRUE(s.next_job("a"));
  EXPECT_TRUE(s.next_job("a"));
  EXPECT_FALSE(s.next_job("a")) << "third job beyond 2 credits";
  EXPECT_EQ(s.outstanding("a"), 2);
}

TEST(Scheduler, AFrameCompletesWhenEveryJobIsBackAndFramesComeInOrder) {
  Scheduler s(4, 2);
  s.add_worker("a");
  s.add_frame(0, tiles(2));
  s.add_frame(1, tiles(2));
  EXPECT_FALSE(s.can_add_frame()) << "two frames in flight at most";
  std::vector<JobAssignment> jobs;
  while (auto j = s.next_job("a")) jobs.push_back(*j);
  ASSERT_EQ(jobs.size(), 4u) << "the next frame's jobs go out while the first is unfinished";
  EXPECT_EQ(jobs[0].frame_id, 0u);
  EXPECT_EQ(jobs[3].frame_id, 1u);
  // Frame 1 finishes first but is reported only after frame 0.
  s.on_result("a", jobs[2].job_id, 7);
  s.on_result("a", jobs[3].job_id, 7);
  EXPECT_TRUE(s.take_completed_frames().empty());
  s.on_result("a", jobs[0].job_id, 7);
  s.on_result("a", jobs[1].job_id, 7);
  EXPECT_EQ(s.take_completed_frames(), (std::vector<uint64_t>{0, 1}));
}

TEST(Scheduler, ADeadWorkersJobsAreIssuedAgain) {
  Scheduler s(2, 2);
  s.add_worker("a");
  s.add_worker("b");
  s.add_frame(0, tiles(2));
  auto ja = s.next_job("a");
  auto jb = s.next_job("a");
  ASSERT_TRUE(ja && jb);
  s.remove_worker("a");
  EXPECT_EQ(s.stats().reissued, 2u);
  auto again = s.next_job("b");
  ASSERT_TRUE(again);
  EXPECT_EQ(again->job_id, ja->job_id) << "lost jobs go to the front";
  EXPECT_FALSE(again->duplicate);
}

TEST(Scheduler, IdleWorkersDuplicateStragglersAndTheFirstResultWins) {
  Scheduler s(1, 2);
  s.add_worker("slow");
  s.add_worker("fast");
  s.add_frame(0, tiles(1));
  auto original = s.next_job("slow");
  auto copy = s.next_job("fast");
  ASSERT_TRUE(original && copy);
  EXPECT_TRUE(copy->duplicate);
  EXPECT_EQ(copy->job_id, original->job_id);
  EXPECT_EQ(s.on_result("fast", copy->job_id, 1), ResultVerdict::Accepted);
  EXPECT_EQ(s.on_result("slow", original->job_id, 1), ResultVerdict::Duplicate);
  EXPECT_EQ(s.stats().late_dropped, 1u);
  EXPECT_EQ(s.take_completed_frames().size(), 1u);
}

TEST(Scheduler, NoMoreThanTwoCopiesOfAJob) {
  Scheduler s(1, 2);
  for (const char* w : {"a", "b", "c"}) s.add_worker(w);
  s.add_frame(0, tiles(1));
  EXPECT_TRUE(s.next_job("a"));
  EXPECT_TRUE(s.next_job("b"));
  EXPECT_FALSE(s.next_job("c"));
}

TEST(Scheduler, ADivergingVplHashBansTheWorkerAndReissuesItsJobs) {
  Scheduler s(2, 2);
  s.add_worker("good");
  s.add_worker("bad");
  s.add_frame(0, tiles(4));
  auto g = s.next_job("good");
  auto b1 = s.next_job("bad");
  auto b2 = s.next_job("bad");
  EXPECT_EQ(s.on_result("good", g->job_id, 42), ResultVerdict::Accepted);
  EXPECT_EQ(s.on_result("bad", b1->job_id, 43), ResultVerdict::HashMismatch);
  EXPECT_FALSE(s.has_worker("bad"));
  EXPECT_FALSE(s.next_job("bad")) << "a banned worker gets no more work";
  std::set<uint64_t> handed;
  while (auto j = s.next_job("good")) {
    handed.insert(j->job_id);
    s.on_result("good", j->job_id, 42);
  }
  EXPECT_TRUE(handed.count(b1->job_id) && handed.count(b2->job_id)) << "the banned worker's jobs go out again";
  EXPECT_EQ(s.take_completed_frames().size(), 1u);
}

TEST(Scheduler, UnknownAndLateResultsAreHarmless) {
  Scheduler s(2, 2);
  s.add_worker("a");
  EXPECT_EQ(s.on_result("a", 999, 0), ResultVerdict::Unknown);
  EXPECT_EQ(s.on_result("ghost", 999, 0), ResultVerdict::Unknown);
}

}  // namespace
}  // namespace igi
