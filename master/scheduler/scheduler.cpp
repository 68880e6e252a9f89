#include "scheduler/scheduler.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace igi {
namespace {

constexpr size_t kRoundTrips = 64;     // the median is taken over this many recent jobs
constexpr size_t kMinRoundTrips = 8;   // fewer: no median yet
constexpr double kUnknownStragglerSeconds = 1.0;
constexpr double kLostSeconds = 60.0;  // a lone worker's job this old is lost, answered or not

bool same_tile(const TileJob& a, const TileJob& b) {
  return a.x == b.x && a.y == b.y && a.w == b.w && a.h == b.h && a.border == b.border;
}

double seconds_between(TimePoint from, TimePoint to) { return std::chrono::duration<double>(to - from).count(); }

}  // namespace

// ---- Workers.

void Scheduler::add_worker(const WorkerId& id, int credits) {
  Worker& w = workers_[id];
  w.max_credits = credits > 0 ? credits : config_.credits;
  w.credits = config_.first_credits > 0 ? std::min(config_.first_credits, w.max_credits) : w.max_credits;
  if (int(w.jobs.size()) < w.credits) hungry_.insert(id);
}

void Scheduler::remove_worker(const WorkerId& id) {
  auto it = workers_.find(id);
  if (it == workers_.end()) return;
  const std::vector<uint64_t> held = std::move(it->second.jobs);
  workers_.erase(it);
  hungry_.erase(id);
  // Newest first: each goes to the front, so the oldest ends up leading.
  for (auto j = held.rbegin(); j != held.rend(); ++j) {
    auto job = jobs_.find(*j);
    if (job == jobs_.end()) continue;
    release_holder(job->second, id, TimePoint{}, false);
    requeue(*j);
  }
  // Fewer possible voters may let a frame decide its hash.
  for (auto& [frame_id, frame] : frames_)
    if (!frame.reference) try_decide(frame);
}

int Scheduler::outstanding(const WorkerId& id) const {
  auto w = workers_.find(id);
  return w == workers_.end() ? 0 : int(w->second.jobs.size());
}

bool Scheduler::holds(const WorkerId& id, uint64_t job_id) const {
  auto job = jobs_.find(job_id);
  return job != jobs_.end() && std::any_of(job->second.holders.begin(), job->second.holders.end(),
                                           [&](const Holder& h) { return h.worker == id; });
}

bool Scheduler::answered(uint64_t job_id) const {
  auto job = jobs_.find(job_id);
  return job != jobs_.end() && (job->second.done || job->second.held_by.has_value());
}

std::vector<WorkerId> Scheduler::take_quarantined() { return std::exchange(newly_quarantined_, {}); }

// The worker no longer holds the job: its credit is free again.
void Scheduler::take_back(Worker& w, const WorkerId& id, uint64_t job_id) {
  auto it = std::find(w.jobs.begin(), w.jobs.end(), job_id);
  if (it == w.jobs.end()) return;
  w.jobs.erase(it);
  if (int(w.jobs.size()) < w.credits) hungry_.insert(id);
}

// ---- Frames and the pool.

void Scheduler::add_frame(uint64_t frame_id, const std::vector<TileJob>& tiles) {
  Frame& frame = frames_[frame_id];
  frame.id = frame_id;
  frame.by_vote = !config_.master_reference;
  for (const TileJob& tile : tiles) {
    const uint64_t id = next_job_id_++;
    Job& job = jobs_[id];
    job.holders.reserve(2);
    job.frame_id = frame_id;
    job.tile = tile;
    job.queued = true;
    frame.jobs.push_back(id);
    unassigned_.push_back(id);
  }
}

void Scheduler::requeue(uint64_t job_id) {
  auto it = jobs_.find(job_id);
  if (it == jobs_.end()) return;
  Job& job = it->second;
  if (job.done || job.held_by || !job.holders.empty() || job.queued || job.own) return;
  job.queued = true;
  unassigned_.push_front(job_id);
  ++stats_.reissued;
}

bool Scheduler::release_holder(Job& job, const WorkerId& id, TimePoint now, bool sample) {
  auto h = std::find_if(job.holders.begin(), job.holders.end(), [&](const Holder& x) { return x.worker == id; });
  if (h == job.holders.end()) return false;
  if (sample) {
    const double seconds = seconds_between(h->issued, now);
    if (round_trips_.size() < kRoundTrips) round_trips_.push_back(seconds);
    else round_trips_[round_trip_next_] = seconds;
    round_trip_next_ = (round_trip_next_ + 1) % kRoundTrips;
    median_.reset();
  }
  job.holders.erase(h);
  return true;
}

void Scheduler::complete(Frame& frame, Job& job) {
  job.done = true;
  job.queued = false;
  ++frame.done;
}

// A copy still out when its frame completes will never be wanted: its worker
// gets the credit back now (its result may have been lost on the way).
std::vector<uint64_t> Scheduler::take_completed_frames() {
  std::vector<uint64_t> done;
  while (!frames_.empty() && frames_.begin()->second.done == frames_.begin()->second.jobs.size()) {
    for (uint64_t job_id : frames_.begin()->second.jobs) {
      for (const Holder& h : jobs_.at(job_id).holders)
        if (auto w = workers_.find(h.worker); w != workers_.end()) take_back(w->second, h.worker, job_id);
      jobs_.erase(job_id);
    }
    done.push_back(frames_.begin()->first);
    frames_.erase(frames_.begin());
  }
  return done;
}

std::set<WorkerId> Scheduler::cancel_frame(uint64_t frame_id) {
  std::set<WorkerId> holders;
  auto frame = frames_.find(frame_id);
  if (frame == frames_.end()) return holders;
  for (uint64_t job_id : frame->second.jobs) {
    for (const Holder& h : jobs_.at(job_id).holders) {
      holders.insert(h.worker);
      if (auto w = workers_.find(h.worker); w != workers_.end()) take_back(w->second, h.worker, job_id);
    }
    jobs_.erase(job_id);  // its entries in unassigned_ and issued_ are skipped from now on
  }
  frames_.erase(frame);
  return holders;
}

// ---- Handing out jobs.

JobAssignment Scheduler::give(const WorkerId& id, uint64_t job_id, TimePoint now) {
  Job& job = jobs_.at(job_id);
  const bool duplicate = !job.holders.empty() || job.held_by.has_value();
  job.queued = false;
  const uint64_t serial = next_serial_++;
  job.holders.push_back({id, now, serial});
  Worker& w = workers_.at(id);
  w.jobs.push_back(job_id);
  if (int(w.jobs.size()) >= w.credits) hungry_.erase(id);
  issued_.push_back({now, job_id, id, serial});
  trim_issued();
  return JobAssignment{id, job_id, job.frame_id, job.tile, duplicate};
}

std::optional<uint64_t> Scheduler::front_unassigned() {
  while (!unassigned_.empty()) {
    auto it = jobs_.find(unassigned_.front());
    if (it != jobs_.end() && it->second.queued) return unassigned_.front();
    unassigned_.pop_front();  // done, held, the caller's or its frame gone since it was queued
  }
  return std::nullopt;
}

// Not a job it failed, nor one it is rendering (a forced copy goes to another).
bool Scheduler::may_take(const Job& job, const WorkerId& id) const {
  return !job.failed_on.count(id) &&
         std::none_of(job.holders.begin(), job.holders.end(), [&](const Holder& h) { return h.worker == id; });
}

// The first queued job the worker may take: almost always the front.
std::optional<size_t> Scheduler::next_unassigned_for(const WorkerId& id) {
  if (!front_unassigned()) return std::nullopt;
  for (size_t i = 0; i < unassigned_.size(); ++i) {
    auto it = jobs_.find(unassigned_[i]);
    if (it != jobs_.end() && it->second.queued && may_take(it->second, id)) return i;
  }
  return std::nullopt;
}

// Water-filling: first one job to each idle worker, then to each worker
// holding one, and so on; so work spreads over the workers, and a job never
// waits behind another on a busy worker while an idle one could take it.
void Scheduler::assign_unassigned(TimePoint now, std::vector<JobAssignment>& out) {
  std::vector<std::pair<size_t, const WorkerId*>> round;  // (jobs held, worker); give() changes hungry_
  for (size_t level = 0; !hungry_.empty() && front_unassigned(); ++level) {
    round.clear();
    size_t deepest = 0;
    for (const WorkerId& id : hungry_) {
      const Worker& w = workers_.find(id)->second;
      deepest = std::max(deepest, w.jobs.size());
      if (w.jobs.size() <= level) round.push_back({w.jobs.size(), &workers_.find(id)->first});
    }
    bool progress = false;
    for (const auto& [held, worker] : round) {
      const WorkerId& id = *worker;
      if (!hungry_.count(id)) continue;
      if (!front_unassigned()) return;
      std::optional<size_t> at = next_unassigned_for(id);
      if (!at) continue;  // every queued job is one it failed, or a forced copy for another worker
      const uint64_t job_id = unassigned_[*at];
      unassigned_.erase(unassigned_.begin() + long(*at));
      out.push_back(give(id, job_id, now));
      if (out.back().duplicate) ++stats_.duplicated;
      if (forced_duplicates_ > 0 && !out.back().duplicate) force_copy(id, job_id, now, out);
      progress = true;
    }
    if (!progress && level >= deepest) return;  // every hungry worker had its turn and took nothing
  }
}

// Test hook: a copy for another worker at once, beyond its credit if need be.
void Scheduler::force_copy(const WorkerId& holder, uint64_t job_id, TimePoint now, std::vector<JobAssignment>& out) {
  for (const auto& [id, worker] : workers_) {
    if (id == holder) continue;
    --forced_duplicates_;
    ++stats_.duplicated;
    out.push_back(give(id, job_id, now));
    return;
  }
}

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
  if (it == jobs_.end() || it->second.done || it->second.held_by) return false;
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
  for (uint64_t job_id : frame.held) {
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
    const bool voting = frame.by_vote || (frame.callers_hash && !frame.disputed);
    if (frame.reference || !voting || frame.held.empty() || frame.done + frame.held.size() != frame.jobs.size())
      continue;
    release_lost_copies(frame, now);
    const bool copy_out = std::any_of(frame.held.begin(), frame.held.end(),
                                      [&](uint64_t j) { return !jobs_.at(j).holders.empty(); });
    if (copy_out) continue;
    auto voted = [&](const WorkerId& id) {
      for (const auto& [hash, voters] : frame.votes)
        if (voters.count(id)) return true;
      return false;
    };
    const Job& job = jobs_.at(frame.held.front());
    auto w = std::find_if(hungry_.begin(), hungry_.end(),
                          [&](const WorkerId& id) { return !voted(id) && !job.failed_on.count(id); });
    if (w == hungry_.end()) continue;
    const WorkerId id = *w;
    ++stats_.verified;
    out.push_back(give(id, frame.held.front(), now));
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

std::vector<JobAssignment> Scheduler::assign(TimePoint now) {
  std::vector<JobAssignment> out;
  reclaim_lost(now);
  hand_failed_jobs_to_caller();
  if (hungry_.empty()) return out;
  assign_unassigned(now, out);
  if (hungry_.empty() || front_unassigned()) return out;
  assign_stragglers(now, out);
  assign_verifications(now, out);
  return out;
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

// ---- Results.

ResultCheck Scheduler::check_result(const WorkerId& id, uint64_t job_id, uint64_t frame_id, const TileJob& tile) const {
  auto it = jobs_.find(job_id);
  if (it == jobs_.end()) return ResultCheck::Unknown;
  const Job& job = it->second;
  const bool holder =
      std::any_of(job.holders.begin(), job.holders.end(), [&](const Holder& h) { return h.worker == id; });
  if (!holder) return ResultCheck::Unknown;  // not a job this worker was given (or still holds)
  if (job.frame_id != frame_id || !same_tile(job.tile, tile)) return ResultCheck::WrongTile;
  if (job.done || job.held_by) return ResultCheck::NotNeeded;
  return ResultCheck::Wanted;
}

void Scheduler::drop_result(const WorkerId& id, uint64_t job_id) {
  auto w = workers_.find(id);
  if (w != workers_.end()) take_back(w->second, id, job_id);
  auto job = jobs_.find(job_id);
  if (job != jobs_.end()) release_holder(job->second, id, TimePoint{}, false);
}

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
  if (!frame.reference) try_decide(frame);  // the last job in: a lone voter may decide now
  return true;
}

std::vector<WorkerId> Scheduler::failed_on(uint64_t job_id) const {
  auto it = jobs_.find(job_id);
  if (it == jobs_.end()) return {};
  return {it->second.failed_on.begin(), it->second.failed_on.end()};
}

ResultVerdict Scheduler::on_result(const WorkerId& id, uint64_t job_id, uint64_t hash, TimePoint now) {
  if (auto w = workers_.find(id); w != workers_.end()) {
    w->second.last_answer = now;
    w->second.overtaken = 0;
  }
  const std::vector<WorkerId> hoarders = overtaken_hoarders(id, job_id, now);
  const ResultVerdict verdict = record_result(id, job_id, hash, now);
  for (const WorkerId& h : hoarders) bench(h);
  return verdict;
}

// The job's other holders, when this is its first result, that have returned
// nothing since they got it, for longer than a copy waits to go out, and
// were overtaken so once before since their latest result.
std::vector<WorkerId> Scheduler::overtaken_hoarders(const WorkerId& id, uint64_t job_id, TimePoint now) {
  std::vector<WorkerId> hoarders;
  auto it = jobs_.find(job_id);
  if (it == jobs_.end() || it->second.done || it->second.held_by) return hoarders;
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

std::vector<WorkerId> Scheduler::take_benched() { return std::exchange(newly_benched_, {}); }

ResultVerdict Scheduler::record_result(const WorkerId& id, uint64_t job_id, uint64_t hash, TimePoint now) {
  auto it = jobs_.find(job_id);
  if (it == jobs_.end()) {
    drop_result(id, job_id);
    return ResultVerdict::Unknown;
  }
  Job& job = it->second;
  Frame& frame = frames_.at(job.frame_id);
  const bool first = !job.done && !job.held_by;
  auto holder = std::find_if(job.holders.begin(), job.holders.end(), [&](const Holder& h) { return h.worker == id; });
  const std::optional<uint64_t> serial = holder != job.holders.end() ? std::optional(holder->serial) : std::nullopt;
  release_holder(job, id, now, first);
  auto w = workers_.find(id);
  if (w != workers_.end()) {
    if (serial) w->second.newest_answered = std::max(w->second.newest_answered, *serial + 1);
    if (first) {
      ++w->second.answered;
      w->second.credits = std::min(w->second.credits + 1, w->second.max_credits);
    }
    take_back(w->second, id, job_id);
  }
  if (frame.reference) {
    if (hash != *frame.reference) {
      quarantine(id);
      requeue(job_id);
      return ResultVerdict::Rejected;
    }
    if (!first) {
      ++stats_.late_dropped;
      return ResultVerdict::Late;
    }
    complete(frame, job);
    return ResultVerdict::Accepted;
  }
  frame.votes[hash].insert(id);
  if (first) {
    job.held_by = id;
    job.held_hash = hash;
    frame.held.push_back(job_id);
  } else {
    ++stats_.late_dropped;
  }
  try_decide(frame);
  if (!first) return quarantined_.count(id) ? ResultVerdict::Rejected : ResultVerdict::Late;
  if (job.done) return ResultVerdict::Accepted;
  if (quarantined_.count(id)) return ResultVerdict::Rejected;
  ++stats_.held;
  return ResultVerdict::Held;
}

// ---- The reference hash.

// Workers that take jobs, and voters since gone or benched.
size_t Scheduler::possible_voters(const Frame& frame) const {
  auto takes_jobs = [&](const WorkerId& id) {
    auto w = workers_.find(id);
    return w != workers_.end() && !w->second.benched;
  };
  size_t n = size_t(std::count_if(workers_.begin(), workers_.end(), [](const auto& w) { return !w.second.benched; }));
  std::set<WorkerId> others;
  for (const auto& [hash, voters] : frame.votes)
    for (const WorkerId& v : voters)
      if (!takes_jobs(v)) others.insert(v);
  return n + others.size();
}

void Scheduler::set_reference(uint64_t frame_id, std::optional<uint64_t> hash) {
  auto it = frames_.find(frame_id);
  if (it == frames_.end() || it->second.reference) return;
  if (hash) {
    it->second.callers_hash = hash;
    return judge(it->second);
  }
  it->second.by_vote = true;
  try_decide(it->second);
}

// The caller's hash, once a worker agrees; or, once every worker present
// that could vote has (a proven one, or one rendering a job of the frame;
// once every job is answered, proven ones only) without one agreeing, the
// caller's hash all the same (the dissenters are quarantined), unless two or
// more agree on another: then the caller is likelier wrong than they, and it is asked.
void Scheduler::judge(Frame& frame) {
  if (frame.reference || !frame.callers_hash || frame.disputed) return;
  const uint64_t callers = *frame.callers_hash;
  if (frame.votes.count(callers)) return decide(frame, callers);
  if (frame.votes.empty()) return;
  auto voted = [&](const WorkerId& id) {
    return std::any_of(frame.votes.begin(), frame.votes.end(), [&](const auto& v) { return v.second.count(id) > 0; });
  };
  std::set<WorkerId> rendering;
  if (frame.done + frame.held.size() < frame.jobs.size())
    for (uint64_t job_id : frame.jobs)
      for (const Holder& h : jobs_.at(job_id).holders) rendering.insert(h.worker);
  for (const auto& [id, worker] : workers_)
    if (!worker.benched && (worker.answered > 0 || rendering.count(id)) && !voted(id))
      return;  // verification copies bring its vote
  if (frame.votes.size() == 1 && frame.votes.begin()->second.size() >= 2) {
    frame.disputed = true;
    const auto& [hash, voters] = *frame.votes.begin();
    disputes_.push_back(HashDispute{frame.id, callers, hash, {voters.begin(), voters.end()}});
    return;
  }
  decide(frame, callers);
}

std::vector<HashDispute> Scheduler::take_disputes() { return std::exchange(disputes_, {}); }

void Scheduler::follow_workers() {
  config_.master_reference = false;
  for (auto& [frame_id, frame] : frames_) {
    if (frame.reference) continue;
    frame.callers_hash.reset();
    frame.by_vote = true;
    if (frame.disputed) {
      frame.disputed = false;
      const uint64_t workers = frame.votes.begin()->first;
      decide(frame, workers);
    } else {
      try_decide(frame);
    }
  }
}

// At least two voters and a strict majority of the possible ones: the losers
// are always fewer than the winners. A worker decides alone only when it is
// the frame's only possible voter and has answered every job.
void Scheduler::try_decide(Frame& frame) {
  if (frame.callers_hash) return judge(frame);
  if (!frame.by_vote || frame.votes.empty()) return;
  const size_t possible = possible_voters(frame);
  for (const auto& [hash, voters] : frame.votes)
    if (voters.size() >= 2 && 2 * voters.size() > possible) {
      const uint64_t reference = hash;  // decide() clears the votes
      return decide(frame, reference);
    }
  const bool all_answered = frame.done + frame.held.size() == frame.jobs.size();
  if (frame.votes.size() == 1 && all_answered && possible == 1) {
    const uint64_t reference = frame.votes.begin()->first;
    decide(frame, reference);
  }
}

void Scheduler::decide(Frame& frame, uint64_t reference) {
  frame.reference = reference;
  std::vector<WorkerId> losers;
  for (const auto& [hash, voters] : frame.votes)
    if (hash != reference) losers.insert(losers.end(), voters.begin(), voters.end());
  frame.votes.clear();
  const std::vector<uint64_t> held = std::exchange(frame.held, {});
  for (uint64_t job_id : held) {
    auto it = jobs_.find(job_id);
    if (it == jobs_.end()) continue;
    Job& job = it->second;
    const bool agrees = job.held_hash == reference;
    job.held_by.reset();
    if (agrees) complete(frame, job);
    else requeue(job_id);
  }
  for (const WorkerId& v : losers) quarantine(v);
}

void Scheduler::quarantine(const WorkerId& id) {
  if (!quarantined_.insert(id).second) return;
  newly_quarantined_.push_back(id);
  ++stats_.quarantined;
  // Its unconfirmed results and votes elsewhere are not to be believed either.
  for (auto& [frame_id, frame] : frames_) {
    for (auto v = frame.votes.begin(); v != frame.votes.end();) {
      v->second.erase(id);
      v = v->second.empty() ? frame.votes.erase(v) : std::next(v);
    }
    std::vector<uint64_t> dropped;
    std::erase_if(frame.held, [&](uint64_t job_id) {
      Job& job = jobs_.at(job_id);
      if (job.held_by != id) return false;
      job.held_by.reset();
      dropped.push_back(job_id);
      return true;
    });
    for (uint64_t job_id : dropped) requeue(job_id);
  }
  remove_worker(id);  // its outstanding jobs go back; frames it blocked may decide now
}

std::optional<HashSplit> Scheduler::stalled_split() const {
  for (const auto& [frame_id, frame] : frames_) {
    if (frame.reference || !frame.by_vote || frame.votes.size() < 2) continue;
    bool everyone_voted = true;
    for (const auto& [id, worker] : workers_) {
      bool voted = false;
      for (const auto& [hash, voters] : frame.votes) voted = voted || voters.count(id);
      everyone_voted = everyone_voted && voted;
    }
    if (!everyone_voted) continue;
    HashSplit split;
    split.frame_id = frame_id;
    for (const auto& [hash, voters] : frame.votes) split.voters[hash].assign(voters.begin(), voters.end());
    return split;
  }
  return std::nullopt;
}

}  // namespace igi
