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
    const bool too_many = int(job.counted_failers.size()) >= config_.max_failed_workers;
    const bool nobody_else = std::none_of(workers_.begin(), workers_.end(), [&](const auto& w) {
      return !w.second.benched && !job.failed_on.count(w.first);
    }) && !workers_.empty();
    if (!too_many && !nobody_else) {
      ++f;
      continue;
    }
    job.queued = false;  // its entry in unassigned_ is skipped from now on
    job.own = true;
    ++stats_.own_jobs;
    own_jobs_.push_back(JobAssignment{WorkerId{}, *f, job.frame_id, job.tile, false});
    f = failing_.erase(f);
  }
}

std::vector<JobAssignment> Scheduler::take_own_jobs() { return std::exchange(own_jobs_, {}); }

bool Scheduler::on_own_result(uint64_t job_id) {
  auto it = jobs_.find(job_id);
  if (it == jobs_.end() || !it->second.own) return false;
  Job& job = it->second;
  job.own = false;
  Frame& frame = frames_.at(job.frame_id);
  if (!job.done) complete(frame, job);
  if (!referee_.decided(job.frame_id)) try_decide(frame);  // the last job in: a lone voter may decide now
  return true;
}

std::vector<WorkerId> Scheduler::failed_on(uint64_t job_id) const {
  auto it = jobs_.find(job_id);
  if (it == jobs_.end()) return {};
  return {it->second.failed_on.begin(), it->second.failed_on.end()};
}

}  // namespace igi
