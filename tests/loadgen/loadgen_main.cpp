// igi-loadgen: the master under the load of many simulated workers (see loadgen_run.h).
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>

#include "cli/option_checks.h"
#include "loadgen_options.h"

namespace {

void append_csv(const std::string& path, const igi::loadgen::CommandLine& c, const igi::loadgen::LoadgenReport& r) {
  const bool fresh = !std::filesystem::exists(path);
  std::ofstream out(path, std::ios::app);
  if (fresh)
    out << "label,workers,width,height,tile,pixels,io_threads,frames,tile_ms,fps,tiles_per_s,cpu_us_per_tile,"
           "session_us_per_tile,cores,latency_median_ms,latency_p95_ms,rss_first_mib,rss_second_mib,rss_peak_mib,"
           "exit_code,quarantined,duplicated,reissued\n";
  const auto& o = c.run;
  out << c.label << "," << o.workers << "," << o.width << "," << o.height << "," << o.tile << "," << o.pixels << ","
      << o.io_threads << "," << r.frames_done << "," << 1e3 * r.tile_seconds << "," << r.fps << "," << r.tiles_per_second
      << "," << r.cpu_us_per_tile << "," << r.session_us_per_tile << "," << r.cores << "," << r.latency_median_ms << ","
      << r.latency_p95_ms << "," << r.rss_first_mib << "," << r.rss_second_mib << "," << r.rss_peak_mib << ","
      << r.exit_code << "," << r.quarantined_workers() << "," << r.duplicated << "," << r.reissued << "\n";
}

}  // namespace

int main(int argc, char** argv) {
  return igi::cli::run_program("igi-loadgen", 2, 2, [&] {
    igi::loadgen::CommandLine c = igi::loadgen::parse_command_line({argv + 1, argv + argc});
    if (c.help) { std::cout << igi::loadgen::usage(); return 0; }
    if (c.run.master_binary.empty()) c.run.master_binary = IGI_MASTER_BINARY;
    const igi::loadgen::LoadgenReport r = igi::loadgen::run_loadgen(c.run, igi::loadgen::behaviours(c));
    std::printf("%s%d workers, %dx%d, %d-pixel tiles (%d a frame), %s pixels: %d/%d frames, exit %d\n",
                c.label.empty() ? "" : (c.label + ": ").c_str(), c.run.workers, c.run.width, c.run.height, c.run.tile,
                r.tiles_per_frame, c.run.pixels.c_str(), r.frames_done, c.run.frames, r.exit_code);
    std::printf("  %.1f fps, %.0f tiles/s (simulated render %.3f ms a tile); master %.2f cores, %.1f us CPU a tile "
                "(session thread %.1f us); latency median %.1f ms, p95 %.1f ms\n",
                r.fps, r.tiles_per_second, 1e3 * r.tile_seconds, r.cores, r.cpu_us_per_tile, r.session_us_per_tile,
                r.latency_median_ms, r.latency_p95_ms);
    std::printf("  master RSS: median %.1f MiB (first half) -> %.1f MiB (second half), peak %.1f MiB; "
                "%d of %d workers welcomed, %d quarantined\n",
                r.rss_first_mib, r.rss_second_mib, r.rss_peak_mib, r.welcomed_workers(), int(r.workers.size()),
                r.quarantined_workers());
    if (r.duplicated >= 0)
      std::printf("  tiles copied (stragglers): %ld, reissued: %ld, verification copies: %ld\n", r.duplicated,
                  r.reissued, r.verified);
    int status = r.exit_code == 0 && r.frames_done == c.run.frames ? 0 : 1;
    if (c.flood > 0) {
      const igi::loadgen::SimOutcome& f = r.workers.back();
      if (f.quarantined_at < 0 || f.quarantined_at - f.first_flood_at > 1.0) status = 1;
      std::printf("  flood: %llu results for jobs never issued, from %.2f s; the flooder %s\n",
                  static_cast<unsigned long long>(f.flooded), f.first_flood_at,
                  f.quarantined_at < 0 ? "was not quarantined"
                                       : ("was quarantined " + std::to_string(f.quarantined_at - f.first_flood_at) +
                                          " s after its first").c_str());
    }
    if (status != 0) std::printf("master log (end):\n%s\n", r.master_log.c_str());
    // Exactly the diverging workers are quarantined: no correct one, none that diverges left in.
    for (size_t i = 0; i < size_t(c.run.workers); ++i) {
      const bool diverging = int(i) < c.diverging;
      if (r.workers[i].quarantined != diverging && r.workers[i].welcomed) {
        std::printf("  FAIL: worker %zu (%s) was%s quarantined\n", i, diverging ? "diverging" : "correct",
                    r.workers[i].quarantined ? "" : " not");
        status = 1;
      }
    }
    if (c.check_every > 0) {
      const std::vector<std::string> problems = igi::loadgen::check_written_frames(c.run, c.check_every);
      for (const std::string& p : problems) std::printf("  FAIL: %s\n", p.c_str());
      if (!problems.empty()) status = 1;
      else std::printf("  every %d-th frame checked: exact\n", c.check_every);
    }
    if (!c.csv.empty()) append_csv(c.csv, c, r);
    return status;
  });
}
