#pragma once
// The verdict on each frame's VPL-set hash (the frame's per-frame state,
// identical on every correct worker): which results count, which wait, which
// the caller renders itself, and which workers are quarantined. Plain
// bookkeeping: no sockets, no clock, no jobs. The scheduler
// (scheduler/scheduler.h) hands it every result's hash and, when a verdict
// may be due, what the jobs' flow knows of the frame's possible voters (a
// Roll); it applies the referee's Decisions to the jobs.
//
// Voters. A worker votes with its key (its CURVE key's name; none without
// CURVE): two connections with one key are one voter, and anonymous voters
// are never independent of each other. A voter's standing is the number of
// frames it voted for a hash that was confirmed: by the caller's own hash,
// or by two or more independent voters. Arrival order counts for nothing.
//
// The rule. No peer wins by being early, nor by having company:
//  - With `master_reference` (the master's default) the caller computes each
//    frame's hash itself (trust/master_renderer.h) and hands it to
//    set_reference(). A worker that agrees with it confirms it: the frame is
//    decided at once, and every worker that reported another hash for the
//    frame loses (however many they are, and whatever their standing).
//  - While no worker agrees, the verdict waits for every worker present that
//    takes jobs (the Roll's `awaited`: each gets a verification copy) and
//    until no other worker can still join in time (the Roll's `settled`: a
//    bound after the latest join, the scheduler's vote_wait). Then:
//     - every worker present (benched ones too) voted one hash, from two or
//       more independent authenticated keys: the caller is the odd one out
//       (another maths library, say). The
//       frame is disputed (take_disputes()) and waits for the caller, which
//       may follow_workers();
//     - anything else (a lone worker, workers that disagree among
//       themselves, anonymous workers, one key on several connections): the
//       referee cannot tell who is wrong. The frame is decided in doubt on
//       the caller's hash (take_doubts()): results that differ are the
//       caller's to render itself, nobody loses and nobody gains standing.
//  - By vote (after follow_workers(), or for a frame whose hash the caller
//    could not compute): where a frame's possible voters (the Roll's active
//    workers, and voters since gone or benched) include voters with
//    standing, a hash decides when it has a strict majority of those with
//    standing and two or more voters in all (or every job of the frame is
//    answered); newcomers then decide nothing, and lose when they contradict
//    it. Where none has standing, a hash decides with two or more voters and
//    a strict majority of the possible ones, so never more workers lose than
//    agree; a worker that is the only possible voter decides alone once
//    every job of the frame is answered (and gains no standing by it).
//  - Until then first results are held: their pixels are kept, but they do
//    not count (the scheduler does not reissue a held job).
//  - When the reference is decided, held results with it count, the others
//    go back to the pool (or to the caller, in doubt), and every worker that
//    reported another hash for the frame loses (the scheduler quarantines
//    it: disqualify()). A late result whose hash differs from its frame's
//    reference loses too (in doubt: its job is the caller's).
//  - A vote with no majority among the workers present: the frame waits
//    (stalled_split() reports it) until another worker joins.
//
// What k colluding keys can do: report the right hash with forged pixels
// (no hash sees that); delay a frame's verdict by up to the bound (or, never
// answering, until they are benched); and, k >= 2, if they are every worker
// present for the bound, make a caller whose hash they all contradict follow
// them (as an honest pair must be followed when the caller's maths library
// is the odd one), after which honest newcomers lose to their standing. What
// they cannot: outvote the caller's hash once one other worker reports it
// (then they lose), be followed while any other worker present has not
// voted with them, evict an honest worker that agrees with the caller, or,
// by vote, outvote a majority of voters with standing. One key on several
// connections is one voter (k = 1: a doubt at most), and anonymous peers,
// however many, are never followed.
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
  // Of them, the votes a verdict against the caller's hash waits for (every active worker).
  std::set<WorkerId> awaited;
  bool all_answered = false;   // every job of the frame counts or is held
  bool settled = true;         // no worker can join in time to vote any more (the bound since the latest join has passed)
  std::set<WorkerId> present;  // every worker present, benched ones too: all must agree before a dispute
};

// A frame's reference decided: what becomes of its held results and who lost.
struct Decision {
  uint64_t frame_id = 0;
  uint64_t reference = 0;
  std::vector<std::pair<uint64_t, bool>> held;  // (job, agrees) in the order held: agrees counts, else back to the pool
  std::vector<WorkerId> losers;                 // every worker that reported another hash for the frame
  bool doubt = false;  // decided in doubt: results that differ are the caller's to render, and nobody loses
};

// A frame whose every awaited worker agrees on a hash that is not the caller's own.
struct HashDispute {
  uint64_t frame_id = 0;
  uint64_t callers_hash = 0, workers_hash = 0;
  std::vector<WorkerId> workers;
};

// A frame no worker's hash agrees with the caller's, where the votes cannot
// outweigh the caller's either: it is decided in doubt.
struct HashDoubt {
  uint64_t frame_id = 0;
  uint64_t callers_hash = 0;
  std::map<uint64_t, std::vector<WorkerId>> voters;  // hash -> workers that reported it
  size_t keys = 0;        // independent authenticated keys among them
  bool anonymous = false; // some voter has no key (no CURVE)
};

// A frame whose voters disagree with no majority possible among the workers present.
struct HashSplit {
  uint64_t frame_id = 0;
  std::map<uint64_t, std::vector<WorkerId>> voters;  // hash -> workers that reported it
};

// A result's hash as the referee takes it.
enum class Vote {
  Counts,     // its frame is decided and it agrees: the job's first result counts
  Late,       // its frame is decided and it agrees, but another copy answered first
  Wrong,      // its frame is decided and it differs: its worker loses
  Contested,  // its frame is decided in doubt and it differs: the job is the caller's, nobody loses
  Recorded,   // its frame is undecided: the vote is counted (a first result held); try_decide() next
};

class Referee {
 public:
  explicit Referee(bool master_reference = false) : master_reference_(master_reference) {}

  // Frames opened from now on wait for set_reference(). Before the first frame.
  void judge_by_reference() { master_reference_ = true; }
  // A frame the scheduler opens; close() forgets it (completed or cancelled) with its held results.
  void open(uint64_t frame_id);
  void close(uint64_t frame_id);
  // A worker present votes with `key` (its CURVE key's name; empty: anonymous). leave(): it is gone.
  void enroll(const WorkerId& id, const std::string& key);
  void leave(const WorkerId& id) { enrolled_.erase(id); }

  // The frame's hash as the caller computed it (unused once it follows its
  // workers); none: the caller could not, and the frame's workers vote. try_decide() next.
  void set_reference(uint64_t frame_id, std::optional<uint64_t> hash);
  // A result's hash; `first`: no other result for its job counts or is held.
  Vote vote(uint64_t frame_id, uint64_t job_id, const WorkerId& id, uint64_t hash, bool first);
  // The frame's reference, when the rules above allow it now.
  std::optional<Decision> try_decide(uint64_t frame_id, const Roll& roll);
  // A worker quarantined: its votes are forgotten, its standing too, and its
  // held results dropped everywhere. Returns those results' jobs, frame by frame, in the order held.
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
  // Undecided, and another vote would help decide it (not while a dispute waits for the caller).
  bool wants_votes(uint64_t frame_id) const;
  bool voted(uint64_t frame_id, const WorkerId& id) const;
  // Frames confirmed with the worker's vote (by its key: every connection of one key shares it).
  uint32_t standing(const WorkerId& id) const;
  // Frames disputed since the last call: the workers agree, the caller's hash differs.
  std::vector<HashDispute> take_disputes();
  // Frames decided in doubt since the last call.
  std::vector<HashDoubt> take_doubts();
  // The oldest frame that cannot be decided without another worker: every
  // worker `present` has voted, on two or more hashes.
  std::optional<HashSplit> stalled_split(const std::vector<WorkerId>& present) const;
  bool may_stall() const;  // a frame could be split (cheap; stalled_split() says which)

 private:
  static constexpr size_t kMaxStanding = 4096;  // voters remembered with their standing; later ones earn none

  struct Ballot {
    std::optional<uint64_t> reference;     // decided: results with it count
    bool by_vote = true;                   // false while the caller's reference is awaited
    std::optional<uint64_t> callers_hash;  // the caller's reference, until a worker agrees with it
    bool disputed = false;
    bool doubt = false;                    // decided in doubt (on the caller's hash)
    std::map<uint64_t, std::set<WorkerId>> votes;  // until the reference is decided
    std::map<WorkerId, std::string> voters;        // each voter's standing key (its CURVE key, or "#" + its id)
    std::vector<uint64_t> held;                    // jobs whose first result waits
  };
  struct Held {
    WorkerId worker;
    uint64_t hash = 0;
  };
  enum class Verdict { Confirmed, Alone, Doubt };
  std::optional<Decision> judge(uint64_t frame_id, Ballot& ballot, const Roll& roll);
  std::optional<Decision> count(uint64_t frame_id, Ballot& ballot, const Roll& roll);
  std::optional<Decision> doubt(uint64_t frame_id, Ballot& ballot, uint64_t callers);
  Decision decide(uint64_t frame_id, Ballot& ballot, uint64_t reference, Verdict verdict);
  std::string voter_key(const WorkerId& id) const;  // its CURVE key, or "#" + its id when it has none
  std::set<std::string> keys_of(const Ballot& ballot, const std::set<WorkerId>& voters) const;
  std::set<std::string> possible_voters(const Ballot& ballot, const Roll& roll) const;
  static bool has_voted(const Ballot& ballot, const WorkerId& id);

  bool master_reference_;
  std::map<uint64_t, Ballot> ballots_;  // open frames, in frame order
  std::unordered_map<uint64_t, Held> held_;  // by job
  std::unordered_map<WorkerId, std::string> enrolled_;  // workers present: their keys
  std::map<std::string, uint32_t> standing_;            // by standing key: frames confirmed with its vote
  std::vector<HashDispute> disputes_;
  std::vector<HashDoubt> doubts_;
};

}  // namespace igi
