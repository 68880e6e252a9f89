#pragma once
// The verdict on each frame's VPL-set hash (the frame's per-frame state,
// identical on every correct worker): which results count, which wait, and
// which workers are quarantined. Plain bookkeeping: no sockets, no clock, no
// jobs. The scheduler (scheduler/scheduler.h) hands it every result's hash
// and, when a verdict may be due, what the jobs' flow knows of the frame's
// possible voters (a Roll); it applies the referee's Decisions to the jobs.
//
// The reference is never whatever the first to answer says:
//  - With `master_reference` (the master's default) the caller computes each
//    frame's hash itself (trust/master_renderer.h) and hands it to
//    set_reference(); every worker is judged against it, so no number of
//    agreeing peers can outvote it. Results are held until a worker's agrees
//    with it; then the others' workers lose, and later results are judged at
//    once. While none agrees, the frame waits for every awaited worker of the
//    Roll to vote; then, if two or more voted and all agree on another hash,
//    the caller is the odd one out (another maths library, say): the frame
//    is disputed (take_disputes()) and waits for the caller, which may
//    follow_workers(); otherwise the dissenters lose.
//  - Otherwise, or for a frame whose hash the caller could not compute, the
//    workers vote: a hash decides when at least two workers and a strict
//    majority of the frame's possible voters (the Roll's active workers, and
//    voters since gone or benched) reported it, so never more workers lose
//    than agree. A worker that is the only possible voter decides alone once
//    every job of the frame is answered.
//  - Until then first results are held: their pixels are kept, but they do
//    not count (the scheduler does not reissue a held job).
//  - When the reference is decided, held results with it count, the others
//    go back to the pool, and every worker that reported another hash for
//    the frame loses (the scheduler quarantines it: disqualify()). A late
//    result whose hash differs from its frame's reference loses too.
//  - A vote with no majority among the workers present: the frame waits
//    (stalled_split() reports it) until another worker joins.
#include <cstdint>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

namespace igi {

using WorkerId = std::string;  // the ZeroMQ identity

// What the jobs' flow knows of a frame's possible voters when a verdict may be due.
struct Roll {
  std::set<WorkerId> active;   // workers present that take jobs (not benched)
  // Of them, the votes a caller's hash waits for: workers that have returned
  // a result, and, while a job of the frame is unanswered, those rendering one.
  std::set<WorkerId> awaited;
  bool all_answered = false;   // every job of the frame counts or is held
};

// A frame's reference decided: what becomes of its held results and who lost.
struct Decision {
  uint64_t frame_id = 0;
  uint64_t reference = 0;
  std::vector<std::pair<uint64_t, bool>> held;  // (job, agrees) in the order held: agrees counts, else back to the pool
  std::vector<WorkerId> losers;                 // every worker that reported another hash for the frame
};

// A frame whose every awaited worker agrees on a hash that is not the caller's own.
struct HashDispute {
  uint64_t frame_id = 0;
  uint64_t callers_hash = 0, workers_hash = 0;
  std::vector<WorkerId> workers;
};

// A frame whose voters disagree with no majority possible among the workers present.
struct HashSplit {
  uint64_t frame_id = 0;
  std::map<uint64_t, std::vector<WorkerId>> voters;  // hash -> workers that reported it
};

// A result's hash as the referee takes it.
enum class Vote {
  Counts,    // its frame is decided and it agrees: the job's first result counts
  Late,      // its frame is decided and it agrees, but another copy answered first
  Wrong,     // its frame is decided and it differs: its worker loses
  Recorded,  // its frame is undecided: the vote is counted (a first result held); try_decide() next
};

class Referee {
 public:
  explicit Referee(bool master_reference = false) : master_reference_(master_reference) {}

  // Frames opened from now on wait for set_reference(). Before the first frame.
  void judge_by_reference() { master_reference_ = true; }
  // A frame the scheduler opens; close() forgets it (completed or cancelled) with its held results.
  void open(uint64_t frame_id);
  void close(uint64_t frame_id);

  // The frame's hash as the caller computed it; none: the caller could not,
  // and the frame's workers vote. try_decide() next.
  void set_reference(uint64_t frame_id, std::optional<uint64_t> hash);
  // A result's hash; `first`: no other result for its job counts or is held.
  Vote vote(uint64_t frame_id, uint64_t job_id, const WorkerId& id, uint64_t hash, bool first);
  // The frame's reference, when the rules above allow it now.
  std::optional<Decision> try_decide(uint64_t frame_id, const Roll& roll);
  // A worker quarantined: its votes are forgotten and its held results
  // dropped everywhere. Returns those results' jobs, frame by frame, in the order held.
  std::vector<uint64_t> disqualify(const WorkerId& id);
  // The caller gives up its own hashes: frames opened from now on are decided by vote.
  void follow_workers() { master_reference_ = false; }
  // ... and so is this undecided frame: a disputed one takes its workers' hash
  // at once (returned), any other is left to try_decide().
  std::optional<Decision> stop_judging(uint64_t frame_id);

  bool decided(uint64_t frame_id) const;
  bool holds(uint64_t job_id) const { return held_.count(job_id) > 0; }  // a first result waits for its frame's hash
  size_t held_count(uint64_t frame_id) const;
  const std::vector<uint64_t>& held_jobs(uint64_t frame_id) const;  // in the order held
  // Undecided, and another vote would help decide it (not while the caller's hash waits, or a dispute).
  bool wants_votes(uint64_t frame_id) const;
  bool voted(uint64_t frame_id, const WorkerId& id) const;
  // Frames disputed since the last call: the workers agree, the caller's hash differs.
  std::vector<HashDispute> take_disputes();
  // The oldest frame that cannot be decided without another worker: every
  // worker `present` has voted, on two or more hashes.
  std::optional<HashSplit> stalled_split(const std::vector<WorkerId>& present) const;
  bool may_stall() const;  // a frame could be split (cheap; stalled_split() says which)

 private:
  struct Ballot {
    std::optional<uint64_t> reference;     // decided: results with it count
    bool by_vote = true;                   // false while the caller's reference is awaited
    std::optional<uint64_t> callers_hash;  // the caller's reference, until a worker agrees with it
    bool disputed = false;
    std::map<uint64_t, std::set<WorkerId>> votes;  // until the reference is decided
    std::vector<uint64_t> held;                    // jobs whose first result waits
  };
  struct Held {
    WorkerId worker;
    uint64_t hash = 0;
  };
  std::optional<Decision> judge(uint64_t frame_id, Ballot& ballot, const Roll& roll);
  Decision decide(uint64_t frame_id, Ballot& ballot, uint64_t reference);
  static size_t possible_voters(const Ballot& ballot, const Roll& roll);
  static bool has_voted(const Ballot& ballot, const WorkerId& id);

  bool master_reference_;
  std::map<uint64_t, Ballot> ballots_;  // open frames, in frame order
  std::unordered_map<uint64_t, Held> held_;  // by job
  std::vector<HashDispute> disputes_;
};

}  // namespace igi
