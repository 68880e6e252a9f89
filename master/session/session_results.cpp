// The session's results: a worker's checked against its job and pasted, its
// verdict taken from the scheduler (and its referee), failures counted
// against their workers, the master's own hashes and tiles taken in.
#include <cstdio>

#include "scene/libraries.h"
#include "session/master_session.h"
#include "trust/reports.h"

namespace igi {
namespace {

constexpr int kMaxFailedResults = 3;  // a peer whose results fail validation this often is quarantined
constexpr size_t kMaxQuarantinedNames = 1000;
constexpr uint64_t kLogFirst = 5;     // repeated conditions are logged this often, then counted

std::string describe(const TileJob& t) {
  char text[96];
  std::snprintf(text, sizeof text, "(%d, %d, %d x %d, border %d)", t.x, t.y, t.w, t.h, t.border);
  return text;
}

}  // namespace

// The job is looked up from the result's header before anything is
// unpacked: a result costs no more than its bytes until it is known to be
// for a job its peer holds, and then at most that job's tile.
void MasterSession::on_result(const std::string& identity, std::span<const uint8_t> bytes) {
  Peer* peer = peers_.find(identity);
  if (!peer) return on_bad_message(identity, "message from a peer that never said hello");
  Peers::heard(*peer, Clock::now());
  std::string error;
  const std::optional<protocol::TileResultHead> head = protocol::tile_result_head(bytes, error);
  if (!head) return on_bad_message(identity, error);
  const ResultCheck check = scheduler_.check_result(identity, head->job_id, head->frame_id, head->tile);
  switch (check) {
    case ResultCheck::Unknown:
      if (!scheduler_.was_given(identity, head->job_id)) return on_foreign_result(identity, *head);
      return on_stale_result(identity, *head, bytes);  // from before a reconnect, or a frame long done
    case ResultCheck::WrongTile:
      return on_bad_result(identity, head->job_id,
                           "frame " + std::to_string(head->frame_id) + ", tile " + describe(head->tile) +
                               " is not what job " + std::to_string(head->job_id) + " asked for");
    case ResultCheck::NotNeeded:
    case ResultCheck::Wanted:
      break;
  }
  std::optional<protocol::TileResultView> view = protocol::decode_tile_result(bytes, error);
  if (!view) return on_bad_result(identity, head->job_id, error);
  if (settings_.detailed_stats) Peers::note_round_trip(*peer, head->job_id);
  if (check == ResultCheck::NotNeeded) {  // another copy answered first: its hash still votes
    if (scheduler_.on_result(identity, head->job_id, view->fields.frame_state_hash, Clock::now()) !=
        ResultVerdict::Rejected)
      scheduler_.heard_result(identity);
    return;
  }
  use_result(identity, *peer, *view, bytes.size());
}

// A result for a job the peer was never given: no worker sends one. It cost
// a header's reading; three such (or failures) and the peer is quarantined.
void MasterSession::on_foreign_result(const std::string& identity, const protocol::TileResultHead& head) {
  ++bad_messages_;
  Peer* peer = peers_.find(identity);
  if (bad_messages_ <= 100 || bad_messages_ % 1000 == 0)
    log("dropped a bad message (" + std::to_string(bad_messages_) + " so far): " + peer->name +
        " sent a result for job " + std::to_string(head.job_id) + " (frame " + std::to_string(head.frame_id) +
        "), which it was never given");
  if (++peer->failed_results >= kMaxFailedResults)
    quarantine_peer(identity, std::to_string(peer->failed_results) +
                                  " of its messages were results for jobs it was never given, or failed validation");
}

// A result for a job the peer was given but holds no more (its frame is
// done or cancelled, or the job went to another): its credit comes back.
// A benched worker works again once such a result of its own passes.
void MasterSession::on_stale_result(const std::string& identity, const protocol::TileResultHead& head,
                                    std::span<const uint8_t> bytes) {
  scheduler_.drop_result(identity, head.job_id);
  if (!scheduler_.is_benched(identity) || head.tile.w > settings_.tile_size || head.tile.h > settings_.tile_size) return;
  std::string error;
  if (protocol::decode_tile_result(bytes, error)) scheduler_.heard_result(identity);
}

// The job's first result: its pixels go straight into the frame, then the
// scheduler decides whether they count (or are held for the frame's hash).
void MasterSession::use_result(const std::string& identity, Peer& peer, const protocol::TileResultView& view,
                               size_t bytes) {
  const protocol::TileResult& r = view.fields;
  if (std::string error = frames_.paste(view); !error.empty()) return on_bad_result(identity, r.job_id, error);
  const ResultVerdict verdict = scheduler_.on_result(identity, r.job_id, r.frame_state_hash, Clock::now());
  if (verdict == ResultVerdict::Accepted || verdict == ResultVerdict::Held) count_failures_against_workers(r.job_id);
  if (verdict != ResultVerdict::Rejected) scheduler_.heard_result(identity);  // it passed: a benched worker works again
  FrameAssembly::OpenFrame& frame = *frames_.find(r.frame_id);  // the scheduler knew the job, so its frame is open
  FrameAssembly::count(frame, r);
  if (r.nonfinite_pixels > 0) {
    nonfinite_pixels_ += r.nonfinite_pixels;
    if (++nonfinite_logged_ <= kLogFirst)
      log(peer.name + " rendered " + std::to_string(r.nonfinite_pixels) + " non-finite pixels in frame " +
          std::to_string(r.frame_id) + ", tile " + describe(r.tile) + ", and sent them as black");
  }
  if (settings_.detailed_stats) {
    PeerStats& stats = frame.record.workers[peer.name];
    ++stats.tiles;
    stats.busy_seconds += r.render_seconds;
    stats.bytes_in += bytes;
  }
  if (tile_sources_) frame.record.tile_sources.push_back({r.tile, peer.number});
  ++accepted_;
  if (on_accepted) on_accepted(accepted_);
}

// The job goes to another worker, or to the master's own renderer when every
// worker that could take it failed it (render_own_jobs()).
void MasterSession::on_bad_result(const std::string& identity, uint64_t job_id, const std::string& error) {
  const Peer& peer = *peers_.find(identity);
  if (++failures_logged_ <= kLogFirst)
    log(peer.name + " sent a result for job " + std::to_string(job_id) + " that fails validation (" + error +
        "): the job goes to another worker");
  job_failures_.add(job_id, identity, peer.name, error);
  scheduler_.on_bad_result(identity, job_id);
  if (scheduler_.answered(job_id)) count_failures_against_workers(job_id);  // a straggler copy passed first
}

// Another worker's result for the job passed: each worker that failed it
// was at fault, and one with three such results is quarantined.
void MasterSession::count_failures_against_workers(uint64_t job_id) {
  for (const std::string& identity : job_failures_.take_workers(job_id)) {
    Peer* peer = peers_.find(identity);
    if (peer && ++peer->failed_results >= kMaxFailedResults)
      quarantine_peer(identity, std::to_string(peer->failed_results) +
                                    " of its results failed validation where another worker's passed");
  }
}

void MasterSession::on_bad_message(const std::string& identity, const std::string& error) {
  ++bad_messages_;
  if (bad_messages_ <= 100 || bad_messages_ % 1000 == 0)
    log("dropped a bad message (" + std::to_string(bad_messages_) + " so far): " + error);
  // A peer that speaks another protocol version is told why, in our version.
  if (error.find("version") != std::string::npos) send(identity, protocol::Refuse{error});
  // A worker of this build never sends what does not decode: one that keeps doing so is broken.
  Peer* peer = peers_.find(identity);
  if (peer && ++peer->failed_results >= kMaxFailedResults)
    quarantine_peer(identity, std::to_string(peer->failed_results) + " of its messages failed to decode");
}

// ---- Peers that leave or lose.

void MasterSession::drop_peer(const std::string& identity, const std::string& why) {
  const Peer* peer = peers_.find(identity);
  if (!peer) return;
  peers_.log_join_or_leave(peer->name + " " + why);
  scheduler_.remove_worker(identity);
  peers_.drop(identity);
}

// Told why, so it exits with its own status; its later messages are ignored.
void MasterSession::quarantine_peer(const std::string& identity, const std::string& why) {
  const Peer* peer = peers_.find(identity);
  if (!peer) return;
  const std::string name = peer->name;
  const std::string key = peer->key_name;
  std::fprintf(stderr, "igi-master: %s quarantined: %s; it gets no more work%s\n", name.c_str(), why.c_str(),
               key.empty() ? "" : (", and its CURVE key '" + key + "' is refused from now on").c_str());
  send(identity, protocol::Bye{"quarantined by the master: " + why, protocol::ByeKind::Quarantined});
  scheduler_.remove_worker(identity);
  peers_.quarantine(identity);
  socket_.refuse_key(key);  // by key: a reconnection is a new connection, not a new worker
  ++quarantined_count_;
  if (quarantined_names_.size() < kMaxQuarantinedNames) quarantined_names_.push_back(name + ": " + why);
}

void MasterSession::take_quarantined() {
  const char* why = own_ ? "its VPL-set hash differs from the master's own for the frame "
                           "(another build, CPU, a fault, or a peer that does not render)"
                         : "its VPL-set hash differs from the one most of its frame's workers reported "
                           "(another build, CPU or a fault)";
  for (const WorkerId& id : scheduler_.take_quarantined()) quarantine_peer(id, why);
}

// ---- The master's own work (trust/own_renders.h).

void MasterSession::take_own_work() {
  if (!own_) return;
  for (const OwnRenders::Hash& h : own_->take_hashes()) scheduler_.set_reference(h.frame_id, h.hash);
  for (const MasterRenderer::TileAnswer& a : own_->take_tiles()) use_own_result(a);
}

// Jobs whose results failed on every worker that could take them: the master
// renders each as a worker would. Only when it cannot is the run over.
void MasterSession::render_own_jobs() {
  for (const JobAssignment& job : scheduler_.take_own_jobs()) {
    const FrameAssembly::OpenFrame* f = frames_.find(job.frame_id);
    if (!f) continue;
    const std::string what = "job " + std::to_string(job.job_id) + " (frame " + std::to_string(job.frame_id) +
                             ", tile " + describe(job.tile) + ") " +
                             (job.contested ? "is contested (its frame's VPL sets are in doubt)"
                                            : "failed validation on " + job_failures_.take_text(job.job_id, "its workers"));
    if (!own_ || own_->follows_workers()) {  // a master whose VPL sets lost to its workers' would render another tile
      if (fatal_.empty())
        fatal_ = what + ", no other worker may take it and the master cannot render it" +
                 (follows_workers() ? " as they would (its VPL sets differ from theirs)" : "") +
                 ": its frame can never complete";
      return;
    }
    own_->render_tile(f->setup, f->settings, job.job_id, job.tile, settings_.pixel_format, what, !job.contested);
  }
}

// The master's own tile is pasted as a worker's is; it counts whatever its
// frame's vote (the master is the judge).
void MasterSession::use_own_result(const MasterRenderer::TileAnswer& answer) {
  const std::string what = own_->take_what(answer.job_id);
  std::string error = answer.error;
  std::optional<protocol::TileResultView> view;
  if (error.empty()) view = protocol::decode_tile_result(answer.result, error);
  FrameAssembly::OpenFrame* frame = view ? frames_.find(view->fields.frame_id) : nullptr;
  if (view && !frame) return;  // the view moved on meanwhile
  if (!scheduler_.wants_own_result(answer.job_id)) return;  // the master follows its workers now: theirs, not its own
  if (view) error = frames_.paste(*view);
  if (!error.empty()) {
    if (fatal_.empty()) fatal_ = what + ", and the master could not render it either (" + error + ")";
    return;
  }
  if (!scheduler_.on_own_result(answer.job_id)) return;
  ++own_tiles_;
  FrameAssembly::count(*frame, view->fields);
  nonfinite_pixels_ += view->fields.nonfinite_pixels;
}

// Every worker present agrees on a frame's VPL sets, from two or more
// authenticated keys (the referee disputes nothing else), and the master's
// own differ: the master is likelier wrong than they (a maths library 1 ulp
// off, which no version names, is enough). It follows them, and says so
// once (the frames disputed with this one are decided by the same step).
void MasterSession::on_dispute(const HashDispute& d) {
  if (own_ && own_->follows_workers()) return;
  std::vector<VoterName> workers;
  for (const WorkerId& id : d.workers) {
    const Peer* peer = peers_.find(id);
    workers.push_back(peer ? VoterName{peer->name, peer->libraries} : VoterName{"a departed worker", ""});
  }
  const std::string what = dispute_report(d, workers, runtime_libraries());
  std::fprintf(stderr, "igi-master: %s. The workers are authenticated by their CURVE keys: the master follows their "
                       "agreement from now on (votes among them decide each frame)\n", what.c_str());
  if (own_) own_->follow_workers();
  scheduler_.follow_workers();
}

// No worker confirms the master's hash and the votes cannot outweigh it: the
// master renders what they contest (take_own_work()), saying so for the
// first frames and every 100th after.
void MasterSession::on_doubt(const HashDoubt& d) {
  if (++doubts_logged_ > kLogFirst && doubts_logged_ % 100 != 0) return;
  std::vector<std::string> names;
  for (const auto& [hash, voters] : d.voters)
    for (const WorkerId& id : voters) {
      const Peer* peer = peers_.find(id);
      names.push_back(peer ? peer->name : "a departed worker");
    }
  std::fprintf(stderr, "igi-master: %s (%llu frames so far)\n", doubt_report(d, names).c_str(),
               static_cast<unsigned long long>(doubts_logged_));
}

}  // namespace igi
