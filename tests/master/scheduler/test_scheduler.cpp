// The master's scheduling rules, one test each, without sockets or clocks.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <map>
#include <set>
#include <queue>

#include "scheduler/scheduler.h"

namespace igi {
namespace {

WorkerId worker_name(int i) {
  char name[16];
  std::snprintf(name, sizeof name, "w%d", i);
  return name;
}

std::vector<TileJob> tiles(int n) {
  std::vector<TileJob> t;
  for (int i = 0; i < n; ++i) t.push_back({8 * i, 0, 8, 8, 1});
  return t;
}

const TimePoint t0 = TimePoint{} + std::chrono::hours(1);
TimePoint at(double ms) {
  return t0 + std::chrono::duration_cast<SchedulerClock::duration>(std::chrono::duration<double, std::milli>(ms));
}

std::vector<JobAssignment> for_worker(const std::vector<JobAssignment>& all, const WorkerId& id) {
  std::vector<JobAssignment> mine;
  for (const JobAssignment& a : all)
    if (a.worker == id) mine.push_back(a);
  return mine;
}

// Answers every job in `jobs` with `hash` at time `when`.
void answer(Scheduler& s, const std::vector<JobAssignment>& jobs, uint64_t hash, TimePoint when) {
  for (const JobAssignment& j : jobs) {
    ASSERT_EQ(s.check_result(j.worker, j.job_id, j.frame_id, j.tile), ResultCheck::Wanted);
    s.on_result(j.worker, j.job_id, hash, when);
  }
}

// Answers copies of jobs another result already answered (their hash still votes).
void answer_late(Scheduler& s, const std::vector<JobAssignment>& jobs, uint64_t hash, TimePoint when) {
  for (const JobAssignment& j : jobs) {
    ASSERT_EQ(s.check_result(j.worker, j.job_id, j.frame_id, j.tile), ResultCheck::NotNeeded);
    s.on_result(j.worker, j.job_id, hash, when);
  }
}

TEST(Scheduler, WorkersHoldAtMostTheirCredits) {
  Scheduler s(2, 2);
  s.add_worker("a");
  s.add_frame(0, tiles(5));
  EXPECT_EQ(s.assign(at(0)).size(), 2u) << "two credits, two jobs";
  EXPECT_TRUE(s.assign(at(1)).empty()) << "no third job beyond 2 credits";
  EXPECT_EQ(s.outstanding("a"), 2);
}

TEST(Scheduler, JobsSpreadOverWorkersOneARound) {
  Scheduler s(4, 2);
  for (const char* w : {"a", "b", "c"}) s.add_worker(w);
  s.add_frame(0, tiles(6));
  const auto jobs = s.assign(at(0));
  ASSERT_EQ(jobs.size(), 6u);
  for (const char* w : {"a", "b", "c"}) EXPECT_EQ(s.outstanding(w), 2) << w;
}

TEST(Scheduler, AFrameCompletesWhenEveryJobIsBackAndFramesComeInOrder) {
  Scheduler s(4, 2);
  s.add_worker("a");
  s.add_frame(0, tiles(2));
  s.add_frame(1, tiles(2));
  EXPECT_FALSE(s.can_add_frame()) << "two frames in flight at most";
  const std::vector<JobAssignment> jobs = s.assign(at(0));
  ASSERT_EQ(jobs.size(), 4u) << "the next frame's jobs go out while the first is unfinished";
  EXPECT_EQ(jobs[0].frame_id, 0u);
  EXPECT_EQ(jobs[3].frame_id, 1u);
  // Frame 1 finishes first but is reported only after frame 0.
  answer(s, {jobs[2], jobs[3]}, 7, at(1));
  EXPECT_TRUE(s.take_completed_frames().empty());
  answer(s, {jobs[0], jobs[1]}, 7, at(2));
  EXPECT_EQ(s.take_completed_frames(), (std::vector<uint64_t>{0, 1}));
}

TEST(Scheduler, ADeadWorkersJobsAreIssuedAgain) {
  Scheduler s(2, 2);
  s.add_worker("a");
  s.add_frame(0, tiles(2));
  const auto lost = s.assign(at(0));
  ASSERT_EQ(lost.size(), 2u);
  s.add_worker("b");
  s.remove_worker("a");
  EXPECT_EQ(s.stats().reissued, 2u);
  const auto again = s.assign(at(1));
  ASSERT_EQ(again.size(), 2u);
  EXPECT_EQ(again[0].job_id, lost[0].job_id) << "lost jobs go to the front, oldest first";
  EXPECT_FALSE(again[0].duplicate);
}

// Twenty round trips of 10 ms make the median 10 ms: a job is late after 30 ms.
void learn_round_trips(Scheduler& s, double& clock_ms) {
  s.add_frame(99, tiles(20));
  for (int i = 0; i < 20; ++i) {
    auto jobs = s.assign(at(clock_ms));
    ASSERT_EQ(jobs.size(), 1u);
    clock_ms += 10;
    answer(s, jobs, 1, at(clock_ms));
  }
  ASSERT_EQ(s.take_completed_frames().size(), 1u);
}

TEST(Scheduler, AStragglerIsCopiedOnlyOnceOlderThanThreeMedianRoundTrips) {
  Scheduler s(1, 2);
  s.add_worker("slow");
  double clock = 0;
  learn_round_trips(s, clock);
  EXPECT_NEAR(s.median_round_trip(), 0.010, 1e-9);
  s.add_worker("fast");
  s.add_frame(0, tiles(1));
  const auto original = s.assign(at(clock));
  ASSERT_EQ(original.size(), 1u);
  EXPECT_TRUE(s.assign(at(clock + 29)).empty()) << "not late yet: younger than 3 x 10 ms";
  ASSERT_TRUE(s.next_straggler_time(at(clock + 29)));
  EXPECT_EQ(*s.next_straggler_time(at(clock + 29)), at(clock + 30));
  const auto copy = s.assign(at(clock + 31));
  ASSERT_EQ(copy.size(), 1u);
  EXPECT_EQ(copy[0].worker, original[0].worker == "slow" ? "fast" : "slow");
  EXPECT_TRUE(copy[0].duplicate);
  EXPECT_EQ(copy[0].job_id, original[0].job_id);
  EXPECT_EQ(s.stats().duplicated, 1u);
  answer(s, copy, 1, at(clock + 35));
  EXPECT_EQ(s.check_result(original[0].worker, original[0].job_id, 0, original[0].tile), ResultCheck::NotNeeded);
  EXPECT_EQ(s.on_result(original[0].worker, original[0].job_id, 1, at(clock + 60)), ResultVerdict::Late);
  EXPECT_EQ(s.stats().late_dropped, 1u);
  EXPECT_EQ(s.take_completed_frames().size(), 1u);
}

// A peer that heartbeats and takes jobs but never answers: its jobs are
// copied to the honest worker; overtaken twice, it is benched, its jobs go to
// others and it gets none, so later frames need no copies at all. A result
// of its own (late) brings it back, from one job.
TEST(Scheduler, AHoarderOvertakenTwiceIsBenchedAndLaterFramesNeedNoCopies) {
  Scheduler s(1, 2);
  s.add_worker("honest");
  double clock = 0;
  learn_round_trips(s, clock);  // 10 ms tiles: late after 30 ms
  s.judge_by_reference();       // as the master does: a frame needs no second voter
  s.add_worker("hoarder");
  // Runs a frame: the honest worker answers each job 10 ms after it gets it.
  auto run_frame = [&](uint64_t frame_id, int jobs) {
    s.add_frame(frame_id, tiles(jobs));
    s.set_reference(frame_id, 1);
    std::vector<JobAssignment> honest;
    for (int step = 0; step < 200 && s.take_completed_frames().empty(); ++step) {
      for (const JobAssignment& j : s.assign(at(clock)))
        if (j.worker == "honest") honest.push_back(j);
      clock += 10;
      for (const JobAssignment& j : std::exchange(honest, {}))
        if (s.check_result(j.worker, j.job_id, j.frame_id, j.tile) == ResultCheck::Wanted ||
            s.check_result(j.worker, j.job_id, j.frame_id, j.tile) == ResultCheck::NotNeeded)
          s.on_result(j.worker, j.job_id, 1, at(clock));
    }
  };
  run_frame(0, 4);
  EXPECT_TRUE(s.take_benched().empty()) << "overtaken once: a slow worker may be";
  run_frame(1, 4);
  EXPECT_EQ(s.take_benched(), std::vector<WorkerId>{"hoarder"});
  EXPECT_EQ(s.stats().benched, 1u);
  EXPECT_EQ(s.outstanding("hoarder"), 0) << "its jobs went back";
  const uint64_t copies = s.stats().duplicated;
  EXPECT_GE(copies, 1u);
  run_frame(2, 4);
  run_frame(3, 4);
  EXPECT_EQ(s.stats().duplicated, copies) << "a benched worker holds nothing a frame must wait for";
  EXPECT_EQ(s.outstanding("hoarder"), 0);
  s.heard_result("hoarder");  // a late result of its own
  s.add_frame(4, tiles(4));
  const auto back = for_worker(s.assign(at(clock)), "hoarder");
  EXPECT_EQ(back.size(), 1u) << "back, with one job";
}

TEST(Scheduler, NoMoreThanTwoCopiesOfAJob) {
  Scheduler s(1, 2);
  for (const char* w : {"a", "b", "c"}) s.add_worker(w);
  s.add_frame(0, tiles(1));
  EXPECT_EQ(s.assign(at(0)).size(), 1u);
  EXPECT_EQ(s.assign(at(5000)).size(), 1u) << "one copy of a late job";
  EXPECT_TRUE(s.assign(at(10000)).empty()) << "no third";
}

TEST(Scheduler, CopiesPerFrameStayWithinTheBudget) {
  SchedulerConfig c;
  c.credits = 1;
  c.duplicate_budget = 0.1;  // 20 jobs: at most 2 copies
  Scheduler s(c);
  for (int i = 0; i < 40; ++i) s.add_worker(worker_name(i));
  s.add_frame(0, tiles(20));
  EXPECT_EQ(s.assign(at(0)).size(), 20u);
  EXPECT_EQ(s.assign(at(5000)).size(), 2u) << "20 late jobs, 20 idle workers, a budget of 2";
  EXPECT_EQ(s.stats().duplicated, 2u);
}

// Eight workers that each take 10 ms a tile, 50 frames of 30 tiles: the
// frames complete, and no tile is ever handed out twice.
TEST(Scheduler, EquallyFastWorkersNeverRenderATileTwice) {
  Scheduler s(2, 2);
  for (int i = 0; i < 8; ++i) s.add_worker(worker_name(i));
  using Due = std::pair<double, JobAssignment>;
  auto later = [](const Due& a, const Due& b) { return a.first > b.first; };
  std::priority_queue<Due, std::vector<Due>, decltype(later)> due(later);
  std::map<WorkerId, double> free_at;  // each worker renders one tile at a time
  int next_frame = 0, completed = 0;
  double clock = 0;
  while (completed < 50) {
    while (next_frame < 50 && s.can_add_frame()) s.add_frame(uint64_t(next_frame++), tiles(30));
    for (const JobAssignment& j : s.assign(at(clock))) {
      const double start = std::max(clock, free_at[j.worker]);
      free_at[j.worker] = start + 10;
      due.push({start + 10, j});
    }
    ASSERT_FALSE(due.empty()) << "nothing in flight at " << clock << " ms";
    clock = due.top().first;
    const JobAssignment j = due.top().second;
    due.pop();
    EXPECT_EQ(s.check_result(j.worker, j.job_id, j.frame_id, j.tile), ResultCheck::Wanted);
    s.on_result(j.worker, j.job_id, 42, at(clock));
    completed += int(s.take_completed_frames().size());
  }
  EXPECT_EQ(s.stats().duplicated, 0u);
  EXPECT_EQ(s.stats().verified, 0u);
  EXPECT_EQ(s.stats().late_dropped, 0u);
}

// Always more work than credit (the copies' queue was only trimmed when a
// worker had nothing to do, and grew by a copy a tile): 2,000 frames later
// the bookkeeping holds what is in flight and no more.
TEST(Scheduler, BookkeepingStaysBoundedOverThousandsOfFrames) {
  Scheduler s(2, 2);
  s.add_worker("a");
  s.add_worker("b");
  size_t most_copies = 0, most_jobs = 0;
  int next = 0;
  double clock = 0;
  for (int completed = 0; completed < 2000;) {
    while (s.can_add_frame()) s.add_frame(uint64_t(next++), tiles(8));
    const auto jobs = s.assign(at(clock));
    ASSERT_FALSE(jobs.empty());
    clock += 1;
    answer(s, jobs, 3, at(clock));
    completed += int(s.take_completed_frames().size());
    most_copies = std::max(most_copies, s.tracked_copies());
    most_jobs = std::max(most_jobs, s.tracked_jobs());
  }
  EXPECT_LE(most_copies, 8u) << "copies tracked: at most those in flight, and the frame's";
  EXPECT_LE(most_jobs, 2u * 16u) << "two open frames of 8 jobs, each at most once in the pool";
}

TEST(Scheduler, AWrongFirstHashQuarantinesOnlyTheDivergingWorker) {
  Scheduler s(2, 2);
  for (const char* w : {"bad", "good1", "good2"}) s.add_worker(w);
  s.add_frame(0, tiles(6));
  const auto jobs = s.assign(at(0));
  ASSERT_EQ(jobs.size(), 6u);
  const auto bad = for_worker(jobs, "bad"), good1 = for_worker(jobs, "good1"), good2 = for_worker(jobs, "good2");
  // The diverging worker answers first: its result is held, not believed.
  EXPECT_EQ(s.on_result("bad", bad[0].job_id, 666, at(1)), ResultVerdict::Held);
  EXPECT_EQ(s.on_result("good1", good1[0].job_id, 42, at(2)), ResultVerdict::Held) << "one against one: undecided";
  EXPECT_TRUE(s.take_quarantined().empty());
  // A second worker agrees with good1: 42 is the reference, "bad" is quarantined.
  EXPECT_EQ(s.on_result("good2", good2[0].job_id, 42, at(3)), ResultVerdict::Accepted);
  EXPECT_EQ(s.take_quarantined(), std::vector<WorkerId>{"bad"});
  EXPECT_FALSE(s.has_worker("bad"));
  EXPECT_TRUE(s.has_worker("good1") && s.has_worker("good2"));
  EXPECT_EQ(s.stats().quarantined, 1u);
  // good1's held result now counts; bad's two jobs (held and outstanding) go out again.
  answer(s, {good1[1], good2[1]}, 42, at(4));
  auto again = s.assign(at(5));
  ASSERT_EQ(again.size(), 2u);
  std::set<uint64_t> reissued{again[0].job_id, again[1].job_id};
  EXPECT_EQ(reissued, (std::set<uint64_t>{bad[0].job_id, bad[1].job_id}));
  answer(s, again, 42, at(6));
  EXPECT_EQ(s.take_completed_frames(), std::vector<uint64_t>{0});
}

TEST(Scheduler, TwoWorkersThatDisagreeWaitForAThird) {
  Scheduler s(1, 2);
  s.add_worker("a");
  s.add_worker("b");
  s.add_frame(0, tiles(3));
  const auto jobs = s.assign(at(0));
  ASSERT_EQ(jobs.size(), 2u);
  s.on_result("a", for_worker(jobs, "a")[0].job_id, 1, at(1));
  s.on_result("b", for_worker(jobs, "b")[0].job_id, 2, at(1));
  EXPECT_TRUE(s.take_quarantined().empty()) << "one against one: nobody can tell who is right";
  std::optional<HashSplit> split = s.stalled_split();
  ASSERT_TRUE(split) << "both workers voted, the frame cannot be decided";
  EXPECT_EQ(split->voters.size(), 2u);
  // A third worker agrees with b.
  s.add_worker("c");
  answer(s, s.assign(at(2)), 2, at(3));
  EXPECT_EQ(s.take_quarantined(), std::vector<WorkerId>{"a"});
  EXPECT_FALSE(s.stalled_split());
}

TEST(Scheduler, ALoneWorkerDecidesOnceItHasAnsweredEveryJobButJudgesNoNewcomer) {
  Scheduler s(4, 2);
  s.add_worker("a");
  s.add_frame(0, tiles(3));
  const auto j = s.assign(at(0));
  ASSERT_EQ(j.size(), 3u);
  EXPECT_EQ(s.on_result("a", j[0].job_id, 5, at(1)), ResultVerdict::Held) << "another worker may still come";
  EXPECT_EQ(s.on_result("a", j[1].job_id, 5, at(1)), ResultVerdict::Held);
  EXPECT_EQ(s.on_result("a", j[2].job_id, 5, at(1)), ResultVerdict::Accepted) << "all answered, nobody else: decided";
  EXPECT_EQ(s.take_completed_frames().size(), 1u);
  // A newcomer that computes other VPL sets is not judged by a hash nobody confirmed: a tie.
  s.add_worker("b");
  s.add_frame(1, tiles(2));
  const auto jobs = s.assign(at(2));
  ASSERT_EQ(jobs.size(), 2u);
  EXPECT_EQ(s.on_result("a", for_worker(jobs, "a")[0].job_id, 5, at(3)), ResultVerdict::Held);
  EXPECT_EQ(s.on_result("b", for_worker(jobs, "b")[0].job_id, 6, at(3)), ResultVerdict::Held);
  EXPECT_TRUE(s.take_quarantined().empty());
  EXPECT_TRUE(s.stalled_split());
}

// Two peers that agree on a made-up hash and answer first (the sybil pair):
// judged by the master's own hash, they lose however many they are.
TEST(Scheduler, WithTheMastersHashNoNumberOfAgreeingWorkersOutvotesIt) {
  SchedulerConfig config;
  config.credits = 1;
  config.master_reference = true;
  Scheduler s(config);
  for (const char* w : {"fake1", "fake2", "honest"}) s.add_worker(w);
  s.add_frame(0, tiles(3));
  const auto jobs = s.assign(at(0));
  ASSERT_EQ(jobs.size(), 3u);
  EXPECT_EQ(s.on_result("fake1", for_worker(jobs, "fake1")[0].job_id, 666, at(1)), ResultVerdict::Held);
  EXPECT_EQ(s.on_result("fake2", for_worker(jobs, "fake2")[0].job_id, 666, at(1)), ResultVerdict::Held)
      << "two agree, but only the master's hash decides";
  EXPECT_EQ(s.on_result("honest", for_worker(jobs, "honest")[0].job_id, 42, at(2)), ResultVerdict::Held);
  EXPECT_TRUE(s.take_quarantined().empty());
  EXPECT_TRUE(s.assign(at(3)).empty()) << "no verification copies: votes decide nothing";
  EXPECT_FALSE(s.stalled_split());
  s.set_reference(0, 42);
  std::vector<WorkerId> out = s.take_quarantined();
  std::sort(out.begin(), out.end());
  EXPECT_EQ(out, (std::vector<WorkerId>{"fake1", "fake2"}));
  // The fakes' two jobs go to the honest worker, one at a time; a wrong hash now is rejected at once.
  s.add_worker("late-fake");
  const auto again = s.assign(at(4));
  ASSERT_EQ(again.size(), 2u);
  for (const JobAssignment& j : again)
    EXPECT_EQ(s.on_result(j.worker, j.job_id, j.worker == "honest" ? 42 : 666, at(5)),
              j.worker == "honest" ? ResultVerdict::Accepted : ResultVerdict::Rejected);
  answer(s, s.assign(at(6)), 42, at(7));
  EXPECT_EQ(s.take_completed_frames(), std::vector<uint64_t>{0});
  EXPECT_EQ(s.stats().verified, 0u);
}

// The caller is the odd one out: its two workers agree on another hash. The
// frame is disputed, no one is quarantined, and once the caller follows them
// the frame completes with theirs, and later frames are decided by vote.
TEST(Scheduler, TwoWorkersThatAgreeAgainstTheCallerDisputeTheFrame) {
  SchedulerConfig config;
  config.credits = 1;
  config.master_reference = true;
  Scheduler s(config);
  s.add_worker("a", 0, "key-a");  // two independent authenticated keys
  s.add_worker("b", 0, "key-b");
  s.add_frame(0, tiles(3));
  const auto first = s.assign(at(0));
  ASSERT_EQ(first.size(), 2u);
  s.set_reference(0, 5);
  EXPECT_EQ(s.on_result("a", for_worker(first, "a")[0].job_id, 7, at(1)), ResultVerdict::Held);
  EXPECT_TRUE(s.take_disputes().empty()) << "b renders a job of the frame: its vote is awaited";
  EXPECT_TRUE(s.take_quarantined().empty());
  EXPECT_EQ(s.on_result("b", for_worker(first, "b")[0].job_id, 7, at(1)), ResultVerdict::Held);
  const auto disputes = s.take_disputes();
  ASSERT_EQ(disputes.size(), 1u);
  EXPECT_EQ(disputes[0].frame_id, 0u);
  EXPECT_EQ(disputes[0].callers_hash, 5u);
  EXPECT_EQ(disputes[0].workers_hash, 7u);
  EXPECT_EQ(disputes[0].workers.size(), 2u);
  EXPECT_TRUE(s.take_quarantined().empty());
  s.follow_workers();
  answer(s, s.assign(at(2)), 7, at(3));
  EXPECT_EQ(s.take_completed_frames(), std::vector<uint64_t>{0});
  s.add_frame(1, tiles(2));
  answer(s, s.assign(at(4)), 7, at(5));
  EXPECT_EQ(s.take_completed_frames(), std::vector<uint64_t>{1}) << "by vote, no caller's hash awaited";
  EXPECT_TRUE(s.take_quarantined().empty());
}

// One worker against the caller is no dispute (it could be a fake, or
// faulty): it is quarantined as soon as no other worker's vote is awaited;
// and a second that agrees with the caller settles it at once.
TEST(Scheduler, OneWorkerAgainstTheCallerIsQuarantinedNotADispute) {
  SchedulerConfig config;
  config.credits = 1;
  config.master_reference = true;
  Scheduler s(config);
  s.add_worker("a");
  s.add_worker("b");
  s.add_frame(0, tiles(2));
  const auto jobs = s.assign(at(0));
  s.set_reference(0, 5);
  EXPECT_EQ(s.on_result("a", for_worker(jobs, "a")[0].job_id, 7, at(1)), ResultVerdict::Held);
  EXPECT_TRUE(s.take_quarantined().empty()) << "b's vote is awaited";
  EXPECT_EQ(s.on_result("b", for_worker(jobs, "b")[0].job_id, 5, at(1)), ResultVerdict::Accepted);
  EXPECT_EQ(s.take_quarantined(), std::vector<WorkerId>{"a"});
  EXPECT_TRUE(s.take_disputes().empty());
}

// A frame whose hash the master could not compute falls back to a vote.
TEST(Scheduler, AFrameWithoutTheMastersHashIsDecidedByItsWorkers) {
  SchedulerConfig config;
  config.master_reference = true;
  Scheduler s(config);
  s.add_worker("a");
  s.add_worker("b");
  s.add_frame(0, tiles(2));
  answer(s, s.assign(at(0)), 5, at(1));
  EXPECT_TRUE(s.take_completed_frames().empty()) << "waits for the master's hash";
  s.set_reference(0, std::nullopt);
  EXPECT_EQ(s.take_completed_frames(), std::vector<uint64_t>{0}) << "two of two agree";
}

// Without the master's hash: a pair is no majority of four, so neither two
// fakes nor two honest workers decide, and no one is quarantined until a
// fifth worker makes a majority; the losers are never more than the winners.
TEST(Scheduler, ByVoteAHashNeedsAStrictMajorityOfThePossibleVoters) {
  Scheduler s(1, 2);
  for (const char* w : {"fake1", "fake2", "h1", "h2"}) s.add_worker(w);
  s.add_frame(0, tiles(5));
  const auto jobs = s.assign(at(0));
  ASSERT_EQ(jobs.size(), 4u);
  for (const char* w : {"fake1", "fake2"}) s.on_result(w, for_worker(jobs, w)[0].job_id, 666, at(1));
  EXPECT_TRUE(s.take_quarantined().empty()) << "two of four is no majority";
  for (const char* w : {"h1", "h2"}) s.on_result(w, for_worker(jobs, w)[0].job_id, 42, at(2));
  EXPECT_TRUE(s.take_quarantined().empty()) << "two against two: nobody can tell who is right";
  EXPECT_TRUE(s.stalled_split());
  s.add_worker("h3");
  answer(s, s.assign(at(3)), 42, at(4));
  std::vector<WorkerId> out = s.take_quarantined();
  std::sort(out.begin(), out.end());
  EXPECT_EQ(out, (std::vector<WorkerId>{"fake1", "fake2"})) << "three of five decide";
  EXPECT_FALSE(s.stalled_split());
}

TEST(Scheduler, AFrameAnsweredByOneWorkerGetsAVerificationCopy) {
  Scheduler s(4, 2);
  s.add_worker("a");
  s.add_worker("b");
  s.add_frame(0, tiles(1));
  const auto j = s.assign(at(0));
  ASSERT_EQ(j.size(), 1u);
  EXPECT_EQ(s.on_result(j[0].worker, j[0].job_id, 9, at(1)), ResultVerdict::Held);
  const auto verify = s.assign(at(2));
  ASSERT_EQ(verify.size(), 1u) << "the other worker votes on the frame";
  EXPECT_NE(verify[0].worker, j[0].worker);
  EXPECT_TRUE(verify[0].duplicate);
  EXPECT_EQ(s.stats().verified, 1u);
  EXPECT_EQ(s.check_result(verify[0].worker, verify[0].job_id, 0, verify[0].tile), ResultCheck::NotNeeded);
  EXPECT_EQ(s.on_result(verify[0].worker, verify[0].job_id, 9, at(3)), ResultVerdict::Late);
  EXPECT_EQ(s.take_completed_frames().size(), 1u) << "two votes: the held result counts";
}

TEST(Scheduler, ADeadVoterStillCountsSoTheSurvivorCannotDecideAlone) {
  Scheduler s(1, 2);
  s.add_worker("a");
  s.add_worker("b");
  s.add_frame(0, tiles(4));
  const auto jobs = s.assign(at(0));
  s.on_result("a", for_worker(jobs, "a")[0].job_id, 1, at(1));
  s.on_result("b", for_worker(jobs, "b")[0].job_id, 2, at(1));
  s.remove_worker("b");
  EXPECT_TRUE(s.take_quarantined().empty());
  EXPECT_TRUE(s.stalled_split()) << "a said 1, b said 2 before it died: still a tie";
}

// A peer that claims many threads and never answers (a hoarder) holds two
// jobs, not its threads' worth; one that answers gains a credit per result;
// a late job's copy goes to a worker that has answered, not to another newcomer.
TEST(Scheduler, ANewWorkerHoldsTwoJobsUntilItAnswersAndCopiesGoToProvenWorkers) {
  SchedulerConfig config;
  config.first_credits = 2;
  Scheduler s(config);
  s.add_worker("hoarder", 64);
  s.add_worker("w", 64);
  s.add_frame(0, tiles(6));
  const auto first = s.assign(at(0));
  EXPECT_EQ(for_worker(first, "hoarder").size(), 2u);
  EXPECT_EQ(for_worker(first, "w").size(), 2u);
  answer(s, for_worker(first, "w"), 5, at(1));
  const auto more = s.assign(at(1));
  EXPECT_EQ(for_worker(more, "w").size(), 2u) << "four credits now; two jobs were left";
  answer(s, more, 5, at(2));
  s.add_worker("newcomer", 64);
  const auto copies = s.assign(at(1500));  // the hoarder's jobs are late (1 s before round trips are known)
  ASSERT_EQ(copies.size(), 1u) << "one copy: the frame's budget";
  EXPECT_EQ(copies[0].worker, "w") << "a proven worker, not a silent newcomer";
  EXPECT_TRUE(copies[0].duplicate);
}

// A failed job goes to another worker, never back to the one that failed it
// (which takes the next job meanwhile).
TEST(Scheduler, AResultThatFailsValidationSendsItsJobToAnotherWorker) {
  Scheduler s(1, 2);
  s.add_worker("a");
  s.add_worker("b");
  s.add_frame(0, tiles(3));
  const auto first = s.assign(at(0));
  ASSERT_EQ(first.size(), 2u);
  const JobAssignment failed = for_worker(first, "a").at(0);
  s.on_bad_result("a", failed.job_id);
  EXPECT_EQ(s.outstanding("a"), 0) << "its credit is back";
  EXPECT_EQ(s.stats().reissued, 1u);
  const auto next = s.assign(at(1));
  ASSERT_EQ(next.size(), 1u);
  EXPECT_EQ(next[0].worker, "a");
  EXPECT_NE(next[0].job_id, failed.job_id) << "a takes the next job, not the one it failed";
  answer(s, for_worker(first, "b"), 5, at(2));
  const auto again = s.assign(at(2));
  ASSERT_EQ(again.size(), 1u);
  EXPECT_EQ(again[0].worker, "b");
  EXPECT_EQ(again[0].job_id, failed.job_id) << "b, which has not failed it, does";
  EXPECT_TRUE(s.take_own_jobs().empty()) << "one failure with another worker present: not the caller's";
  answer(s, again, 5, at(3));
  answer(s, next, 5, at(3));
  EXPECT_EQ(s.take_completed_frames(), std::vector<uint64_t>{0});
  EXPECT_EQ(s.stats().failed_results, 1u);
}

// Two workers failed it: the caller renders it, and its result completes the frame.
TEST(Scheduler, AJobTwoWorkersFailedIsTheCallers) {
  Scheduler s(1, 2);
  s.add_worker("a");
  s.add_worker("b");
  s.add_worker("c");
  s.add_frame(0, tiles(1));
  auto j = s.assign(at(0));
  ASSERT_EQ(j.size(), 1u);
  const uint64_t job = j[0].job_id;
  s.on_bad_result(j[0].worker, job);
  auto again = s.assign(at(1));
  ASSERT_EQ(again.size(), 1u);
  EXPECT_NE(again[0].worker, j[0].worker);
  EXPECT_TRUE(s.take_own_jobs().empty());
  s.on_bad_result(again[0].worker, job);
  EXPECT_TRUE(s.assign(at(2)).empty()) << "the third worker does not get it: two failed it";
  const auto own = s.take_own_jobs();
  ASSERT_EQ(own.size(), 1u);
  EXPECT_EQ(own[0].job_id, job);
  EXPECT_EQ(own[0].frame_id, 0u);
  EXPECT_TRUE(own[0].worker.empty());
  EXPECT_EQ(s.stats().own_jobs, 1u);
  const auto failers = s.failed_on(job);
  EXPECT_EQ(std::set<WorkerId>(failers.begin(), failers.end()), (std::set<WorkerId>{j[0].worker, again[0].worker}));
  EXPECT_TRUE(s.take_completed_frames().empty());
  EXPECT_TRUE(s.on_own_result(job));
  EXPECT_FALSE(s.on_own_result(job)) << "once";
  EXPECT_EQ(s.take_completed_frames(), std::vector<uint64_t>{0});
}

// A lone worker that fails a job: the caller renders it at once; the worker
// never sees it again, and the frame completes.
TEST(Scheduler, ALoneWorkersFailedJobIsTheCallersAtOnce) {
  Scheduler s(1, 2);
  s.add_worker("only");
  s.add_frame(0, tiles(2));
  auto j = s.assign(at(0));
  ASSERT_EQ(j.size(), 1u);
  s.on_bad_result("only", j[0].job_id);
  const auto own = s.take_own_jobs();
  ASSERT_EQ(own.size(), 1u);
  EXPECT_EQ(own[0].job_id, j[0].job_id);
  auto next = s.assign(at(1));
  ASSERT_EQ(next.size(), 1u);
  EXPECT_NE(next[0].job_id, j[0].job_id);
  answer(s, next, 5, at(2));
  EXPECT_TRUE(s.assign(at(3)).empty()) << "nothing left for it";
  EXPECT_TRUE(s.take_completed_frames().empty()) << "the caller's job is still out";
  EXPECT_TRUE(s.on_own_result(j[0].job_id));
  EXPECT_EQ(s.take_completed_frames(), std::vector<uint64_t>{0});
}

// A job one worker failed waits for the other; when the other leaves, the
// only worker present has failed it: the caller's.
TEST(Scheduler, AFailedJobBecomesTheCallersWhenItsOtherWorkersLeave) {
  Scheduler s(1, 2);
  s.add_worker("a");
  s.add_worker("b");
  s.add_frame(0, tiles(3));
  const auto first = s.assign(at(0));
  const JobAssignment failed = for_worker(first, "a").at(0);
  s.on_bad_result("a", failed.job_id);
  s.assign(at(1));  // a takes the third job
  EXPECT_TRUE(s.take_own_jobs().empty());
  s.remove_worker("b");
  s.assign(at(2));
  const auto own = s.take_own_jobs();
  ASSERT_EQ(own.size(), 1u);
  EXPECT_EQ(own[0].job_id, failed.job_id);
}

// The caller's job of a frame the view left: its result is not wanted.
TEST(Scheduler, ACancelledFramesOwnJobIsNotWanted) {
  Scheduler s(1, 2);
  s.add_worker("only");
  s.add_frame(0, tiles(1));
  auto j = s.assign(at(0));
  s.on_bad_result("only", j[0].job_id);
  ASSERT_EQ(s.take_own_jobs().size(), 1u);
  s.cancel_frame(0);
  EXPECT_FALSE(s.on_own_result(j[0].job_id));
}

// Fresh identities that fail a job on purpose only lose it: with proven
// workers present the job is theirs, and the caller takes it over only when
// two proven workers failed it.
TEST(Scheduler, FailuresFromWorkersThatNeverAnsweredDoNotCondemnAJob) {
  SchedulerConfig config;
  config.credits = 1;
  config.failures_need_standing = true;
  Scheduler s(config);
  s.add_worker("a");
  s.add_worker("b");
  s.add_frame(0, tiles(4));
  answer(s, s.assign(at(0)), 5, at(1));  // a and b have each answered: in good standing
  const auto busy = s.assign(at(1));     // and each holds frame 0's other jobs
  ASSERT_EQ(busy.size(), 2u);
  s.add_frame(1, tiles(1));
  for (int i = 0; i < 4; ++i) {  // fresh identities, each failing frame 1's job at once
    const WorkerId fake = worker_name(i);
    s.add_worker(fake);
    auto j = s.assign(at(2 + i));
    ASSERT_EQ(j.size(), 1u);
    ASSERT_EQ(j[0].worker, fake);
    s.on_bad_result(fake, j[0].job_id);
    EXPECT_TRUE(s.take_own_jobs().empty()) << "fake " << i;
    s.remove_worker(fake);
  }
  for (const char* w : {"a", "b"}) {  // the proven workers fail it too: now it is the job
    answer(s, for_worker(busy, w), 5, at(10));
    auto j = s.assign(at(10));
    ASSERT_EQ(j.size(), 1u);
    ASSERT_EQ(j[0].worker, w);
    s.on_bad_result(w, j[0].job_id);
    EXPECT_EQ(s.take_own_jobs().size(), std::string(w) == "b" ? 1u : 0u) << w;
  }
}

TEST(Scheduler, AResultIsCheckedAgainstItsOwnJob) {
  Scheduler s(2, 2);
  s.add_worker("a");
  s.add_frame(0, tiles(2));
  const auto j = s.assign(at(0));
  ASSERT_EQ(j.size(), 2u);
  EXPECT_EQ(s.check_result("a", j[0].job_id, 0, j[1].tile), ResultCheck::WrongTile) << "another job's rectangle";
  TileJob shifted = j[0].tile;
  shifted.border = 0;
  EXPECT_EQ(s.check_result("a", j[0].job_id, 0, shifted), ResultCheck::WrongTile);
  EXPECT_EQ(s.check_result("a", j[0].job_id, 1, j[0].tile), ResultCheck::WrongTile) << "another frame";
  EXPECT_EQ(s.check_result("b", j[0].job_id, 0, j[0].tile), ResultCheck::Unknown) << "not b's job";
  EXPECT_EQ(s.check_result("a", j[0].job_id, 0, j[0].tile), ResultCheck::Wanted);
}

// Two workers; one answers a tile but its result is lost on the way (it is
// alive and heartbeats). The other copies the late tile, but its result alone
// cannot decide the frame's hash: the lost copy is given up, and the worker
// that lost it votes with a fresh copy. Nothing hangs, no credit is kept.
TEST(Scheduler, AResultLostOnTheWayNeitherHangsTheFrameNorKeepsItsCredit) {
  Scheduler s(1, 2);
  s.add_worker("lost");
  double clock = 0;
  learn_round_trips(s, clock);  // 10 ms tiles: late after 30 ms
  s.add_worker("fast");
  s.add_frame(0, tiles(1));
  const auto original = s.assign(at(clock));
  ASSERT_EQ(original.size(), 1u);
  const auto copy = s.assign(at(clock + 40));
  ASSERT_EQ(copy.size(), 1u) << "the late tile is copied";
  EXPECT_EQ(s.on_result(copy[0].worker, copy[0].job_id, 1, at(clock + 50)), ResultVerdict::Held);
  const auto verify = s.assign(at(clock + 100));
  ASSERT_EQ(verify.size(), 1u) << "the lost copy is given up; its worker verifies";
  EXPECT_EQ(verify[0].worker, original[0].worker);
  EXPECT_EQ(s.stats().verified, 1u);
  answer_late(s, verify, 1, at(clock + 110));
  EXPECT_EQ(s.take_completed_frames().size(), 1u);
  EXPECT_EQ(s.outstanding("lost"), 0);
  EXPECT_EQ(s.outstanding("fast"), 0);
}

// With one worker no copy can go elsewhere: a job ten times late (here 10 x
// 1 s, before any round trip is known) that a later job overtook comes back
// to the pool, credit and all; one that is only slow is left alone.
TEST(Scheduler, ALoneWorkersLostResultsAreIssuedToItAgain) {
  Scheduler s(2, 2);
  s.add_worker("only");
  s.add_frame(0, tiles(3));
  const auto first = s.assign(at(0));
  ASSERT_EQ(first.size(), 2u);
  answer(s, {first[1]}, 1, at(100));  // the second answers; the first never will
  const auto third = s.assign(at(100));
  ASSERT_EQ(third.size(), 1u);
  EXPECT_TRUE(s.assign(at(9000)).empty()) << "late, but not yet lost";
  ASSERT_TRUE(s.next_straggler_time(at(9000)));
  EXPECT_EQ(*s.next_straggler_time(at(9000)), at(10000));
  const auto again = s.assign(at(10001));
  ASSERT_EQ(again.size(), 1u) << "the overtaken job, again to the only worker";
  EXPECT_EQ(again[0].worker, "only");
  EXPECT_EQ(again[0].job_id, first[0].job_id);
  EXPECT_EQ(s.stats().reissued, 1u);
  EXPECT_EQ(s.outstanding("only"), 2) << "credit came back with it";
  answer(s, again, 1, at(10010));
  answer(s, third, 1, at(10020));
  EXPECT_EQ(s.take_completed_frames().size(), 1u);
  // A first copy that was only slow answers after all: dropped, harmless.
  EXPECT_EQ(s.check_result("only", first[0].job_id, 0, first[0].tile), ResultCheck::Unknown);
  EXPECT_EQ(s.outstanding("only"), 0);
}

// Jobs that nothing overtook are slow, not lost, until a minute has passed.
TEST(Scheduler, ALoneWorkersSlowJobsAreNotRenderedTwice) {
  Scheduler s(2, 2);
  s.add_worker("only");
  s.add_frame(0, tiles(2));
  const auto first = s.assign(at(0));
  ASSERT_EQ(first.size(), 2u);
  EXPECT_TRUE(s.assign(at(30000)).empty()) << "30 s tiles on a lone worker are rendered once";
  ASSERT_TRUE(s.next_straggler_time(at(30000))) << "the caller wakes when they count as lost";
  EXPECT_EQ(*s.next_straggler_time(at(30000)), at(60000)) << "not a time already past: the caller would spin";
  EXPECT_EQ(s.stats().reissued, 0u);
  const auto again = s.assign(at(60001));
  EXPECT_EQ(again.size(), 2u) << "after a minute both are taken as lost";
}

TEST(Scheduler, UnknownResultsAreHarmless) {
  Scheduler s(2, 2);
  s.add_worker("a");
  EXPECT_EQ(s.check_result("a", 999, 0, {}), ResultCheck::Unknown);
  EXPECT_EQ(s.on_result("a", 999, 0, at(0)), ResultVerdict::Unknown);
  EXPECT_EQ(s.on_result("ghost", 999, 0, at(0)), ResultVerdict::Unknown);
  s.drop_result("ghost", 999);
  s.on_bad_result("ghost", 999);
  EXPECT_TRUE(s.take_own_jobs().empty());
  EXPECT_FALSE(s.on_own_result(999));
}

TEST(Scheduler, ForcedDuplicatesGoToAnotherWorker) {
  Scheduler s(1, 2);
  s.add_worker("a");
  s.add_worker("b");
  s.force_duplicates(1);
  s.add_frame(0, tiles(2));
  const auto jobs = s.assign(at(0));
  ASSERT_EQ(jobs.size(), 2u);
  EXPECT_EQ(jobs[0].job_id, jobs[1].job_id);
  EXPECT_NE(jobs[0].worker, jobs[1].worker);
  EXPECT_TRUE(jobs[1].duplicate);
  EXPECT_EQ(s.stats().duplicated, 1u);
}

}  // namespace
}  // namespace igi

namespace igi {
namespace {

TEST(Scheduler, ACancelledFrameGivesItsCreditBackAndItsLateResultsAreUnknown) {
  Scheduler s(2, 2);
  s.add_worker("a");
  s.add_worker("b");
  s.add_frame(0, tiles(6));
  s.add_frame(1, tiles(6));
  const std::vector<JobAssignment> first = s.assign(at(0));
  ASSERT_EQ(first.size(), 4u);
  EXPECT_EQ(s.cancel_frame(0), (std::set<WorkerId>{"a", "b"}));
  EXPECT_EQ(s.outstanding("a"), 0) << "its credit comes back at once";
  EXPECT_TRUE(s.can_add_frame());
  const std::vector<JobAssignment> next = s.assign(at(1));
  ASSERT_EQ(next.size(), 4u);
  for (const JobAssignment& j : next) EXPECT_EQ(j.frame_id, 1u) << "the cancelled frame's jobs never go out again";
  const JobAssignment& late = first.front();
  EXPECT_EQ(s.check_result(late.worker, late.job_id, late.frame_id, late.tile), ResultCheck::Unknown);
  s.drop_result(late.worker, late.job_id);
  EXPECT_EQ(s.outstanding(late.worker), 2) << "a late result takes back no credit twice";
  answer(s, next, 7, at(2));
  answer(s, s.assign(at(3)), 7, at(3));
  EXPECT_EQ(s.take_completed_frames(), std::vector<uint64_t>{1});
}

}  // namespace
}  // namespace igi
