#include "scheduler.h"

#include <algorithm>

namespace igi {

void Scheduler::add_worker(const WorkerId& id, int credits) {
  workers_.try_emplace(id).first->second.credits = credits > 0 ? credits : credits_;
}

void Scheduler::remove_worker(const WorkerId& id) {
  auto it = workers_.find(id);
  if (it == workers_.end()) return;
  const std::set<uint64_t> held = it->second.jobs;
  workers_.erase(it);
  // Newest first: each goes to the front, so the oldest ends up leading.
  for (auto it = held.rbegin(); it != held.rend(); ++it) release(id, *it);
}

// A job lost its worker: back to the front of the queue unless another copy
// is still out or it is already done.
void Scheduler::release(const WorkerId& id, uint64_t job_id) {
  auto it = jobs_.find(job_id);
  if (it == jobs_.end()) return;
  Job& job = it->second;
  job.holders.erase(id);
  if (!job.done && job.holders.empty() &&
      std::find(unassigned_.begin(), unassigned_.end(), job_id) == unassigned_.end()) {
    unassigned_.push_front(job_id);
    ++stats_.reissued;
  }
}

void Scheduler::add_frame(uint64_t frame_id, const std::vector<TileJob>& tiles) {
  Frame& frame = frames_[frame_id];
  for (const TileJob& tile : tiles) {
    const uint64_t id = next_job_id_++;
    jobs_[id] = Job{frame_id, tile, {}, false};
    frame.jobs.push_back(id);
    unassigned_.push_back(id);
  }
}

std::optional<uint64_t> Scheduler::take_unassigned(const WorkerId& id) {
  for (auto it = unassigned_.begin(); it != unassigned_.end(); ++it)
    if (!jobs_[*it].holders.count(id)) {
      uint64_t job_id = *it;
      unassigned_.erase(it);
      return job_id;
    }
  return std::nullopt;
}

// The oldest outstanding job with a single holder that is not this worker.
std::optional<uint64_t> Scheduler::pick_straggler(const WorkerId& id) const {
  for (const auto& [frame_id, frame] : frames_)
    for (uint64_t job_id : frame.jobs) {
      const Job& job = jobs_.at(job_id);
      if (!job.done && job.holders.size() == 1 && !job.holders.count(id)) return job_id;
    }
  return std::nullopt;
}

std::optional<JobAssignment> Scheduler::next_job(const WorkerId& id) {
  auto w = workers_.find(id);
  if (w == workers_.end() || int(w->second.jobs.size()) >= w->second.credits) return std::nullopt;
  bool duplicate = false;
  std::optional<uint64_t> job_id = take_unassigned(id);
  if (!job_id) {
    job_id = pick_straggler(id);
    duplicate = job_id.has_value();
  }
  if (!job_id) return std::nullopt;
  Job& job = jobs_[*job_id];
  job.holders.insert(id);
  w->second.jobs.insert(*job_id);
  if (duplicate) ++stats_.duplicated;
  if (!duplicate && forced_duplicates_ > 0) {  // test hook: the next worker gets it too
    --forced_duplicates_;
    unassigned_.push_front(*job_id);
    ++stats_.duplicated;
  }
  return JobAssignment{*job_id, job.frame_id, job.tile, duplicate};
}

ResultVerdict Scheduler::on_result(const WorkerId& id, uint64_t job_id, uint64_t frame_state_hash) {
  auto it = jobs_.find(job_id);
  auto w = workers_.find(id);
  if (w != workers_.end()) w->second.jobs.erase(job_id);
  if (it == jobs_.end()) return ResultVerdict::Unknown;
  Job& job = it->second;
  job.holders.erase(id);
  if (job.done) {
    ++stats_.late_dropped;
    return ResultVerdict::Duplicate;
  }
  Frame& frame = frames_[job.frame_id];
  if (frame.state_hash && *frame.state_hash != frame_state_hash) {
    remove_worker(id);  // its other jobs go back too
    release(id, job_id);
    return ResultVerdict::HashMismatch;
  }
  frame.state_hash = frame_state_hash;
  job.done = true;
  ++frame.done;
  unassigned_.erase(std::remove(unassigned_.begin(), unassigned_.end(), job_id), unassigned_.end());
  return ResultVerdict::Accepted;
}

std::vector<uint64_t> Scheduler::take_completed_frames() {
  std::vector<uint64_t> done;
  while (!frames_.empty() && frames_.begin()->second.done == frames_.begin()->second.jobs.size()) {
    for (uint64_t job_id : frames_.begin()->second.jobs) jobs_.erase(job_id);
    done.push_back(frames_.begin()->first);
    frames_.erase(frames_.begin());
  }
  return done;
}

int Scheduler::outstanding(const WorkerId& id) const {
  auto w = workers_.find(id);
  return w == workers_.end() ? 0 : int(w->second.jobs.size());
}

}  // namespace igi
