#pragma once
// Which tile job goes to which worker: pure bookkeeping, no sockets, no
// clocks of its own (callers pass `now`), so every rule is unit-tested.
//
// Rules:
//  - Pull by credits: a worker holds at most `credits` jobs at once.
//  - Frames are pipelined: jobs of the next frame are handed out once the
//    current frame's are all assigned (at most `frames_in_flight` frames).
//  - Stragglers: when nothing unassigned is left, an idle worker gets a
//    duplicate of the oldest outstanding job (at most two copies in flight).
//  - The first result for a job wins; later copies are dropped.
//  - A worker declared dead or banned gives its jobs back to the pool.
//  - A result whose VPL-set hash differs from the frame's first result bans
//    its worker (reported), and the job is issued again.
#include <cstdint>
#include <deque>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "render/frame.h"

namespace igi {

using WorkerId = std::string;  // the ZeroMQ identity

struct JobAssignment {
  uint64_t job_id;
  uint64_t frame_id;
  TileJob tile;
  bool duplicate;
};

enum class ResultVerdict { Accepted, Duplicate, Unknown, HashMismatch };

struct SchedulerStats {
  uint64_t reissued = 0;      // jobs handed out again after a worker died or was banned
  uint64_t duplicated = 0;    // straggler copies handed out
  uint64_t late_dropped = 0;  // results that arrived after another copy won
};

class Scheduler {
 public:
  Scheduler(int credits, int frames_in_flight) : credits_(credits), frames_in_flight_(frames_in_flight) {}

  // credits: jobs this worker may hold; 0 means the scheduler's default.
  void add_worker(const WorkerId& id, int credits = 0);
  // Forgets the worker; its outstanding jobs go back to the pool.
  void remove_worker(const WorkerId& id);
  bool has_worker(const WorkerId& id) const { return workers_.count(id) > 0; }
  size_t worker_count() const { return workers_.size(); }

  void add_frame(uint64_t frame_id, const std::vector<TileJob>& tiles);
  bool can_add_frame() const { return int(frames_.size()) < frames_in_flight_; }

  // The next job for this worker, or nothing (no credit, or no work).
  std::optional<JobAssignment> next_job(const WorkerId& id);
  ResultVerdict on_result(const WorkerId& id, uint64_t job_id, uint64_t frame_state_hash);
  // Frames whose every job is back, in frame order; removes them.
  std::vector<uint64_t> take_completed_frames();

  int outstanding(const WorkerId& id) const;
  const SchedulerStats& stats() const { return stats_; }
  // Test hook: hand the next `n` jobs out twice on purpose.
  void force_duplicates(int n) { forced_duplicates_ = n; }

 private:
  struct Job {
    uint64_t frame_id;
    TileJob tile;
    std::set<WorkerId> holders;  // workers rendering it now
    bool done = false;
  };
  struct Frame {
    std::vector<uint64_t> jobs;
    size_t done = 0;
    std::optional<uint64_t> state_hash;
  };
  struct Worker {
    std::set<uint64_t> jobs;
    int credits = 1;
  };
  std::optional<uint64_t> take_unassigned(const WorkerId& id);
  std::optional<uint64_t> pick_straggler(const WorkerId& id) const;
  void release(const WorkerId& id, uint64_t job_id);

  int credits_;
  int frames_in_flight_;
  int forced_duplicates_ = 0;
  uint64_t next_job_id_ = 1;
  std::map<WorkerId, Worker> workers_;
  std::map<uint64_t, Frame> frames_;
  std::map<uint64_t, Job> jobs_;
  std::deque<uint64_t> unassigned_;  // in the order they should go out
  SchedulerStats stats_;
};

}  // namespace igi
