// The scheduler's failed jobs: results that fail validation, and the jobs
// that failed on every worker that could take them, which the caller renders
// itself (scheduler.h says the rules).
#include "scheduler/scheduler.h"

#include <algorithm>
#include <utility>

namespace igi {

void Scheduler::on_bad_result(const WorkerId& id, uint64_t job_id) {
  ++stats_.failed_results;
  auto w = workers_.find(id);
  const bool standing = !config_.failures_need_standing || (w != workers_.end() && w->second.answered > 0);
  drop_result(id, job_id);
  auto it = jobs_.find(job_id);
  if (it == jobs_.end()) return;
  Job& job = it->second;
  job.failed_on.insert(id);
  if (standing) job.counted_failers.insert(id);  // a peer that never returned a result only loses the job
  requeue(job_id);
  failing_.insert(job_id);
  hand_failed_jobs_to_caller();
}

// A queued job that failed on every worker present (on the only one, say),
// or on too many: no worker gets it again; the caller renders it itself.
void Scheduler::hand_failed_jobs_to_caller() {
  for (auto f = failing_.begin(); f != failing_.end();) {
    auto it = jobs_.find(*f);
    if (it == jobs_.end() || it->second.done || !it->second.queued) {
      f = failing_.erase(f);  // done, gone, or out again (a new failure adds it back)
      continue;
    }
    Job& job = it->second;
    // A caller that follows its workers would render another tile than theirs: only when none may take it.
    const bool too_many = config_.caller_renders && int(job.counted_failers.size()) >= config_.max_failed_workers;
    const bool nobody_else = std::none_of(workers_.begin(), workers_.end(), [&](const auto& w) {
      return !w.second.benched && !job.failed_on.count(w.first);
    }) && !workers_.empty();
    if (!too_many && !nobody_else) {
      ++f;
      continue;
    }
    make_own(*f, false);
    f = failing_.erase(f);
  }
}

std::vector<JobAssignment> Scheduler::take_own_jobs() { return std::exchange(own_jobs_, {}); }

bool Scheduler::wants_own_result(uint64_t job_id) const {
  auto it = jobs_.find(job_id);
  return it != jobs_.end() && it->second.own;
}

bool Scheduler::on_own_result(uint64_t job_id) {
  auto it = jobs_.find(job_id);
  if (it == jobs_.end() || !it->second.own) return false;
  Job& job = it->second;
  job.own = false;
  job.by_caller = !job.done;
  Frame& frame = frames_.at(job.frame_id);
  if (!job.done) complete(frame, job);
  if (!referee_.decided(job.frame_id)) try_decide(frame);  // the last job in: a lone voter may decide now
  return true;
}

// The caller follows its workers now: what it rendered of a frame not yet
// decided would be its own maths library's tile. Those jobs go to workers
// (one that has not failed them), or, failed by every one, back to it.
void Scheduler::return_callers_jobs() {
  for (auto& [frame_id, frame] : frames_) {
    if (referee_.decided(frame_id)) continue;
    for (uint64_t job_id : frame.jobs) {
      Job& job = jobs_.at(job_id);
      if (!job.own && !job.by_caller) continue;
      if (job.by_caller) {
        job.done = false;
        --frame.done;
      }
      job.own = job.by_caller = false;
      requeue(job_id);
      failing_.insert(job_id);
    }
  }
  hand_failed_jobs_to_caller();
}

std::vector<WorkerId> Scheduler::failed_on(uint64_t job_id) const {
  auto it = jobs_.find(job_id);
  if (it == jobs_.end()) return {};
  return {it->second.failed_on.begin(), it->second.failed_on.end()};
}

}  // namespace igi
