// Headless: frames along the camera path, written by a FrameSink, statistics by a StatsWriter.
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <optional>

#include "frame_plan.h"
#include "frame_sink.h"
#include "frame_stats.h"
#include "run_modes.h"
#include "stats_writer.h"

namespace igi {
namespace {

using Clock = std::chrono::steady_clock;
constexpr size_t kMaxBacklog = 3;  // frames waiting for the sink before the session stops adding more
constexpr auto kNoWorkerLimit = std::chrono::seconds(60);

std::string frame_path(const std::string& output, int frame, int frames, int first) {
  if (frames <= 1 && first == 0) return output;
  std::filesystem::path p(output);
  char suffix[16];
  std::snprintf(suffix, sizeof suffix, "-%04d", frame);
  return (p.parent_path() / (p.stem().string() + suffix + p.extension().string())).string();
}

// Why the run cannot go on without workers: none for a minute, or a tie nobody breaks for a minute.
class Watchdog {
 public:
  // Empty while progress is possible.
  std::string check(const MasterSession& session) {
    const auto now = Clock::now();
    if (session.worker_count() > 0) no_worker_since_ = now;
    const std::string stall = session.stall();
    if (stall.empty()) stall_since_ = now;
    if (now - no_worker_since_ > kNoWorkerLimit)
      return "no worker for 60 s; start some with igi-worker --connect " + session.endpoint();
    if (now - stall_since_ > kNoWorkerLimit) return stall + " (60 s without another worker)";
    return {};
  }

 private:
  Clock::time_point no_worker_since_ = Clock::now(), stall_since_ = Clock::now();
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

}  // namespace

int run_headless(const MasterOptions& o, const Scene& scene, MasterSession& session, LocalWorkers& workers,
                 const std::atomic<bool>& interrupted) {
  // --first-frame with --progressive: the sum of the frames before it is rebuilt (rendered again, not written).
  const int replay = o.progressive ? o.first_frame : 0;
  if (replay > 0)
    std::fprintf(stderr, "igi-master: --first-frame %d with --progressive: rendering frames 0-%d again (not written) "
                 "to rebuild the accumulated image\n", o.first_frame, o.first_frame - 1);
  const int total = replay + o.frames, first_index = o.first_frame - replay;
  std::optional<FrameSink> sink(std::in_place, o.render.width, o.render.height, o.render.exposure, o.progressive);
  std::optional<StatsWriter> stats;
  if (!o.stats.empty()) stats.emplace(o.stats);
  int next = 0, done = 0;
  const auto wall_start = Clock::now();
  const double cpu_start = process_cpu_seconds();
  auto totals_now = [&] {
    return run_totals(session, o.io_threads, cpu_start, std::chrono::duration<double>(Clock::now() - wall_start).count());
  };
  // The statistics so far, so a master that is killed leaves them: once a
  // second, and a second more per 1000 frames (each rewrite holds every frame).
  auto last_flush = wall_start;
  Watchdog watchdog;
  std::string failure;
  bool gathered = o.min_workers == 0;
  try {
    while (done < total && !interrupted) {
      gathered = gathered || workers_gathered(o, session, wall_start);
      while (gathered && next < total && session.can_add_frame() && sink->backlog() < kMaxBacklog)
        session.add_frame(plan_frame(o.render, o.camera_path, scene, first_index + next++, o.progressive));
      for (CompletedFrame& f : session.pump(50)) {
        const int index = first_index + done;
        const bool written = done >= replay && !o.no_write;
        if (written || o.progressive)
          sink->push(std::move(f.pixels), written ? frame_path(o.render.output, index, o.frames, o.first_frame) : "");
        if (!o.render.quiet && done >= replay)
          std::printf("frame %d: %.1f ms, %.1f Mrays/s, %zu workers\n", index, 1e3 * f.record.seconds,
                      f.record.seconds > 0 ? f.record.rays.total() * 1e-6 / f.record.seconds : 0.0,
                      session.worker_count());
        std::fflush(stdout);  // a line per frame as it completes, for whoever follows the log
        if (stats) stats->add(f.record);
        ++done;
      }
      if (stats && Clock::now() - last_flush > std::chrono::seconds(1 + done / 1000)) {
        stats->write(totals_now());
        last_flush = Clock::now();
      }
      if (failure = watchdog.check(session); !failure.empty()) break;
    }
  } catch (const SessionError& e) {
    failure = e.what();
  }
  RunTotals totals = totals_now();
  totals.complete = true;
  if (!o.render.quiet) {
    const SchedulerStats& s = session.scheduler_stats();
    std::fprintf(stderr, "igi-master: %d frames; tiles copied %llu, reissued %llu, verification copies %llu, "
                 "results failing validation %llu, workers quarantined %llu, non-finite pixels %llu\n", done,
                 (unsigned long long)s.duplicated, (unsigned long long)s.reissued, (unsigned long long)s.verified,
                 (unsigned long long)s.failed_results, (unsigned long long)s.quarantined,
                 (unsigned long long)session.nonfinite_pixels());
  }
  session.close(done == total ? "done" : failure.empty() ? "interrupted" : "failed");
  workers.stop_all();
  sink->finish();  // waits for the last images
  const std::string write_error = sink->error();
  if (stats) stats->write_final(totals);
  if (!failure.empty()) throw std::runtime_error(failure);
  if (!write_error.empty()) throw std::runtime_error(write_error);
  return done == total ? 0 : 1;
}

}  // namespace igi
