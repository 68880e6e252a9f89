#pragma once
// Which tile job goes to which worker, and which results a frame may use:
// pure bookkeeping, no sockets, no clock of its own (callers pass `now`), so
// every rule is unit-tested (tests/master/scheduler/test_scheduler.cpp).
//
// Rules:
//  - Pull by credits: a worker holds at most `credits` jobs at once; jobs go
//    out when credit comes back (assign()), oldest frame first. With
//    `first_credits`, a new worker starts with that many and gains one per
//    result it returns, up to its own: a peer that claims many threads and
//    never answers holds a job or two, not dozens.
//  - Frames are pipelined: at most `frames_in_flight` frames are open.
//  - Stragglers: when nothing unassigned is left, a worker with free credit
//    gets a copy of the oldest outstanding job, but only of one older than
//    `straggler_factor` x the median round trip of recent jobs (at least
//    `min_straggler_seconds`; 1 s until 8 round trips are known), at most two
//    copies of a job, and at most `duplicate_budget` x the frame's jobs copies
//    per frame (a job ten times late is copied whatever the budget: its
//    result was lost). Workers that are all equally fast never render a tile
//    twice. Water-filling: idle workers get jobs before busy ones.
//  - A lone worker's job ten times late, when the worker has answered a job
//    given after it (or after a minute), was lost (no other worker can take
//    a copy): it goes back to the pool with the worker's credit, and the
//    worker renders it again.
//  - A copy still out when its frame completes gives its worker's credit back.
//  - The first usable result for a job wins; later copies are dropped.
//  - A result that fails validation (it does not decode, non-finite pixels,
//    a rectangle that is not its job's) releases the job to the pool, and the
//    job never goes back to a worker that failed it. When every worker
//    present has failed it, or `max_failed_workers` workers have (only while
//    the caller renders as workers do: not once it follows them), the caller
//    renders it itself (take_own_jobs(), then on_own_result()): no one
//    worker, nor two, can keep a frame from completing. With
//    `failures_need_standing` only workers that have returned a result count
//    towards that limit (fresh identities that fail on purpose only lose the
//    job, and the caller renders a job only when the workers present failed it).
//  - A worker declared dead gives its outstanding jobs back to the pool.
//  - Hoarders: when a copy of a job answers first and the job's other holder
//    has returned nothing since it got the job, for longer than a copy waits
//    to go out, the holder is overtaken. A worker overtaken twice with no
//    result in between (it heartbeats, so it is not dead, but holds jobs far
//    past the others' rate) is benched: its jobs go back to the pool and it
//    gets no more until a result of its own comes in (heard_result()), when it
//    starts again from one job. take_benched() names it. A benched worker is
//    no voter that a frame waits for.
//
// Which results count is the referee's (trust/referee.h): the scheduler
// hands it each result's hash and what it knows of a frame's voters, and
// applies its decisions: results it holds wait (a held job is not reissued;
// when a vote lacks voters once all its jobs are held, an idle worker that
// has not voted gets a copy to verify, and a late copy still out on a held
// job counts as lost, its worker's credit back so it can be the one), held
// results that agree count, the others go back to the pool, and losers are
// quarantined: removed, their jobs reissued, their unconfirmed results
// elsewhere dropped. A frame decided in doubt is the caller's to finish:
// every job of it that no result with its hash answered goes to
// take_own_jobs() (`contested`). A verdict against the caller's hash waits
// `vote_wait_seconds` after the latest join (the Roll's `settled`), so that a
// worker that starts late still votes.
#include <chrono>
#include <cstdint>
#include <deque>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <unordered_map>
#include <vector>

#include "core/frame.h"
#include "trust/referee.h"

namespace igi {

using SchedulerClock = std::chrono::steady_clock;
using TimePoint = SchedulerClock::time_point;

struct SchedulerConfig {
  int credits = 2;                     // a worker's default credits
  int frames_in_flight = 2;
  double straggler_factor = 3.0;       // late: older than this many median round trips...
  double min_straggler_seconds = 0.02; // ...and at least this old
  double duplicate_budget = 0.1;       // straggler copies per frame, as a fraction of its jobs (at least 1)
  int max_failed_workers = 2;          // distinct workers whose result for a job failed: the caller renders it
  bool failures_need_standing = false; // only failures from workers that have returned a result count
  bool master_reference = false;       // frames' hashes come from set_reference(), not from votes
  int first_credits = 0;               // a new worker's credits until it answers (0: all of them at once)
  double vote_wait_seconds = 0.0;      // a verdict against the caller's hash waits this long after the latest join
  bool caller_renders = true;          // the caller renders a job as workers would (not once it follows them)
};

struct JobAssignment {
  WorkerId worker;
  uint64_t job_id;
  uint64_t frame_id;
  TileJob tile;
  bool duplicate;  // another copy is out or answered (a straggler or a verification copy)
  bool contested = false;  // the caller's (take_own_jobs): its frame was decided in doubt, not a failed job
};

// What to do with a result's pixels, before they are read.
enum class ResultCheck {
  Wanted,     // the job's first result: copy the pixels, then call on_result()
  NotNeeded,  // another copy already answered: do not copy, but call on_result() (its hash is a vote)
  Unknown,    // no such job (its frame is complete, or never was): call drop_result()
  WrongTile,  // frame or rectangle differ from the job's: call on_bad_result()
};

enum class ResultVerdict {
  Accepted,  // counts towards its frame
  Held,      // kept until the frame's reference hash is decided
  Late,      // another copy answered first; dropped (its hash was checked)
  Rejected,  // its hash differs from the frame's reference: its worker is quarantined
  Contested, // its frame was decided in doubt and its hash differs: the caller renders the job, nobody is quarantined
  Unknown,   // no such job
};


struct SchedulerStats {
  uint64_t reissued = 0;      // jobs handed out again after a worker died, was quarantined, or failed them
  uint64_t duplicated = 0;    // straggler copies handed out
  uint64_t verified = 0;      // copies handed out so a second worker votes on a frame
  uint64_t late_dropped = 0;  // results that arrived after another copy answered
  uint64_t held = 0;          // results held until their frame's hash was decided
  uint64_t failed_results = 0;  // results that failed validation
  uint64_t own_jobs = 0;        // jobs given to the caller (take_own_jobs): no worker could render them, or contested
  uint64_t quarantined = 0;   // workers quarantined for a hash that lost
  uint64_t benched = 0;       // times a worker was benched for holding jobs it did not answer
  uint64_t doubted = 0;       // frames decided in doubt: the caller rendered what their workers' hash contested
};


class Scheduler {
 public:
  explicit Scheduler(SchedulerConfig config = {}) : config_(config), referee_(config.master_reference) {}
  Scheduler(int credits, int frames_in_flight) : Scheduler(SchedulerConfig{credits, frames_in_flight}) {}

  // credits: jobs this worker may hold; 0 means the configured default.
  // key: its CURVE key's name (empty: anonymous), by which it votes; `now`:
  // when it joined (a verdict against the caller's hash waits for late joiners).
  void add_worker(const WorkerId& id, int credits = 0, const std::string& key = {}, TimePoint now = {});
  // Forgets the worker (dead, left, or reconnected); its outstanding jobs go
  // back to the pool. Its held results and votes stay: they were correct or not
  // whether it lives or not.
  void remove_worker(const WorkerId& id);
  bool has_worker(const WorkerId& id) const { return workers_.count(id) > 0; }
  size_t worker_count() const { return workers_.size(); }

  // Frames added from now on wait for set_reference() (master_reference). Before the first frame.
  void judge_by_reference() {
    config_.master_reference = true;
    referee_.judge_by_reference();
  }
  void add_frame(uint64_t frame_id, const std::vector<TileJob>& tiles);
  bool can_add_frame() const { return int(frames_.size()) < config_.frames_in_flight; }
  // The view moved on: the frame and its jobs are forgotten, and the credit
  // of its copies out comes back at once (a result still on its way is
  // Unknown: drop_result()). Returns the workers that held any of its jobs.
  std::set<WorkerId> cancel_frame(uint64_t frame_id);
  size_t open_frames() const { return frames_.size(); }

  // Jobs for workers with free credit, as many as there are (in frame order).
  std::vector<JobAssignment> assign(TimePoint now);
  // When the oldest outstanding job becomes a straggler, or a lone worker's
  // job counts as lost (nullopt: none out, or that time is past `now`, when
  // assign() could not act on it); a caller sleeping in poll() wakes then to
  // call assign() again.
  std::optional<TimePoint> next_straggler_time(TimePoint now);
  // When a frame waiting for late joiners may be decided (nullopt: none waits).
  std::optional<TimePoint> next_verdict_time() const;

  ResultCheck check_result(const WorkerId& id, uint64_t job_id, uint64_t frame_id, const TileJob& tile) const;
  // The job was given to the worker lately (it holds it, or held it among
  // the last kGivenRemembered it was given): a result for any other is not its to send.
  bool was_given(const WorkerId& id, uint64_t job_id) const;
  // The frame's hash as the caller computed it (master_reference); none: the
  // caller could not, and the frame's workers vote. Results held for it count
  // now, or go back to the pool and quarantine their workers.
  void set_reference(uint64_t frame_id, std::optional<uint64_t> hash);
  // A result may decide its frame's reference hash and so quarantine workers
  // that contradicted it: take_quarantined() names them.
  ResultVerdict on_result(const WorkerId& id, uint64_t job_id, uint64_t frame_state_hash, TimePoint now);
  // The result's job is unknown: only the worker's credit comes back.
  void drop_result(const WorkerId& id, uint64_t job_id);
  // A result of the worker's passed: a benched one works again, from one job.
  void heard_result(const WorkerId& id);
  bool is_benched(const WorkerId& id) const;
  // Workers benched since the last call (hoarders: see above).
  std::vector<WorkerId> take_benched();
  // The result failed validation: the worker no longer holds the job, which
  // goes back to the pool for another worker, or to the caller's own.
  void on_bad_result(const WorkerId& id, uint64_t job_id);
  // Jobs that failed on every worker that could take them: the caller renders
  // each itself and hands the result in with on_own_result(). `worker` is empty.
  std::vector<JobAssignment> take_own_jobs();
  // The caller's own result for a job from take_own_jobs(): it counts, whatever
  // its frame's hash (the caller is the judge). False when the job is gone
  // (its frame was cancelled) or no longer the caller's (it follows its
  // workers now): then its pixels are not to be used (wants_own_result()).
  bool on_own_result(uint64_t job_id);
  bool wants_own_result(uint64_t job_id) const;
  // The workers whose results for the job failed validation, in no order.
  std::vector<WorkerId> failed_on(uint64_t job_id) const;

  // Frames whose every job is back and counted, in frame order; removes them,
  // and gives workers back the credit of copies still out for them.
  std::vector<uint64_t> take_completed_frames();
  // Workers quarantined since the last call (by on_result, or by a removal
  // that decided a frame); each is already removed, its jobs back in the pool.
  std::vector<WorkerId> take_quarantined();
  // The oldest frame that cannot be decided without another worker, if any.
  std::optional<HashSplit> stalled_split() const;
  // Frames disputed since the last call: the workers agree, the caller's hash differs.
  std::vector<HashDispute> take_disputes();
  // Frames decided in doubt since the last call (their contested jobs are in take_own_jobs()).
  std::vector<HashDoubt> take_doubts() { return referee_.take_doubts(); }
  uint32_t standing(const WorkerId& id) const { return referee_.standing(id); }
  // The caller gives up its own hashes: disputed frames take their workers'
  // hash, and this frame and every later one are decided by vote; a failed
  // job goes to the caller only when no worker present may take it, and the
  // jobs of undecided frames it rendered or is rendering go back to workers
  // (its tiles would be its own maths library's).
  void follow_workers();

  int outstanding(const WorkerId& id) const;
  bool holds(const WorkerId& id, uint64_t job_id) const;  // the worker has this job and has not answered it
  bool answered(uint64_t job_id) const;  // another copy's result is in (it counts, or is held for the hash)
  const SchedulerStats& stats() const { return stats_; }
  double median_round_trip() const;  // seconds; 0 before any
  double straggler_seconds() const;  // how old an outstanding copy is when it counts as late
  // Test hook: hand the next `n` jobs out twice on purpose (the copy at once, to another worker, whatever its credit).
  void force_duplicates(int n) { forced_duplicates_ = n; }

  const SchedulerConfig& config() const { return config_; }
  // Bookkeeping that must stay bounded however many frames pass (tests).
  size_t tracked_copies() const { return issued_.size(); }
  size_t tracked_jobs() const { return jobs_.size() + unassigned_.size(); }

 private:
  struct Holder {
    WorkerId worker;
    TimePoint issued;
    uint64_t serial = 0;  // copies in the order given
  };
  struct Job {
    uint64_t frame_id = 0;
    TileJob tile;
    std::vector<Holder> holders;  // workers rendering it now (at most two)
    bool done = false;
    bool queued = false;  // in unassigned_
    std::set<WorkerId> failed_on;    // every worker that failed it: it never goes back to them
    std::set<WorkerId> counted_failers;  // those whose failures count (failures_need_standing)
    bool own = false;                // the caller renders it (take_own_jobs)
    bool by_caller = false;          // done by the caller's own result (on_own_result)
  };
  struct Frame {
    uint64_t id = 0;
    std::vector<uint64_t> jobs;
    size_t done = 0;
    size_t copies = 0;  // straggler copies handed out
  };
  struct Worker {
    std::vector<uint64_t> jobs;  // in the order given (at most its credits)
    int credits = 1;             // now: grows with results up to max_credits
    int max_credits = 1;
    uint64_t answered = 0;       // results it returned first (it renders: a proven worker)
    uint64_t newest_answered = 0;  // 1 + the serial of the newest copy it has answered (0: none)
    TimePoint last_answer{};       // its latest result of any kind
    int overtaken = 0;             // its jobs answered first by copies since its latest result
    bool benched = false;          // overtaken twice: no jobs until it answers
    std::vector<uint64_t> given;   // the last kGivenRemembered jobs given to it, as a ring
    size_t given_next = 0;
  };
  struct Issue {
    TimePoint at;
    uint64_t job_id;
    WorkerId worker;
    uint64_t serial = 0;
  };

  void reclaim_lost(TimePoint now);
  void assign_unassigned(TimePoint now, std::vector<JobAssignment>& out);
  void assign_stragglers(TimePoint now, std::vector<JobAssignment>& out);
  void assign_verifications(TimePoint now, std::vector<JobAssignment>& out);
  std::optional<uint64_t> front_unassigned();
  std::optional<size_t> next_unassigned_for(const WorkerId& id);  // index in unassigned_
  bool may_take(const Job& job, const WorkerId& id) const;
  void hand_failed_jobs_to_caller();
  void return_callers_jobs();  // follow_workers(): the caller's tiles of undecided frames
  bool is_outstanding(const Issue& issue) const;
  void trim_issued();
  bool straggler_eligible(const Issue& issue, TimePoint now) const;
  void release_lost_copies(const Frame& frame, TimePoint now);
  size_t duplicate_budget(const Frame& frame) const;
  JobAssignment give(const WorkerId& id, uint64_t job_id, TimePoint now);
  void force_copy(const WorkerId& holder, uint64_t job_id, TimePoint now, std::vector<JobAssignment>& out);
  void take_back(Worker& w, const WorkerId& id, uint64_t job_id);
  void requeue(uint64_t job_id);  // back to the front of the pool, unless out, held, done or queued
  bool release_holder(Job& job, const WorkerId& id, TimePoint now, bool sample);
  void complete(Frame& frame, Job& job);
  void make_own(uint64_t job_id, bool contested);  // the caller renders it (take_own_jobs)
  void decide_settled(TimePoint now);  // frames that waited for late joiners
  Roll roll(const Frame& frame) const;
  void try_decide(Frame& frame);
  void apply(const Decision& decision);
  void quarantine(const WorkerId& id);
  ResultVerdict record_result(const WorkerId& id, uint64_t job_id, uint64_t hash, TimePoint now);
  std::vector<WorkerId> overtaken_hoarders(const WorkerId& id, uint64_t job_id, TimePoint now);
  void bench(const WorkerId& id);

  static constexpr size_t kGivenRemembered = 256;

  SchedulerConfig config_;
  Referee referee_;  // the verdict on each frame's hash
  TimePoint latest_{};     // the latest `now` a caller passed
  TimePoint last_join_{};  // when the latest worker joined
  bool settle_pending_ = false;  // a join since decide_settled() last ran
  int forced_duplicates_ = 0;
  uint64_t next_job_id_ = 1;
  uint64_t next_serial_ = 0;  // of copies given
  std::map<WorkerId, Worker> workers_;
  std::set<WorkerId> hungry_;  // workers with free credit
  std::set<WorkerId> quarantined_;        // ever, this session
  std::vector<WorkerId> newly_quarantined_;
  std::map<uint64_t, Frame> frames_;
  std::unordered_map<uint64_t, Job> jobs_;
  std::deque<uint64_t> unassigned_;  // in the order they should go out; stale entries skipped
  std::deque<Issue> issued_;         // copies in the order handed out; stale entries skipped
  std::set<uint64_t> failing_;       // queued jobs that failed somewhere: may be the caller's now
  std::vector<JobAssignment> own_jobs_;  // for the caller to render (take_own_jobs)
  std::vector<WorkerId> newly_benched_;
  std::vector<double> round_trips_;  // the latest kRoundTrips, as a ring
  size_t round_trip_next_ = 0;
  mutable std::optional<double> median_;  // of round_trips_, until the next sample
  SchedulerStats stats_;
};

}  // namespace igi
