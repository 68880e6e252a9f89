#include "trust/referee.h"

#include <algorithm>
#include <iterator>
#include <utility>

namespace igi {

void Referee::open(uint64_t frame_id) {
  Ballot& ballot = ballots_[frame_id];
  ballot.by_vote = !master_reference_;
}

void Referee::close(uint64_t frame_id) {
  auto it = ballots_.find(frame_id);
  if (it == ballots_.end()) return;
  for (uint64_t job_id : it->second.held) held_.erase(job_id);
  ballots_.erase(it);
}

bool Referee::decided(uint64_t frame_id) const {
  auto it = ballots_.find(frame_id);
  return it != ballots_.end() && it->second.reference.has_value();
}

size_t Referee::held_count(uint64_t frame_id) const {
  auto it = ballots_.find(frame_id);
  return it == ballots_.end() ? 0 : it->second.held.size();
}

const std::vector<uint64_t>& Referee::held_jobs(uint64_t frame_id) const { return ballots_.at(frame_id).held; }

bool Referee::wants_votes(uint64_t frame_id) const {
  const Ballot& b = ballots_.at(frame_id);
  return !b.reference && (b.by_vote || (b.callers_hash && !b.disputed));
}

bool Referee::has_voted(const Ballot& ballot, const WorkerId& id) {
  return std::any_of(ballot.votes.begin(), ballot.votes.end(), [&](const auto& v) { return v.second.count(id) > 0; });
}

bool Referee::voted(uint64_t frame_id, const WorkerId& id) const { return has_voted(ballots_.at(frame_id), id); }

void Referee::set_reference(uint64_t frame_id, std::optional<uint64_t> hash) {
  auto it = ballots_.find(frame_id);
  if (it == ballots_.end() || it->second.reference) return;
  if (hash) it->second.callers_hash = hash;
  else it->second.by_vote = true;
}

Vote Referee::vote(uint64_t frame_id, uint64_t job_id, const WorkerId& id, uint64_t hash, bool first) {
  Ballot& ballot = ballots_.at(frame_id);
  if (ballot.reference) {
    if (hash != *ballot.reference) return Vote::Wrong;
    return first ? Vote::Counts : Vote::Late;
  }
  ballot.votes[hash].insert(id);
  if (first) {
    held_[job_id] = Held{id, hash};
    ballot.held.push_back(job_id);
  }
  return Vote::Recorded;
}

// Workers that take jobs, and voters since gone or benched.
size_t Referee::possible_voters(const Ballot& ballot, const Roll& roll) {
  std::set<WorkerId> others;
  for (const auto& [hash, voters] : ballot.votes)
    for (const WorkerId& v : voters)
      if (!roll.active.count(v)) others.insert(v);
  return roll.active.size() + others.size();
}

// At least two voters and a strict majority of the possible ones: the losers
// are always fewer than the winners. A worker decides alone only when it is
// the frame's only possible voter and every job is answered.
std::optional<Decision> Referee::try_decide(uint64_t frame_id, const Roll& roll) {
  auto it = ballots_.find(frame_id);
  if (it == ballots_.end() || it->second.reference) return std::nullopt;
  Ballot& ballot = it->second;
  if (ballot.callers_hash) return judge(frame_id, ballot, roll);
  if (!ballot.by_vote || ballot.votes.empty()) return std::nullopt;
  const size_t possible = possible_voters(ballot, roll);
  for (const auto& [hash, voters] : ballot.votes)
    if (voters.size() >= 2 && 2 * voters.size() > possible) {
      const uint64_t reference = hash;  // decide() clears the votes
      return decide(frame_id, ballot, reference);
    }
  if (ballot.votes.size() == 1 && roll.all_answered && possible == 1) {
    const uint64_t reference = ballot.votes.begin()->first;
    return decide(frame_id, ballot, reference);
  }
  return std::nullopt;
}

// The caller's hash, once a worker agrees; or, once every awaited worker has
// voted without one agreeing, the caller's hash all the same (the dissenters
// lose), unless two or more agree on another: then the caller is likelier
// wrong than they, and it is asked.
std::optional<Decision> Referee::judge(uint64_t frame_id, Ballot& ballot, const Roll& roll) {
  if (ballot.disputed) return std::nullopt;
  const uint64_t callers = *ballot.callers_hash;
  if (ballot.votes.count(callers)) return decide(frame_id, ballot, callers);
  if (ballot.votes.empty()) return std::nullopt;
  for (const WorkerId& id : roll.awaited)
    if (!has_voted(ballot, id)) return std::nullopt;  // verification copies bring its vote
  if (ballot.votes.size() == 1 && ballot.votes.begin()->second.size() >= 2) {
    ballot.disputed = true;
    const auto& [hash, voters] = *ballot.votes.begin();
    disputes_.push_back(HashDispute{frame_id, callers, hash, {voters.begin(), voters.end()}});
    return std::nullopt;
  }
  return decide(frame_id, ballot, callers);
}

Decision Referee::decide(uint64_t frame_id, Ballot& ballot, uint64_t reference) {
  Decision d;
  d.frame_id = frame_id;
  d.reference = reference;
  ballot.reference = reference;
  for (const auto& [hash, voters] : ballot.votes)
    if (hash != reference) d.losers.insert(d.losers.end(), voters.begin(), voters.end());
  ballot.votes.clear();
  for (uint64_t job_id : std::exchange(ballot.held, {})) {
    auto held = held_.find(job_id);
    d.held.emplace_back(job_id, held->second.hash == reference);
    held_.erase(held);
  }
  return d;
}

std::vector<uint64_t> Referee::disqualify(const WorkerId& id) {
  std::vector<uint64_t> dropped;
  for (auto& [frame_id, ballot] : ballots_) {
    for (auto v = ballot.votes.begin(); v != ballot.votes.end();) {
      v->second.erase(id);
      v = v->second.empty() ? ballot.votes.erase(v) : std::next(v);
    }
    std::erase_if(ballot.held, [&](uint64_t job_id) {
      auto held = held_.find(job_id);
      if (held->second.worker != id) return false;
      held_.erase(held);
      dropped.push_back(job_id);
      return true;
    });
  }
  return dropped;
}

std::optional<Decision> Referee::stop_judging(uint64_t frame_id) {
  Ballot& ballot = ballots_.at(frame_id);
  if (ballot.reference) return std::nullopt;
  ballot.callers_hash.reset();
  ballot.by_vote = true;
  if (!ballot.disputed) return std::nullopt;
  ballot.disputed = false;
  const uint64_t workers = ballot.votes.begin()->first;
  return decide(frame_id, ballot, workers);
}

std::vector<HashDispute> Referee::take_disputes() { return std::exchange(disputes_, {}); }

bool Referee::may_stall() const {
  return std::any_of(ballots_.begin(), ballots_.end(), [](const auto& b) {
    return !b.second.reference && b.second.by_vote && b.second.votes.size() >= 2;
  });
}

std::optional<HashSplit> Referee::stalled_split(const std::vector<WorkerId>& present) const {
  for (const auto& [frame_id, ballot] : ballots_) {
    if (ballot.reference || !ballot.by_vote || ballot.votes.size() < 2) continue;
    if (!std::all_of(present.begin(), present.end(), [&](const WorkerId& id) { return has_voted(ballot, id); }))
      continue;
    HashSplit split;
    split.frame_id = frame_id;
    for (const auto& [hash, voters] : ballot.votes) split.voters[hash].assign(voters.begin(), voters.end());
    return split;
  }
  return std::nullopt;
}

}  // namespace igi
