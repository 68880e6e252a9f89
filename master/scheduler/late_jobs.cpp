// The scheduler's late jobs: copies of stragglers, verification copies,
// lost results of a lone worker, and hoarders (scheduler.h says the rules).
#include "scheduler/scheduler.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace igi {
namespace {

constexpr size_t kMinRoundTrips = 8;   // fewer: no median yet
constexpr double kUnknownStragglerSeconds = 1.0;
constexpr double kLostSeconds = 60.0;  // a lone worker's job this old is lost, answered or not

double seconds_between(TimePoint from, TimePoint to) { return std::chrono::duration<double>(to - from).count(); }

}  // namespace

double Scheduler::median_round_trip() const {
  if (round_trips_.empty()) return 0.0;
  if (!median_) {
    std::vector<double> sorted = round_trips_;
    std::nth_element(sorted.begin(), sorted.begin() + long(sorted.size() / 2), sorted.end());
    median_ = sorted[sorted.size() / 2];
  }
  return *median_;
}

double Scheduler::straggler_seconds() const {
  const double typical =
      round_trips_.size() < kMinRoundTrips ? kUnknownStragglerSeconds : config_.straggler_factor * median_round_trip();
  return std::max(config_.min_straggler_seconds, typical);
}

size_t Scheduler::duplicate_budget(const Frame& frame) const {
  return std::max<size_t>(1, size_t(std::ceil(config_.duplicate_budget * double(frame.jobs.size()))));
}

bool Scheduler::is_outstanding(const Issue& issue) const {
  auto it = jobs_.find(issue.job_id);
  if (it == jobs_.end() || it->second.done || referee_.holds(issue.job_id)) return false;
  const auto& holders = it->second.holders;
  return std::any_of(holders.begin(), holders.end(),
                     [&](const Holder& h) { return h.worker == issue.worker && h.issued == issue.at; });
}

// Outstanding with a single copy out, and its frame has copies to spare.
// Outstanding with a single copy out, and its frame has copies to spare; or
// so overdue (ten times late) that its result was surely lost: a frame must
// not wait for ever on a worker that is alive but lost what it was sending.
bool Scheduler::straggler_eligible(const Issue& issue, TimePoint now) const {
  const Job& job = jobs_.at(issue.job_id);
  const Frame& frame = frames_.at(job.frame_id);
  const bool overdue = seconds_between(issue.at, now) >= 10.0 * straggler_seconds();
  return job.holders.size() == 1 && (frame.copies < duplicate_budget(frame) || overdue);
}

// Copies answered, released or of a finished frame leave the front: the
// queue holds no more than the copies issued since the oldest still out.
void Scheduler::trim_issued() {
  while (!issued_.empty() && !is_outstanding(issued_.front())) issued_.pop_front();
}

void Scheduler::assign_stragglers(TimePoint now, std::vector<JobAssignment>& out) {
  trim_issued();
  const double late = straggler_seconds();
  // Oldest first; stop at the first that is not late yet (all after it are younger).
  const size_t n = issued_.size();
  for (size_t i = 0; i < n && !hungry_.empty(); ++i) {
    const Issue issue = issued_[i];
    if (seconds_between(issue.at, now) < late) break;
    if (!is_outstanding(issue) || !straggler_eligible(issue, now)) continue;
    // A proven worker (one that has answered) first: a copy given to another
    // silent newcomer could be held as long as the original.
    const Job& job = jobs_.at(issue.job_id);
    auto other = [&](const WorkerId& id) { return id != issue.worker && !job.failed_on.count(id); };
    auto w = std::find_if(hungry_.begin(), hungry_.end(),
                          [&](const WorkerId& id) { return other(id) && workers_.at(id).answered > 0; });
    if (w == hungry_.end()) w = std::find_if(hungry_.begin(), hungry_.end(), other);
    if (w == hungry_.end()) break;
    const WorkerId id = *w;
    ++frames_.at(jobs_.at(issue.job_id).frame_id).copies;
    ++stats_.duplicated;
    out.push_back(give(id, issue.job_id, now));
  }
}

// A copy of an answered job that is late has surely been lost (a worker
// that is alive and dropped its result): its worker gets the credit back, so
// that it can vote on the frame with a fresh copy.
void Scheduler::release_lost_copies(const Frame& frame, TimePoint now) {
  const double late = straggler_seconds();
  for (uint64_t job_id : referee_.held_jobs(frame.id)) {
    Job& job = jobs_.at(job_id);
    std::vector<WorkerId> lost;
    for (const Holder& h : job.holders)
      if (seconds_between(h.issued, now) >= late) lost.push_back(h.worker);
    for (const WorkerId& id : lost) drop_result(id, job_id);
  }
}

// A frame whose every job is answered but whose hash is undecided needs
// another worker's vote: an idle worker that has not voted renders a copy.
void Scheduler::assign_verifications(TimePoint now, std::vector<JobAssignment>& out) {
  for (auto& entry : frames_) {
    const Frame& frame = entry.second;  // a plain reference: clang 14 lambdas cannot capture structured bindings
    if (hungry_.empty()) return;
    const std::vector<uint64_t>& held = referee_.held_jobs(frame.id);
    if (!referee_.wants_votes(frame.id) || held.empty() || frame.done + held.size() != frame.jobs.size()) continue;
    release_lost_copies(frame, now);
    const bool copy_out =
        std::any_of(held.begin(), held.end(), [&](uint64_t j) { return !jobs_.at(j).holders.empty(); });
    if (copy_out) continue;
    const Job& job = jobs_.at(held.front());
    auto w = std::find_if(hungry_.begin(), hungry_.end(), [&](const WorkerId& id) {
      return !referee_.voted(frame.id, id) && !job.failed_on.count(id);
    });
    if (w == hungry_.end()) continue;
    const WorkerId id = *w;
    ++stats_.verified;
    out.push_back(give(id, held.front(), now));
  }
}

// A copy ten times late whose worker is the only one: no other worker can
// take a straggler copy. If the worker has answered a job given after it (it
// renders its jobs in order), or a minute has passed, its result is taken as
// lost and the job goes back to the pool with its worker's credit: the same
// worker renders it again (should the first result come after all, the
// second is dropped). A slow tile on a lone worker is not rendered twice.
void Scheduler::reclaim_lost(TimePoint now) {
  if (workers_.size() != 1) return;
  trim_issued();
  const double late = 10.0 * straggler_seconds();
  const Worker& worker = workers_.begin()->second;
  std::vector<Issue> reclaimed;
  for (const Issue& issue : issued_) {
    const double age = seconds_between(issue.at, now);
    if (age < late) break;
    const bool overtaken = worker.newest_answered > issue.serial + 1;  // a job given after it came back
    if ((overtaken || age >= kLostSeconds) && is_outstanding(issue) && jobs_.at(issue.job_id).holders.size() == 1)
      reclaimed.push_back(issue);
  }
  for (const Issue& issue : reclaimed) {
    drop_result(issue.worker, issue.job_id);
    requeue(issue.job_id);
  }
}

std::optional<TimePoint> Scheduler::next_straggler_time(TimePoint now) {
  if (hungry_.empty() && workers_.size() != 1) return std::nullopt;  // a lone worker's lost jobs come back
  trim_issued();
  const double late = straggler_seconds();
  for (const Issue& issue : issued_) {
    if (!is_outstanding(issue)) continue;
    const Job& job = jobs_.at(issue.job_id);
    const Frame& frame = frames_.at(job.frame_id);
    if (job.holders.size() != 1) continue;
    double seconds = 10 * late;  // overdue: a copy whatever the budget
    if (workers_.size() > 1 && frame.copies < duplicate_budget(frame)) seconds = late;
    if (workers_.size() == 1 && workers_.begin()->second.newest_answered <= issue.serial + 1)
      seconds = std::max(seconds, kLostSeconds);  // nothing overtook it (reclaim_lost)
    const TimePoint when = issue.at + std::chrono::duration_cast<SchedulerClock::duration>(std::chrono::duration<double>(seconds));
    // Past already: assign() just ran and could not act (no other worker free);
    // what could change that (a result, a join) arrives as traffic and wakes the caller.
    return when > now ? std::optional(when) : std::nullopt;
  }
  return std::nullopt;
}

// The job's other holders, when this is its first result, that have returned
// nothing since they got it, for longer than a copy waits to go out, and
// were overtaken so once before since their latest result.
std::vector<WorkerId> Scheduler::overtaken_hoarders(const WorkerId& id, uint64_t job_id, TimePoint now) {
  std::vector<WorkerId> hoarders;
  auto it = jobs_.find(job_id);
  if (it == jobs_.end() || it->second.done || referee_.holds(job_id)) return hoarders;
  const double late = straggler_seconds();
  for (const Holder& h : it->second.holders) {
    auto w = workers_.find(h.worker);
    if (h.worker == id || w == workers_.end() || w->second.benched) continue;
    if (seconds_between(std::max(w->second.last_answer, h.issued), now) >= late && ++w->second.overtaken >= 2)
      hoarders.push_back(h.worker);
  }
  return hoarders;
}

// Its jobs go back to the pool (in order, as a dead worker's do); it keeps
// its connection, and its next result brings it back (heard_result()).
void Scheduler::bench(const WorkerId& id) {
  auto it = workers_.find(id);
  if (it == workers_.end() || it->second.benched) return;
  Worker& w = it->second;
  w.benched = true;
  w.credits = 0;
  hungry_.erase(id);
  const std::vector<uint64_t> held = std::exchange(w.jobs, {});
  for (auto j = held.rbegin(); j != held.rend(); ++j) {
    auto job = jobs_.find(*j);
    if (job == jobs_.end()) continue;
    release_holder(job->second, id, TimePoint{}, false);
    requeue(*j);
  }
  ++stats_.benched;
  newly_benched_.push_back(id);
}

void Scheduler::heard_result(const WorkerId& id) {
  auto it = workers_.find(id);
  if (it == workers_.end() || !it->second.benched) return;
  it->second.benched = false;
  it->second.credits = 1;  // and one more per result, as a newcomer
  if (it->second.jobs.empty()) hungry_.insert(id);
}

bool Scheduler::is_benched(const WorkerId& id) const {
  auto it = workers_.find(id);
  return it != workers_.end() && it->second.benched;
}

std::vector<WorkerId> Scheduler::take_benched() { return std::exchange(newly_benched_, {}); }

}  // namespace igi
