#include "scheduler/scheduler.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace igi {
namespace {

constexpr size_t kRoundTrips = 64;     // the median is taken over this many recent jobs

bool same_tile(const TileJob& a, const TileJob& b) {
  return a.x == b.x && a.y == b.y && a.w == b.w && a.h == b.h && a.border == b.border;
}

double seconds_between(TimePoint from, TimePoint to) { return std::chrono::duration<double>(to - from).count(); }

SchedulerClock::duration wait_duration(double seconds) {
  return std::chrono::duration_cast<SchedulerClock::duration>(std::chrono::duration<double>(seconds));
}

}  // namespace

// ---- Workers.

void Scheduler::add_worker(const WorkerId& id, int credits, const std::string& key, TimePoint now) {
  Worker& w = workers_[id];
  w.max_credits = credits > 0 ? credits : config_.credits;
  w.credits = config_.first_credits > 0 ? std::min(config_.first_credits, w.max_credits) : w.max_credits;
  if (int(w.jobs.size()) < w.credits) hungry_.insert(id);
  referee_.enroll(id, key);
  last_join_ = std::max(last_join_, now);
  settle_pending_ = true;
}

void Scheduler::remove_worker(const WorkerId& id) {
  auto it = workers_.find(id);
  if (it == workers_.end()) return;
  const std::vector<uint64_t> held = std::move(it->second.jobs);
  workers_.erase(it);
  hungry_.erase(id);
  referee_.leave(id);
  // Newest first: each goes to the front, so the oldest ends up leading.
  for (auto j = held.rbegin(); j != held.rend(); ++j) {
    auto job = jobs_.find(*j);
    if (job == jobs_.end()) continue;
    release_holder(job->second, id, TimePoint{}, false);
    requeue(*j);
  }
  // Fewer possible voters may let a frame decide its hash.
  for (auto& [frame_id, frame] : frames_)
    if (!referee_.decided(frame_id)) try_decide(frame);
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
  return job != jobs_.end() && (job->second.done || referee_.holds(job_id));
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
  referee_.open(frame_id);
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
  if (job.done || referee_.holds(job_id) || !job.holders.empty() || job.queued || job.own) return;
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
    referee_.close(frames_.begin()->first);
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
  referee_.close(frame_id);
  frames_.erase(frame);
  return holders;
}

// ---- Handing out jobs.

JobAssignment Scheduler::give(const WorkerId& id, uint64_t job_id, TimePoint now) {
  Job& job = jobs_.at(job_id);
  const bool duplicate = !job.holders.empty() || referee_.holds(job_id);
  job.queued = false;
  const uint64_t serial = next_serial_++;
  job.holders.push_back({id, now, serial});
  Worker& w = workers_.at(id);
  w.jobs.push_back(job_id);
  if (w.given.size() < kGivenRemembered) w.given.push_back(job_id);
  else w.given[w.given_next] = job_id;
  w.given_next = (w.given_next + 1) % kGivenRemembered;
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

std::vector<JobAssignment> Scheduler::assign(TimePoint now) {
  std::vector<JobAssignment> out;
  latest_ = std::max(latest_, now);
  decide_settled(now);
  reclaim_lost(now);
  hand_failed_jobs_to_caller();
  if (hungry_.empty()) return out;
  assign_unassigned(now, out);
  if (hungry_.empty() || front_unassigned()) return out;
  assign_stragglers(now, out);
  assign_verifications(now, out);
  return out;
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
  if (job.done || referee_.holds(job_id)) return ResultCheck::NotNeeded;
  return ResultCheck::Wanted;
}

bool Scheduler::was_given(const WorkerId& id, uint64_t job_id) const {
  auto w = workers_.find(id);
  return w != workers_.end() && std::find(w->second.given.begin(), w->second.given.end(), job_id) != w->second.given.end();
}

void Scheduler::drop_result(const WorkerId& id, uint64_t job_id) {
  auto w = workers_.find(id);
  if (w != workers_.end()) take_back(w->second, id, job_id);
  auto job = jobs_.find(job_id);
  if (job != jobs_.end()) release_holder(job->second, id, TimePoint{}, false);
}

ResultVerdict Scheduler::on_result(const WorkerId& id, uint64_t job_id, uint64_t hash, TimePoint now) {
  latest_ = std::max(latest_, now);
  if (auto w = workers_.find(id); w != workers_.end()) {
    w->second.last_answer = now;
    w->second.overtaken = 0;
  }
  const std::vector<WorkerId> hoarders = overtaken_hoarders(id, job_id, now);
  const ResultVerdict verdict = record_result(id, job_id, hash, now);
  for (const WorkerId& h : hoarders) bench(h);
  return verdict;
}

ResultVerdict Scheduler::record_result(const WorkerId& id, uint64_t job_id, uint64_t hash, TimePoint now) {
  auto it = jobs_.find(job_id);
  if (it == jobs_.end()) {
    drop_result(id, job_id);
    return ResultVerdict::Unknown;
  }
  Job& job = it->second;
  Frame& frame = frames_.at(job.frame_id);
  const bool first = !job.done && !referee_.holds(job_id);
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
  switch (referee_.vote(job.frame_id, job_id, id, hash, first)) {
    case Vote::Wrong:
      quarantine(id);
      requeue(job_id);
      return ResultVerdict::Rejected;
    case Vote::Late:
      ++stats_.late_dropped;
      return ResultVerdict::Late;
    case Vote::Contested:
      make_own(job_id, true);
      return ResultVerdict::Contested;
    case Vote::Counts:
      complete(frame, job);
      return ResultVerdict::Accepted;
    case Vote::Recorded:
      break;
  }
  if (!first) ++stats_.late_dropped;
  try_decide(frame);
  if (!first) return quarantined_.count(id) ? ResultVerdict::Rejected : ResultVerdict::Late;
  if (job.done) return ResultVerdict::Accepted;
  if (quarantined_.count(id)) return ResultVerdict::Rejected;
  ++stats_.held;
  return ResultVerdict::Held;
}

// ---- The verdict (trust/referee.h), applied to the jobs.

void Scheduler::set_reference(uint64_t frame_id, std::optional<uint64_t> hash) {
  auto it = frames_.find(frame_id);
  if (it == frames_.end() || referee_.decided(frame_id)) return;
  referee_.set_reference(frame_id, hash);
  try_decide(it->second);
}

std::vector<HashDispute> Scheduler::take_disputes() { return referee_.take_disputes(); }

void Scheduler::follow_workers() {
  config_.master_reference = false;
  config_.caller_renders = false;
  referee_.follow_workers();
  return_callers_jobs();
  for (auto& [frame_id, frame] : frames_) {
    if (referee_.decided(frame_id)) continue;
    if (std::optional<Decision> d = referee_.stop_judging(frame_id)) apply(*d);
    else try_decide(frame);
  }
}

// What the referee needs to know of the frame's possible voters: every
// worker that takes jobs is awaited (verification copies bring its vote).
Roll Scheduler::roll(const Frame& frame) const {
  Roll roll;
  roll.all_answered = frame.done + referee_.held_count(frame.id) == frame.jobs.size();
  roll.settled = latest_ >= last_join_ + wait_duration(config_.vote_wait_seconds);
  for (const auto& [id, worker] : workers_) {
    roll.present.insert(id);
    if (worker.benched) continue;
    roll.active.insert(id);
    roll.awaited.insert(id);
  }
  return roll;
}

// A join restarts the wait; once it has passed, frames that waited for it are judged.
void Scheduler::decide_settled(TimePoint now) {
  if (!settle_pending_ || now < last_join_ + wait_duration(config_.vote_wait_seconds)) return;
  settle_pending_ = false;
  for (auto& [frame_id, frame] : frames_)
    if (!referee_.decided(frame_id)) try_decide(frame);
}

std::optional<TimePoint> Scheduler::next_verdict_time() const {
  const bool undecided = std::any_of(frames_.begin(), frames_.end(), [&](const auto& f) {
    return !referee_.decided(f.first) && referee_.held_count(f.first) > 0;
  });
  if (!settle_pending_ || !undecided) return std::nullopt;
  return last_join_ + wait_duration(config_.vote_wait_seconds);
}

void Scheduler::try_decide(Frame& frame) {
  if (std::optional<Decision> d = referee_.try_decide(frame.id, roll(frame))) apply(*d);
}

// Held results that agree count, the others go back to the pool, and the
// losers are quarantined. In doubt, every job the caller's hash has no result
// for is the caller's: its workers would only answer it with theirs again.
void Scheduler::apply(const Decision& d) {
  Frame& frame = frames_.at(d.frame_id);
  for (const auto& [job_id, agrees] : d.held) {
    auto it = jobs_.find(job_id);
    if (it == jobs_.end()) continue;
    if (agrees) complete(frame, it->second);
    else if (!d.doubt) requeue(job_id);
  }
  if (d.doubt) {
    ++stats_.doubted;
    for (uint64_t job_id : frame.jobs) make_own(job_id, true);
  }
  for (const WorkerId& v : d.losers) quarantine(v);
}

void Scheduler::make_own(uint64_t job_id, bool contested) {
  Job& job = jobs_.at(job_id);
  if (job.done || job.own) return;
  job.queued = false;  // its entry in unassigned_ is skipped from now on
  job.own = true;
  ++stats_.own_jobs;
  own_jobs_.push_back(JobAssignment{WorkerId{}, job_id, job.frame_id, job.tile, false, contested});
}

void Scheduler::quarantine(const WorkerId& id) {
  if (!quarantined_.insert(id).second) return;
  newly_quarantined_.push_back(id);
  ++stats_.quarantined;
  // Its unconfirmed results and votes elsewhere are not to be believed either.
  for (uint64_t job_id : referee_.disqualify(id)) requeue(job_id);
  remove_worker(id);  // its outstanding jobs go back; frames it blocked may decide now
}

std::optional<HashSplit> Scheduler::stalled_split() const {
  if (!referee_.may_stall()) return std::nullopt;
  std::vector<WorkerId> present;
  for (const auto& entry : workers_) present.push_back(entry.first);
  return referee_.stalled_split(present);
}

}  // namespace igi
