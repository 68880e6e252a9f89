#include "trust/referee.h"

#include <algorithm>
#include <iterator>
#include <utility>

namespace igi {
namespace {

bool anonymous(const std::string& key) { return key.empty() || key[0] == '#'; }

}  // namespace

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

void Referee::enroll(const WorkerId& id, const std::string& key) { enrolled_[id] = key; }

std::string Referee::voter_key(const WorkerId& id) const {
  auto it = enrolled_.find(id);
  return it == enrolled_.end() || it->second.empty() ? "#" + id : it->second;
}

uint32_t Referee::standing(const WorkerId& id) const {
  auto it = standing_.find(voter_key(id));
  return it == standing_.end() ? 0 : it->second;
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

bool Referee::has_voted(const Ballot& ballot, const WorkerId& id) { return ballot.voters.count(id) > 0; }

bool Referee::voted(uint64_t frame_id, const WorkerId& id) const { return has_voted(ballots_.at(frame_id), id); }

void Referee::set_reference(uint64_t frame_id, std::optional<uint64_t> hash) {
  auto it = ballots_.find(frame_id);
  if (it == ballots_.end() || it->second.reference) return;
  if (!hash) it->second.by_vote = true;
  else if (master_reference_) it->second.callers_hash = hash;  // not once it follows its workers
}

Vote Referee::vote(uint64_t frame_id, uint64_t job_id, const WorkerId& id, uint64_t hash, bool first) {
  Ballot& ballot = ballots_.at(frame_id);
  if (ballot.reference) {
    if (hash != *ballot.reference) return ballot.doubt ? Vote::Contested : Vote::Wrong;
    return first ? Vote::Counts : Vote::Late;
  }
  ballot.votes[hash].insert(id);
  ballot.voters.emplace(id, voter_key(id));
  if (first) {
    held_[job_id] = Held{id, hash};
    ballot.held.push_back(job_id);
  }
  return Vote::Recorded;
}

std::set<std::string> Referee::keys_of(const Ballot& ballot, const std::set<WorkerId>& voters) const {
  std::set<std::string> keys;
  for (const WorkerId& v : voters) keys.insert(ballot.voters.at(v));
  return keys;
}

// Workers that take jobs, and voters since gone or benched: by key.
std::set<std::string> Referee::possible_voters(const Ballot& ballot, const Roll& roll) const {
  std::set<std::string> keys;
  for (const WorkerId& id : roll.active) keys.insert(voter_key(id));
  for (const auto& [id, key] : ballot.voters)
    if (!roll.active.count(id)) keys.insert(key);
  return keys;
}

std::optional<Decision> Referee::try_decide(uint64_t frame_id, const Roll& roll) {
  auto it = ballots_.find(frame_id);
  if (it == ballots_.end() || it->second.reference) return std::nullopt;
  Ballot& ballot = it->second;
  if (ballot.callers_hash) return judge(frame_id, ballot, roll);
  if (!ballot.by_vote || ballot.votes.empty()) return std::nullopt;
  return count(frame_id, ballot, roll);
}

// By vote. Where voters with standing are possible, only they decide (a
// strict majority of them, with a second voter or the whole frame answered);
// otherwise two voters and a strict majority of the possible ones, so the
// losers are always fewer than the winners. A worker decides alone only when
// it is the frame's only possible voter and every job is answered.
std::optional<Decision> Referee::count(uint64_t frame_id, Ballot& ballot, const Roll& roll) {
  const std::set<std::string> possible = possible_voters(ballot, roll);
  std::set<std::string> proven;
  std::copy_if(possible.begin(), possible.end(), std::inserter(proven, proven.end()),
               [&](const std::string& key) { return standing_.count(key) > 0; });
  for (const auto& [hash, voters] : ballot.votes) {
    const std::set<std::string> keys = keys_of(ballot, voters);
    const uint64_t reference = hash;  // decide() clears the votes
    if (proven.empty()) {
      if (keys.size() >= 2 && 2 * keys.size() > possible.size())
        return decide(frame_id, ballot, reference, Verdict::Confirmed);
      continue;
    }
    const size_t with_standing = size_t(std::count_if(keys.begin(), keys.end(), [&](const std::string& k) {
      return proven.count(k) > 0;
    }));
    if (2 * with_standing > proven.size() && (keys.size() >= 2 || roll.all_answered))
      return decide(frame_id, ballot, reference, keys.size() >= 2 ? Verdict::Confirmed : Verdict::Alone);
  }
  if (ballot.votes.size() == 1 && roll.all_answered && possible.size() == 1) {
    const uint64_t reference = ballot.votes.begin()->first;
    return decide(frame_id, ballot, reference, Verdict::Alone);
  }
  return std::nullopt;
}

// The caller's hash, once a worker agrees. While none does, the verdict
// waits for every awaited worker, and for the bound in which another could
// join; then two or more independent keys that agree on another hash, and
// every worker present (benched ones too) among them, are likelier right
// than the caller, which is asked (a dispute); anything else is a doubt.
std::optional<Decision> Referee::judge(uint64_t frame_id, Ballot& ballot, const Roll& roll) {
  if (ballot.disputed) return std::nullopt;
  const uint64_t callers = *ballot.callers_hash;
  if (ballot.votes.count(callers)) return decide(frame_id, ballot, callers, Verdict::Confirmed);
  if (ballot.votes.empty() || !roll.settled) return std::nullopt;
  for (const WorkerId& id : roll.awaited)
    if (!has_voted(ballot, id)) return std::nullopt;  // verification copies bring its vote
  if (ballot.votes.size() == 1) {
    const auto& [hash, voters] = *ballot.votes.begin();
    const std::set<std::string> keys = keys_of(ballot, voters);
    const bool independent = keys.size() >= 2 && std::none_of(keys.begin(), keys.end(), anonymous);
    const auto& of_hash = voters;  // a structured binding cannot be captured before C++20 (clang 14)
    const bool everyone = std::all_of(roll.present.begin(), roll.present.end(),
                                      [&](const WorkerId& id) { return of_hash.count(id) > 0; });
    if (independent && everyone) {
      ballot.disputed = true;
      disputes_.push_back(HashDispute{frame_id, callers, hash, {voters.begin(), voters.end()}});
      return std::nullopt;
    }
  }
  return doubt(frame_id, ballot, callers);
}

// Nobody can tell who is wrong: the caller's hash stands for the frame, but
// what differs from it is the caller's to render, not a reason to quarantine.
std::optional<Decision> Referee::doubt(uint64_t frame_id, Ballot& ballot, uint64_t callers) {
  HashDoubt d;
  d.frame_id = frame_id;
  d.callers_hash = callers;
  std::set<std::string> keys;
  for (const auto& [hash, voters] : ballot.votes)
    for (const WorkerId& v : voters) {
      d.voters[hash].push_back(v);
      const std::string& key = ballot.voters.at(v);
      if (anonymous(key)) d.anonymous = true;
      else keys.insert(key);
    }
  d.keys = keys.size();
  doubts_.push_back(std::move(d));
  ballot.doubt = true;
  return decide(frame_id, ballot, callers, Verdict::Doubt);
}

Decision Referee::decide(uint64_t frame_id, Ballot& ballot, uint64_t reference, Verdict verdict) {
  Decision d;
  d.frame_id = frame_id;
  d.reference = reference;
  d.doubt = verdict == Verdict::Doubt;
  ballot.reference = reference;
  for (const auto& [hash, voters] : ballot.votes) {
    if (hash != reference && !d.doubt) d.losers.insert(d.losers.end(), voters.begin(), voters.end());
    if (hash != reference || verdict != Verdict::Confirmed) continue;
    for (const std::string& key : keys_of(ballot, voters))
      if (standing_.count(key) || standing_.size() < kMaxStanding) ++standing_[key];
  }
  ballot.votes.clear();
  for (uint64_t job_id : std::exchange(ballot.held, {})) {
    auto held = held_.find(job_id);
    d.held.emplace_back(job_id, held->second.hash == reference);
    held_.erase(held);
  }
  return d;
}

std::vector<uint64_t> Referee::disqualify(const WorkerId& id) {
  standing_.erase(voter_key(id));
  std::vector<uint64_t> dropped;
  for (auto& [frame_id, ballot] : ballots_) {
    for (auto v = ballot.votes.begin(); v != ballot.votes.end();) {
      v->second.erase(id);
      v = v->second.empty() ? ballot.votes.erase(v) : std::next(v);
    }
    ballot.voters.erase(id);
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
  return decide(frame_id, ballot, workers, Verdict::Confirmed);
}

std::vector<HashDispute> Referee::take_disputes() { return std::exchange(disputes_, {}); }

std::vector<HashDoubt> Referee::take_doubts() { return std::exchange(doubts_, {}); }

bool Referee::may_stall() const {
  return std::any_of(ballots_.begin(), ballots_.end(), [](const auto& b) {
    return !b.second.reference && b.second.by_vote && b.second.votes.size() >= 2;
  });
}

std::optional<HashSplit> Referee::stalled_split(const std::vector<WorkerId>& present) const {
  for (const auto& [frame_id, ballot] : ballots_) {
    if (ballot.reference || !ballot.by_vote || ballot.votes.size() < 2) continue;
    const Ballot& voted = ballot;  // captured below: a structured binding cannot be (clang 14)
    if (!std::all_of(present.begin(), present.end(), [&](const WorkerId& id) { return has_voted(voted, id); }))
      continue;
    HashSplit split;
    split.frame_id = frame_id;
    for (const auto& [hash, voters] : ballot.votes) split.voters[hash].assign(voters.begin(), voters.end());
    return split;
  }
  return std::nullopt;
}

}  // namespace igi
