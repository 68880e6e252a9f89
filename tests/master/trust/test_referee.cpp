// The referee's rules (master/trust/referee.h) on plain inputs: votes in, decisions out.
#include <gtest/gtest.h>

#include "trust/referee.h"

namespace igi {
namespace {

// Every worker present takes jobs and has answered (a proven voter).
Roll proven(std::initializer_list<const char*> workers, bool all_answered = false) {
  Roll roll;
  for (const char* w : workers) roll.active.insert(w), roll.awaited.insert(w);
  roll.all_answered = all_answered;
  return roll;
}

// A decision was made, for `reference`, and `losers` lost.
void expect_decision(const std::optional<Decision>& d, uint64_t reference, const std::vector<WorkerId>& losers) {
  ASSERT_TRUE(d);
  EXPECT_EQ(d->reference, reference);
  EXPECT_EQ(d->losers, losers);
}

TEST(Referee, TheCallersHashDecidesOnceAWorkerAgreesAndTheOthersLose) {
  Referee r(true);
  r.open(0);
  r.set_reference(0, 7);
  const Roll roll = proven({"a", "b", "c"});
  EXPECT_EQ(r.vote(0, 1, "a", 9, true), Vote::Recorded);
  EXPECT_FALSE(r.try_decide(0, roll)) << "b and c have not voted: no verdict on a alone";
  EXPECT_TRUE(r.holds(1));
  EXPECT_EQ(r.vote(0, 2, "b", 7, true), Vote::Recorded);
  std::optional<Decision> d = r.try_decide(0, roll);
  ASSERT_TRUE(d);
  EXPECT_EQ(d->reference, 7u);
  EXPECT_EQ(d->held, (std::vector<std::pair<uint64_t, bool>>{{1, false}, {2, true}})) << "in the order held";
  EXPECT_EQ(d->losers, std::vector<WorkerId>{"a"});
  EXPECT_FALSE(r.holds(1));
  EXPECT_TRUE(r.decided(0));
  EXPECT_EQ(r.vote(0, 3, "c", 7, true), Vote::Counts);
  EXPECT_EQ(r.vote(0, 3, "a", 7, false), Vote::Late);
  EXPECT_EQ(r.vote(0, 4, "c", 8, true), Vote::Wrong) << "a decided frame judges at once";
}

TEST(Referee, TwoWorkersWhoAgreeAgainstTheCallerAreADisputeNotAVerdict) {
  Referee r(true);
  r.enroll("a", "key-a");  // two independent authenticated keys
  r.enroll("b", "key-b");
  r.open(0);
  r.set_reference(0, 7);
  const Roll roll = proven({"a", "b"});
  r.vote(0, 1, "a", 9, true);
  EXPECT_FALSE(r.try_decide(0, roll));
  EXPECT_TRUE(r.take_disputes().empty()) << "b, awaited, has not voted yet";
  r.vote(0, 2, "b", 9, true);
  EXPECT_FALSE(r.try_decide(0, roll));
  const std::vector<HashDispute> disputes = r.take_disputes();
  ASSERT_EQ(disputes.size(), 1u);
  EXPECT_EQ(disputes[0].callers_hash, 7u);
  EXPECT_EQ(disputes[0].workers_hash, 9u);
  EXPECT_FALSE(r.wants_votes(0)) << "a disputed frame waits for the caller";
  r.follow_workers();
  std::optional<Decision> d = r.stop_judging(0);
  ASSERT_TRUE(d);
  EXPECT_EQ(d->reference, 9u);
  EXPECT_TRUE(d->losers.empty());
  r.open(1);
  EXPECT_TRUE(r.wants_votes(1)) << "frames opened after follow_workers() are decided by vote";
}

// One voice against another: the referee cannot tell which is wrong (the
// caller's maths library, or the worker), so nobody loses and the caller
// renders what the worker contests.
TEST(Referee, ALoneDissenterAgainstTheCallerIsADoubtNotAVerdict) {
  Referee r(true);
  r.enroll("a", "key-a");
  r.open(0);
  r.set_reference(0, 7);
  r.vote(0, 1, "a", 9, true);
  std::optional<Decision> d = r.try_decide(0, proven({"a"}));
  expect_decision(d, 7u, {});  // no one is quarantined on one voice
  EXPECT_TRUE(d->doubt);
  EXPECT_EQ(d->held, (std::vector<std::pair<uint64_t, bool>>{{1, false}}));
  EXPECT_TRUE(r.take_disputes().empty());
  const std::vector<HashDoubt> doubts = r.take_doubts();
  ASSERT_EQ(doubts.size(), 1u);
  EXPECT_EQ(doubts[0].voters.at(9), std::vector<WorkerId>{"a"});
  EXPECT_EQ(r.vote(0, 2, "a", 9, true), Vote::Contested) << "its later results are the caller's to render";
  EXPECT_EQ(r.vote(0, 3, "a", 7, true), Vote::Counts);
  EXPECT_EQ(r.standing("a"), 0u) << "a doubt confirms no one";
}

TEST(Referee, AVoteNeedsTwoAndAStrictMajorityOfThePossibleVoters) {
  Referee r;
  r.open(0);
  const Roll four = proven({"a", "b", "c", "d"});
  r.vote(0, 1, "a", 5, true);
  r.vote(0, 2, "b", 5, true);
  EXPECT_FALSE(r.try_decide(0, four)) << "two of four is no majority";
  r.vote(0, 3, "c", 6, true);
  EXPECT_FALSE(r.try_decide(0, four));
  r.vote(0, 4, "d", 5, true);
  expect_decision(r.try_decide(0, four), 5u, {"c"});
}

TEST(Referee, VotersThatLeftStillCountAmongThePossibleOnes) {
  Referee r;
  r.open(0);
  r.vote(0, 1, "a", 5, true);
  r.vote(0, 2, "b", 6, true);
  r.vote(0, 3, "c", 5, true);
  // b and c left: a and the two gone voters are three possible, two of them agree.
  std::optional<Decision> d = r.try_decide(0, proven({"a"}));
  ASSERT_TRUE(d);
  EXPECT_EQ(d->reference, 5u);
  Referee s;
  s.open(0);
  s.vote(0, 1, "a", 5, true);
  s.vote(0, 2, "b", 5, true);
  EXPECT_FALSE(s.try_decide(0, proven({"a", "b", "c", "d", "e"}))) << "two of five";
}

TEST(Referee, ALoneWorkerDecidesAloneOnlyOnceEveryJobIsAnswered) {
  Referee r;
  r.open(0);
  r.vote(0, 1, "a", 5, true);
  EXPECT_FALSE(r.try_decide(0, proven({"a"}, false)));
  std::optional<Decision> d = r.try_decide(0, proven({"a"}, true));
  ASSERT_TRUE(d);
  EXPECT_EQ(d->reference, 5u);
}

TEST(Referee, AQuarantinedWorkersVotesAndHeldResultsGoEverywhere) {
  Referee r;
  r.open(0);
  r.open(1);
  r.vote(0, 1, "a", 5, true);
  r.vote(1, 11, "a", 5, true);
  r.vote(1, 12, "b", 5, true);
  EXPECT_EQ(r.disqualify("a"), (std::vector<uint64_t>{1, 11})) << "frame by frame, in the order held";
  EXPECT_FALSE(r.holds(1));
  EXPECT_TRUE(r.holds(12));
  EXPECT_FALSE(r.voted(1, "a"));
  EXPECT_TRUE(r.voted(1, "b"));
  r.close(1);
  EXPECT_FALSE(r.holds(12)) << "a closed frame forgets its held results";
}

TEST(Referee, ASplitWithEveryoneVotedStallsAndNamesTheVoters) {
  Referee r;
  r.open(0);
  r.vote(0, 1, "a", 5, true);
  EXPECT_FALSE(r.may_stall());
  r.vote(0, 2, "b", 6, true);
  EXPECT_FALSE(r.try_decide(0, proven({"a", "b"})));
  ASSERT_TRUE(r.may_stall());
  EXPECT_FALSE(r.stalled_split({"a", "b", "c"})) << "c may still break the tie";
  std::optional<HashSplit> split = r.stalled_split({"a", "b"});
  ASSERT_TRUE(split);
  EXPECT_EQ(split->voters.at(5), std::vector<WorkerId>{"a"});
  EXPECT_EQ(split->voters.at(6), std::vector<WorkerId>{"b"});
}

}  // namespace
}  // namespace igi
