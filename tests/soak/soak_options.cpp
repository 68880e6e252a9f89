#include "soak_options.h"

#include <CLI/CLI.hpp>
#include <cstdint>

#include "cli/option_checks.h"
#include "options/liveness_options.h"
#include "protocol/messages.h"

namespace igi::soak {
namespace {

using cli::integer;
using cli::non_negative_number;

constexpr int kMaxFrames = 1000000;
constexpr int kMaxWorkers = 256;

const char* kAbout =
    "igi-soak: runs igi-master and igi-worker processes on loopback for a number of frames while injecting\n"
    "faults from a seeded schedule, then checks every frame bit for bit against the single-process\n"
    "render and the master's memory for growth. Exit 0 only when nothing was lost, nothing differs\n"
    "and memory stayed bounded.";

void add_run_options(CLI::App& app, SoakOptions& o) {
  app.add_option("--frames", o.frames, "frames to render [300]")->check(integer(2, kMaxFrames))->type_name("N");
  cli::add_size_option(app, "--size", o.width, o.height, protocol::kMaxImageSide, "[128x96]");
  app.add_option("--render-args", o.render_args, "scene, method and settings, as igi-render takes them "
                 "[--scene cornell --method igi --vpl-paths 16 --clamp 0.05 --tile 16]")->type_name("\"...\"");
  app.add_option("--workers", o.workers, "loopback workers [3]")->check(integer(1, kMaxWorkers))->type_name("K");
  add_liveness_options(app, o.heartbeat_ms, o.timeout_ms);
  app.add_option("--deadline", o.deadline_seconds, "give up (and fail) after S seconds; 0 = 30 + 0.6 x frames [0]")
      ->check(non_negative_number())->type_name("S");
  app.add_option("--dir", o.dir, "working folder, emptied first [soak-run]")->type_name("DIR");
  app.add_option("--master", o.master_binary, "igi-master [next to igi-soak]")->type_name("PATH");
  app.add_option("--worker", o.worker_binary, "igi-worker [next to igi-soak]")->type_name("PATH");
}

void add_fault_options(CLI::App& app, SoakOptions& o) {
  app.add_option("--seed", o.seed, "fault schedule seed; 0 = from the clock [0]")
      ->check(integer<uint64_t>(0, UINT64_MAX))->type_name("S");
  app.add_option("--faults", o.faults, "faults to inject; 0 = one per 10 frames [0]")
      ->check(integer(0, kMaxFrames))->type_name("F");
  app.add_option("--kinds", o.kinds, "of kill,stop,slow,garbage,restart,cut,hostile [all]")->type_name("LIST");
  app.add_option("--netns", o.netns, "also run a worker in a network namespace behind a veth link that is cut and "
                 "restored; auto skips (and says why) where the machine does not allow it [auto]")
      ->check(cli::one_of({"auto", "on", "off"}))->type_name("auto|on|off");
  app.add_flag("--real-oversized", o.real_oversized, "also send one real 512 MB + 64 KB + 1 message (the limit is "
               "checked on the header)");
}

void add_check_options(CLI::App& app, SoakOptions& o) {
  app.add_option("--rss-margin", o.rss_margin_mib, "allowed growth of the master's median RSS, first half to second "
                 "half, MiB [2]")->check(non_negative_number())->type_name("MIB");
  app.add_option_function<std::string>(
      "--memory-check", [&o](const std::string& v) { o.memory_check = v != "off"; },
      "off: report the master's memory but do not judge it (sanitizer builds keep freed memory in quarantine, so "
      "their RSS grows without a leak)")->type_name("off");
  app.add_option("--corrupt-frame", o.corrupt_frame, "self-test: alter frame I's file by one ulp before the check "
                 "(the run must fail)")->check(integer(0, kMaxFrames))->type_name("I");
  app.add_option("--delete-frame", o.delete_frame, "self-test: delete frame I's file before the check (the run "
                 "must fail)")->check(integer(0, kMaxFrames))->type_name("I");
}

void declare(CLI::App& app, SoakOptions& o) {
  add_run_options(app, o);
  add_fault_options(app, o);
  add_check_options(app, o);
}

}  // namespace

std::string soak_usage() { return cli::help<SoakOptions>(kAbout, "igi-soak", declare); }

SoakOptions parse_soak_options(const std::vector<std::string>& args) {
  SoakOptions o;
  o.help = !cli::parse_into(o, declare, args);
  if (!o.help) check_liveness(o.heartbeat_ms, o.timeout_ms);
  if (o.faults == 0) o.faults = o.frames / 10;
  if (o.deadline_seconds == 0) o.deadline_seconds = 30.0 + 0.6 * o.frames;
  return o;
}

}  // namespace igi::soak
