// Trust that a slow worker, two colluding keys or a flood of results cannot
// break (issue 64), on plain inputs: the scheduler and its referee
// (master/trust/referee.h) without sockets or clocks, and the header a result
// is looked up by. The same cases with real processes: tests/system/test_scale.cpp
// and test_security.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <set>

#include "protocol/codec.h"
#include "scheduler/scheduler.h"

namespace igi {
namespace {

constexpr uint64_t kCallers = 5;   // the master's own hash of every frame here
constexpr uint64_t kWorkers = 7;   // what workers whose maths library differs from it report
constexpr uint64_t kMadeUp = 666;  // what colluders report

std::vector<TileJob> tiles(int n) {
  std::vector<TileJob> t;
  for (int i = 0; i < n; ++i) t.push_back({8 * i, 0, 8, 8, 1});
  return t;
}

const TimePoint t0 = TimePoint{} + std::chrono::hours(1);
TimePoint at(double ms) {
  return t0 + std::chrono::duration_cast<SchedulerClock::duration>(std::chrono::duration<double, std::milli>(ms));
}

// The master's scheduler: its own hash judges, and a verdict against it waits 3 s after the latest join.
Scheduler judging(int credits = 2) {
  SchedulerConfig c;
  c.credits = credits;
  c.master_reference = true;
  c.vote_wait_seconds = 3.0;
  return Scheduler(c);
}

// Answers each job: its first result, or a copy's (another answered first).
void answer(Scheduler& s, const std::vector<JobAssignment>& jobs, uint64_t hash, TimePoint when) {
  for (const JobAssignment& j : jobs) {
    ASSERT_NE(s.check_result(j.worker, j.job_id, j.frame_id, j.tile), ResultCheck::Unknown);
    s.on_result(j.worker, j.job_id, hash, when);
  }
}

// Every job of the frames open, answered by whoever gets it, until none is left to hand out.
void answer_all(Scheduler& s, uint64_t hash, TimePoint when) {
  for (std::vector<JobAssignment> jobs = s.assign(when); !jobs.empty(); jobs = s.assign(when)) answer(s, jobs, hash, when);
}

std::set<WorkerId> sorted(std::vector<WorkerId> ids) { return {ids.begin(), ids.end()}; }

// Workers c1 and c2 (their keys as given; empty: anonymous) join at once and
// answer every job of frame 0 with a made-up hash by 10 ms.
Scheduler two_against_the_caller(const std::string& key1, const std::string& key2) {
  Scheduler s = judging();
  s.add_worker("c1", 0, key1, at(0));
  s.add_worker("c2", 0, key2, at(0));
  s.add_frame(0, tiles(4));
  s.set_reference(0, kCallers);
  answer_all(s, kMadeUp, at(10));
  return s;
}

// Case 1: the master's maths library differs from its workers'. One worker
// answers the whole frame alone; it is neither quarantined nor believed
// while another may still join. One that starts 1.4 s late (within the
// master's timeout) gets a copy to verify, agrees, and the two keys are
// followed once the wait after its join is over.
TEST(Trust, ALoneDissenterWaitsForALateJoinerAndTwoKeysThatAgreeAreFollowed) {
  Scheduler s = judging();
  s.add_worker("a", 0, "key-a", at(0));
  s.add_frame(0, tiles(4));
  s.set_reference(0, kCallers);
  answer_all(s, kWorkers, at(100));
  EXPECT_TRUE(s.take_quarantined().empty()) << "one voice against the master's";
  EXPECT_TRUE(s.take_disputes().empty());
  EXPECT_TRUE(s.take_doubts().empty()) << "another worker may still join";
  EXPECT_TRUE(s.take_own_jobs().empty());
  ASSERT_TRUE(s.next_verdict_time());
  EXPECT_EQ(*s.next_verdict_time(), at(3000));
  s.add_worker("b", 0, "key-b", at(1400));
  EXPECT_EQ(*s.next_verdict_time(), at(4400)) << "a join restarts the wait";
  const std::vector<JobAssignment> verify = s.assign(at(1400));
  ASSERT_EQ(verify.size(), 1u);
  EXPECT_EQ(verify[0].worker, "b");
  EXPECT_TRUE(verify[0].duplicate) << "a verification copy of a held job";
  answer(s, verify, kWorkers, at(1500));
  EXPECT_TRUE(s.take_disputes().empty()) << "a third may still join until 4.4 s";
  s.assign(at(4400));
  const std::vector<HashDispute> disputes = s.take_disputes();
  ASSERT_EQ(disputes.size(), 1u);
  EXPECT_EQ(sorted(disputes[0].workers), (std::set<WorkerId>{"a", "b"}));
  s.follow_workers();
  EXPECT_EQ(s.take_completed_frames(), std::vector<uint64_t>{0});
  EXPECT_TRUE(s.take_quarantined().empty());
  EXPECT_EQ(s.standing("a"), 1u) << "a confirmed frame: both keys gain standing";
  EXPECT_EQ(s.standing("b"), 1u);
}

// Case 1 when no one joins: one voice against another, so the master cannot
// tell who is wrong. The frame is decided in doubt: the master renders what
// the worker contests, nobody is quarantined, and later frames of the same
// lone worker are decided at once (the wait for joiners is over).
TEST(Trust, ALoneDissenterThatNoOneJoinsIsADoubtAndTheMasterRendersTheFrame) {
  Scheduler s = judging(4);
  s.add_worker("a", 0, "key-a", at(0));
  s.add_frame(0, tiles(4));
  s.set_reference(0, kCallers);
  answer_all(s, kWorkers, at(100));
  s.assign(at(2999));
  EXPECT_TRUE(s.take_doubts().empty());
  s.assign(at(3000));
  const std::vector<HashDoubt> doubts = s.take_doubts();
  ASSERT_EQ(doubts.size(), 1u);
  EXPECT_EQ(doubts[0].voters.at(kWorkers), std::vector<WorkerId>{"a"});
  const std::vector<JobAssignment> own = s.take_own_jobs();
  ASSERT_EQ(own.size(), 4u) << "every tile of the frame";
  for (const JobAssignment& j : own) {
    EXPECT_TRUE(j.contested);
    EXPECT_TRUE(s.on_own_result(j.job_id));
  }
  EXPECT_EQ(s.take_completed_frames(), std::vector<uint64_t>{0});
  EXPECT_TRUE(s.take_quarantined().empty());
  EXPECT_EQ(s.standing("a"), 0u);
  s.add_frame(1, tiles(4));
  s.set_reference(1, kCallers);
  answer_all(s, kWorkers, at(3100));
  EXPECT_EQ(s.take_doubts().size(), 1u) << "no join since: no second wait";
  EXPECT_EQ(s.take_own_jobs().size(), 4u);
  EXPECT_EQ(s.stats().doubted, 2u);
}

// Case 2: two authorised keys answer a frame before the honest worker has
// returned anything (it joined 0.5 s later). They are not "all the workers":
// the honest one is asked, agrees with the master, and the colluders lose.
TEST(Trust, TwoColludingKeysThatAnswerFirstLoseToTheHonestWorkerThatAnswersLater) {
  Scheduler s = two_against_the_caller("key-c1", "key-c2");
  s.add_worker("h", 0, "key-h", at(500));
  const std::vector<JobAssignment> copy = s.assign(at(100000));  // long past the wait
  EXPECT_TRUE(s.take_disputes().empty()) << "every worker present is awaited: h has not voted";
  EXPECT_TRUE(s.take_quarantined().empty());
  ASSERT_EQ(copy.size(), 1u);
  EXPECT_EQ(copy[0].worker, "h") << "asked to verify";
  answer(s, copy, kCallers, at(100100));
  EXPECT_EQ(sorted(s.take_quarantined()), (std::set<WorkerId>{"c1", "c2"}));
  answer_all(s, kCallers, at(100200));
  EXPECT_EQ(s.take_completed_frames(), std::vector<uint64_t>{0});
  EXPECT_TRUE(s.take_disputes().empty());
  EXPECT_EQ(s.standing("h"), 1u);
}

// Case 2 with one stolen key on two connections: one voter, which cannot
// outweigh the master even when no one else comes. A doubt, not a dispute.
TEST(Trust, OneKeyOnTwoConnectionsIsOneVoter) {
  Scheduler s = two_against_the_caller("stolen", "stolen");
  s.assign(at(3000));
  EXPECT_TRUE(s.take_disputes().empty());
  const std::vector<HashDoubt> doubts = s.take_doubts();
  ASSERT_EQ(doubts.size(), 1u);
  EXPECT_EQ(doubts[0].keys, 1u);
  EXPECT_EQ(s.take_own_jobs().size(), 4u);
  EXPECT_TRUE(s.take_quarantined().empty());
}

// Case 2 where the colluders answered copies of an honest newcomer's jobs
// first until it was benched: it takes no jobs, but it is present and has
// not voted, so two keys that agree are not every worker present. A doubt,
// not a dispute: the caller renders the frame and follows no one.
TEST(Trust, TwoKeysAreNotEveryWorkerWhileAWorkerTheyBenchedHasNotVoted) {
  Referee r(true);
  for (const char* w : {"c1", "c2", "h"}) r.enroll(w, std::string("key-") + w);
  r.open(0);
  r.set_reference(0, kCallers);
  r.vote(0, 1, "c1", kMadeUp, true);
  r.vote(0, 2, "c2", kMadeUp, true);
  Roll roll;
  roll.active = roll.awaited = {"c1", "c2"};
  roll.present = {"c1", "c2", "h"};
  roll.all_answered = true;
  const std::optional<Decision> d = r.try_decide(0, roll);
  ASSERT_TRUE(d);
  EXPECT_TRUE(d->doubt);
  EXPECT_TRUE(d->losers.empty());
  EXPECT_TRUE(r.take_disputes().empty());
  EXPECT_EQ(r.take_doubts().size(), 1u);
}

// Case 3: without CURVE two peers that agree could be two fakes: they are
// never followed (nor do they end the run), and lose to any worker that
// agrees with the master, however late it answers.
TEST(Trust, AnonymousPeersThatAgreeAreNeverFollowedAndLoseToAWorkerThatAgreesWithTheMaster) {
  Scheduler alone = two_against_the_caller("", "");
  alone.assign(at(3000));
  EXPECT_TRUE(alone.take_disputes().empty());
  const std::vector<HashDoubt> doubts = alone.take_doubts();
  ASSERT_EQ(doubts.size(), 1u);
  EXPECT_TRUE(doubts[0].anonymous);

  Scheduler s = two_against_the_caller("", "");
  s.add_worker("local", 0, "", at(300));  // a local worker, still loading its scene when they answered
  answer(s, s.assign(at(300)), kCallers, at(2000));
  EXPECT_EQ(sorted(s.take_quarantined()), (std::set<WorkerId>{"c1", "c2"}));
  answer_all(s, kCallers, at(2100));
  EXPECT_EQ(s.take_completed_frames(), std::vector<uint64_t>{0});
}

// By vote (a master that follows its workers): newcomers decide nothing
// against voters with standing, however many they are, and lose when they
// contradict them; a lone voter with standing decides once the frame is answered.
TEST(Trust, ByVoteNewcomersCannotOutvoteVotersWithStanding) {
  Scheduler s(1, 2);
  s.add_worker("p1", 0, "key-p1");
  s.add_worker("p2", 0, "key-p2");
  s.add_frame(0, tiles(2));
  answer_all(s, kWorkers, at(1));
  EXPECT_EQ(s.take_completed_frames(), std::vector<uint64_t>{0});
  ASSERT_EQ(s.standing("p1"), 1u);
  for (const char* n : {"n1", "n2", "n3"}) s.add_worker(n, 0, std::string("key-") + n);
  s.add_frame(1, tiles(5));
  const std::vector<JobAssignment> jobs = s.assign(at(2));
  ASSERT_EQ(jobs.size(), 5u);
  for (const JobAssignment& j : jobs)
    if (j.worker[0] == 'n') answer(s, {j}, kMadeUp, at(3));
  EXPECT_TRUE(s.take_quarantined().empty()) << "three of five, but none with standing";
  for (const JobAssignment& j : jobs)
    if (j.worker[0] == 'p') answer(s, {j}, kWorkers, at(4));
  EXPECT_EQ(sorted(s.take_quarantined()), (std::set<WorkerId>{"n1", "n2", "n3"}));

  Scheduler lone(4, 2);
  lone.add_worker("p", 0, "key-p");
  lone.add_worker("q", 0, "key-q");
  lone.add_frame(0, tiles(2));
  answer_all(lone, kWorkers, at(1));
  lone.remove_worker("q");
  lone.take_completed_frames();
  lone.add_worker("n1", 0, "key-n1");
  lone.add_worker("n2", 0, "key-n2");
  lone.add_frame(1, tiles(3));
  const std::vector<JobAssignment> mixed = lone.assign(at(2));
  for (const JobAssignment& j : mixed) answer(lone, {j}, j.worker == "p" ? kWorkers : kMadeUp, at(3));
  answer_all(lone, kWorkers, at(4));
  EXPECT_EQ(sorted(lone.take_quarantined()), (std::set<WorkerId>{"n1", "n2"}));
  EXPECT_EQ(lone.take_completed_frames(), std::vector<uint64_t>{1});
}

// Case 5: a master that follows its workers would render another tile than
// theirs. A job two workers failed goes to a third, not to the master; and
// a tile the master rendered for a frame still undecided when it began to
// follow them goes back to a worker.
TEST(Trust, AFollowingMasterGivesAJobTwoWorkersFailedToAThirdWorker) {
  SchedulerConfig c;
  c.credits = 1;
  c.master_reference = true;
  c.failures_need_standing = true;
  Scheduler s(c);
  for (const char* w : {"a", "b", "c"}) s.add_worker(w, 0, std::string("key-") + w);
  s.add_frame(0, tiles(6));
  s.set_reference(0, kCallers);
  std::vector<JobAssignment> first = s.assign(at(0));
  ASSERT_EQ(first.size(), 3u);
  answer(s, first, kWorkers, at(1));  // each has answered: their failures count
  std::vector<JobAssignment> next = s.assign(at(2));
  ASSERT_EQ(next.size(), 3u);
  const JobAssignment poisoned = next[0];
  s.on_bad_result(poisoned.worker, poisoned.job_id);
  answer(s, {next[1], next[2]}, kWorkers, at(3));
  const std::vector<JobAssignment> again = s.assign(at(4));
  auto to_failed = std::find_if(again.begin(), again.end(), [&](const JobAssignment& j) { return j.job_id == poisoned.job_id; });
  ASSERT_NE(to_failed, again.end());
  s.on_bad_result(to_failed->worker, to_failed->job_id);  // a second worker fails it: the master's, while it judges
  for (const JobAssignment& j : again)
    if (j.job_id != poisoned.job_id) answer(s, {j}, kWorkers, at(5));
  const std::vector<JobAssignment> own = s.take_own_jobs();
  ASSERT_EQ(own.size(), 1u);
  EXPECT_FALSE(own[0].contested);
  EXPECT_TRUE(s.on_own_result(own[0].job_id)) << "the master renders it (its own maths library)";
  EXPECT_EQ(s.take_disputes().size(), 1u) << "all three agree against the master";
  s.follow_workers();
  EXPECT_FALSE(s.wants_own_result(own[0].job_id));
  EXPECT_TRUE(s.take_completed_frames().empty()) << "the master's tile no longer counts";
  const std::vector<JobAssignment> third = s.assign(at(6));
  ASSERT_EQ(third.size(), 1u) << "the one worker that has not failed it";
  EXPECT_EQ(third[0].job_id, poisoned.job_id);
  answer(s, third, kWorkers, at(7));
  EXPECT_EQ(s.take_completed_frames(), std::vector<uint64_t>{0});
  // Following: a job two workers fail goes to the third, not to the master.
  s.add_frame(1, tiles(3));
  const std::vector<JobAssignment> jobs = s.assign(at(8));
  ASSERT_EQ(jobs.size(), 3u);
  s.on_bad_result(jobs[0].worker, jobs[0].job_id);
  answer(s, {jobs[1], jobs[2]}, kWorkers, at(9));
  const std::vector<JobAssignment> retry = s.assign(at(10));
  ASSERT_EQ(retry.size(), 1u);
  s.on_bad_result(retry[0].worker, retry[0].job_id);
  EXPECT_TRUE(s.take_own_jobs().empty()) << "two failed it, a third may take it";
  const std::vector<JobAssignment> last = s.assign(at(11));
  ASSERT_EQ(last.size(), 1u);
  EXPECT_NE(last[0].worker, jobs[0].worker);
  EXPECT_NE(last[0].worker, retry[0].worker);
  answer(s, last, kWorkers, at(12));
  EXPECT_EQ(s.take_completed_frames(), std::vector<uint64_t>{1});
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
