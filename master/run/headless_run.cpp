// Headless: frames along the camera path, written by a FrameSink, statistics by a StatsWriter.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <optional>

#include "view/frame_plan.h"
#include "output/frame_sink.h"
#include "image/exposure_check.h"
#include "scene/builtin_scenes.h"
#include "output/frame_stats.h"
#include "run/run_modes.h"
#include "output/stats_writer.h"

namespace igi {
namespace {

using Clock = std::chrono::steady_clock;
constexpr size_t kMaxBacklog = 3;  // frames waiting for the sink before the session stops adding more
constexpr auto kNoWorkerLimit = std::chrono::seconds(60);
constexpr int kHashesAhead = 2;  // frames whose hashes the master computes before it adds them

std::string frame_path(const std::string& output, int frame, int frames, int first) {
  if (frames <= 1 && first == 0) return output;
  std::filesystem::path p(output);
  char suffix[16];
  std::snprintf(suffix, sizeof suffix, "-%04d", frame);
  return (p.parent_path() / (p.stem().string() + suffix + p.extension().string())).string();
}

// Why the run cannot go on without workers: none for a minute; the last
// worker failed (saying why) and none came for 10 s after it; or a tie
// nobody breaks for a minute. While none is there it says so every 5 s.
class Watchdog {
 public:
  // Empty while progress is possible.
  std::string check(const MasterSession& session, bool quiet) {
    const auto now = Clock::now();
    if (session.worker_count() > 0) no_worker_since_ = next_notice_ = now;
    const std::string stall = session.stall();
    if (stall.empty()) stall_since_ = now;
    const std::string& failure = session.last_worker_failure();
    // The last worker to leave failed (the failure came after the last check that saw a worker).
    if (session.worker_count() == 0 && !failure.empty() && session.last_worker_failure_time() >= no_worker_since_ &&
        now - session.last_worker_failure_time() > kFailedGrace)
      return "the workers failed and none came for 10 s; the last: " + failure;
    if (now - no_worker_since_ > kNoWorkerLimit)
      return "no worker for 60 s; start some with igi-worker --connect " + session.endpoint();
    if (now - stall_since_ > kNoWorkerLimit) return stall + " (60 s without another worker)";
    if (session.worker_count() == 0 && now - next_notice_ > kNotice) {
      next_notice_ = now;
      if (!quiet)
        std::fprintf(stderr, "igi-master: waiting for workers (none for %.0f s): start one with igi-worker --connect %s\n",
                     std::chrono::duration<double>(now - no_worker_since_).count(), session.endpoint().c_str());
    }
    return {};
  }

 private:
  static constexpr auto kFailedGrace = std::chrono::seconds(10);
  static constexpr auto kNotice = std::chrono::seconds(5);
  Clock::time_point no_worker_since_ = Clock::now(), stall_since_ = Clock::now(), next_notice_ = Clock::now();
};

// --min-workers: a cluster's render starts when all of it is there, not with
// whichever worker dialled back first; a host that never comes costs at most
// --min-workers-wait seconds.
bool workers_gathered(const MasterOptions& o, const MasterSession& session, Clock::time_point since) {
  const size_t joined = session.worker_count();
  if (joined >= size_t(o.min_workers)) return true;
  if (Clock::now() - since < std::chrono::seconds(o.min_workers_wait)) return false;
  std::fprintf(stderr, "igi-master: only %zu of %d workers joined in %d s: starting with them\n", joined,
               o.min_workers, o.min_workers_wait);
  return true;
}

// One headless run: queues frames along the camera path, pumps the session,
// hands completed frames to the sink (which accumulates and writes them) and
// their records to the statistics, and stops when every frame is done, on an
// interrupt, or when the watchdog sees that no progress is possible.
class HeadlessRun {
 public:
  HeadlessRun(const MasterOptions& o, const Scene& scene, MasterSession& session)
      : o_(o), scene_(scene), session_(session), replay_(o.progressive ? o.first_frame : 0),
        total_(replay_ + o.frames), first_index_(o.first_frame - replay_), gathered_(o.min_workers == 0),
        sink_(o.render.width, o.render.height, o.render.exposure, o.render.view, o.progressive) {
    if (!o.stats.empty()) stats_.emplace(o.stats);
  }

  // Returns the exit status: 0 when every frame was written.
  int run(LocalWorkers& workers, const std::atomic<bool>& interrupted) {
    announce_replay();
    std::string failure;
    try {
      while (done_ < total_ && !interrupted) {
        queue_frames();
        pump();
        flush_stats_when_due();
        if (failure = watchdog_.check(session_, o_.render.quiet); !failure.empty()) break;
      }
    } catch (const SessionError& e) {
      failure = e.what();
    }
    return finish(workers, failure);
  }

 private:
  // --first-frame with --progressive: the sum of the frames before it is rebuilt (rendered again, not written).
  void announce_replay() const {
    if (replay_ > 0)
      std::fprintf(stderr, "igi-master: --first-frame %d with --progressive: rendering frames 0-%d again (not "
                   "written) to rebuild the accumulated image\n", o_.first_frame, o_.first_frame - 1);
  }

  // Once the workers have gathered: frames up to what the session and the sink's backlog take.
  void queue_frames() {
    gathered_ = gathered_ || workers_gathered(o_, session_, wall_start_);
    while (gathered_ && next_ < total_ && session_.can_add_frame() && sink_.backlog() < kMaxBacklog)
      session_.add_frame(plan_frame(o_.render, o_.camera_path, scene_, first_index_ + next_++, o_.progressive));
    // The master's own VPL-set hashes of the next frames, computed while these render; each planned once.
    for (expected_ = std::max(expected_, next_); expected_ < std::min(total_, next_ + kHashesAhead); ++expected_)
      session_.expect_frame(plan_frame(o_.render, o_.camera_path, scene_, first_index_ + expected_, o_.progressive));
  }

  void pump() {
    for (CompletedFrame& f : session_.pump(50)) take_completed(f);
  }

  // A completed frame, in order: to the sink (accumulated, and written unless it is replayed or
  // --no-write), a line on stdout, its record to the statistics.
  void take_completed(CompletedFrame& f) {
    const int index = first_index_ + done_;
    const bool written = done_ >= replay_ && !o_.no_write;
    if (written || o_.progressive)
      sink_.push(std::move(f.pixels), written ? frame_path(o_.render.output, index, o_.frames, o_.first_frame) : "");
    if (!o_.render.quiet && done_ >= replay_)
      std::printf("frame %d: %.1f ms, %.1f Mrays/s, %zu workers\n", index, 1e3 * f.record.seconds,
                  f.record.seconds > 0 ? f.record.rays.total() * 1e-6 / f.record.seconds : 0.0,
                  session_.worker_count());
    std::fflush(stdout);  // a line per frame as it completes, for whoever follows the log
    if (stats_) stats_->add(f.record);
    ++done_;
  }

  // The run's totals so far, so a master that is killed leaves them: once a
  // second (the writer appends the frames' records by count and time itself).
  void flush_stats_when_due() {
    if (!stats_ || Clock::now() - last_flush_ < StatsWriter::kFlushInterval) return;
    stats_->write(totals_now());
    last_flush_ = Clock::now();
  }

  RunTotals totals_now() const {
    return run_totals(session_, o_.io_threads, cpu_start_,
                      std::chrono::duration<double>(Clock::now() - wall_start_).count());
  }

  void print_summary() const {
    const SchedulerStats& s = session_.scheduler_stats();
    std::fprintf(stderr, "igi-master: %d frames; tiles copied %llu, reissued %llu, verification copies %llu, "
                 "results failing validation %llu, tiles the master rendered %llu, hoarders benched %llu, "
                 "workers quarantined %llu, declared dead %llu, non-finite pixels %llu\n", done_,
                 (unsigned long long)s.duplicated, (unsigned long long)s.reissued, (unsigned long long)s.verified,
                 (unsigned long long)s.failed_results, (unsigned long long)session_.own_tiles(),
                 (unsigned long long)session_.benched(),
                 (unsigned long long)session_.quarantined_count(), (unsigned long long)session_.declared_dead(),
                 (unsigned long long)session_.nonfinite_pixels());
  }

  // An image all black, nearly black or mostly white: said, with the option
  // that fixes it; or, metered, the exposure of the last image written.
  void say_how_exposed() const {
    const std::optional<Image> last = sink_.last_written();
    if (!last) return;
    if (o_.render.exposure.metered && !is_float_format(o_.render.output))
      std::fprintf(stderr, "igi-master: exposure metered: %+.2f EV (the last image written)\n",
                   std::log2(sink_.last_exposure()));
    const bool file_lamps = !is_builtin_scene(o_.render.scene) && !scene_.lights.empty();
    if (auto advice = exposure_advice(*last, {sink_.last_exposure(), o_.render.exposure.metered, o_.render.view,
                                             !is_float_format(o_.render.output), file_lamps,
                                             o_.render.light_units == LightUnits::Photometric,
                                             !scene_.camera}))
      std::fprintf(stderr, "igi-master: %s\n", advice->c_str());
  }

  // Closes the session and the workers, waits for the last images, writes the final statistics.
  int finish(LocalWorkers& workers, const std::string& failure) {
    RunTotals totals = totals_now();
    totals.complete = true;
    totals.outcome = done_ == total_ ? "done" : failure.empty() ? "interrupted" : "failed";
    if (!o_.render.quiet) print_summary();
    session_.close(done_ == total_ ? "done" : failure.empty() ? "interrupted" : "failed");
    workers.stop_all();
    sink_.finish();  // waits for the last images
    const std::string write_error = sink_.error();
    if (!o_.render.quiet) say_how_exposed();
    if (stats_) stats_->write_final(totals);
    if (!failure.empty()) throw std::runtime_error(failure);
    if (!write_error.empty()) throw std::runtime_error(write_error);
    return done_ == total_ ? 0 : 1;
  }

  const MasterOptions& o_;
  const Scene& scene_;
  MasterSession& session_;
  const int replay_, total_, first_index_;
  bool gathered_;
  FrameSink sink_;
  std::optional<StatsWriter> stats_;
  int next_ = 0, done_ = 0;
  int expected_ = 0;  // frames below this were given to expect_frame() (or added)
  const Clock::time_point wall_start_ = Clock::now();
  const double cpu_start_ = process_cpu_seconds();
  Clock::time_point last_flush_ = wall_start_;
  Watchdog watchdog_;
};

}  // namespace

int run_headless(const MasterOptions& o, const Scene& scene, MasterSession& session, LocalWorkers& workers,
                 const std::atomic<bool>& interrupted) {
  return HeadlessRun(o, scene, session).run(workers, interrupted);
}

}  // namespace igi
