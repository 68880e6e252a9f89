#include "loadgen_options.h"

#include <CLI/CLI.hpp>
#include <climits>
#include <cstdint>
#include <random>

#include "cli/option_checks.h"
#include "options/liveness_options.h"
#include "protocol/messages.h"

namespace igi::loadgen {
namespace {

using cli::integer;
constexpr int kMaxWorkers = 65536, kMaxFrames = 10000000, kMaxPools = 256;

const char* kAbout =
    "igi-loadgen: runs igi-master with --workers 0 and simulated workers over real ZeroMQ sockets, each\n"
    "answering its jobs with pre-rendered tiles, and measures the master from outside.";

void add_load_options(CLI::App& app, LoadgenOptions& o) {
  app.add_option("--workers", o.workers, "simulated workers [8]")->check(integer(1, kMaxWorkers))->type_name("N");
  cli::add_size_option(app, "--size", o.width, o.height, protocol::kMaxImageSide, "frame size [640x480]");
  app.add_option("--tile", o.tile, "tile side [32]")->check(integer(1, protocol::kMaxTileSide))->type_name("T");
  app.add_option("--pixels", o.pixels, "the master's --pixels: half, float or rgb9e5 [half]")
      ->check(cli::one_of({"half", "float", "rgb9e5"}));
  app.add_option("--pixel-codec", o.pixel_codec, "the master's --pixel-codec: raw, zstd or lz4 [raw]")
      ->check(cli::one_of({"raw", "zstd", "lz4"}));
  app.add_option("--picture", o.picture, "the simulated tiles' pixels: this image's (a frame rendered at --size, "
                 "e.g. by igi-render -o F.exr), not a gradient that flatters any codec")
      ->check(CLI::ExistingFile)->type_name("FILE");
  app.add_option("--frames", o.frames, "[300]")->check(integer(1, kMaxFrames))->type_name("F");
  app.add_option("--warmup", o.warmup_frames, "[10]")->check(integer(0, kMaxFrames))->type_name("F");
  app.add_option("--fps", o.fps, "pace the workers for F frames a second [30]")
      ->check(cli::non_negative_number())->type_name("F");
  app.add_option("--tile-ms", o.tile_ms, "render time per tile instead (0: answer at once, flat out)")
      ->check(cli::non_negative_number())->type_name("MS");
  app.add_option("--threads", o.threads, "tiles a simulated worker renders at once [1]")
      ->check(integer(1, cli::kMaxThreads))->type_name("T");
  app.add_option("--pools", o.pools, "threads driving the simulated workers [2]")
      ->check(integer(1, kMaxPools))->type_name("P");
  app.add_option("--io-threads", o.io_threads, "the master's ZeroMQ I/O threads [1]")
      ->check(integer(1, cli::kMaxIoThreads))->type_name("N");
  app.add_option("--endpoint", o.endpoint, "the master listens here and the workers connect here [loopback, a free "
                 "port]; off loopback the master needs --master-arg --key and --authorized-keys, the workers --key "
                 "and --master-key")->type_name("tcp://HOST:PORT");
  app.add_option("--key", o.worker_key, "CURVE: the simulated workers' secret key (igi-keys new NAME)")
      ->check(CLI::ExistingFile)->type_name("WORKER.key");
  app.add_option("--master-key", o.master_public_key, "CURVE: the master's public key")
      ->check(CLI::ExistingFile)->type_name("MASTER.pub");
  add_liveness_options(app, o.heartbeat_ms, o.timeout_ms);
}

void add_fault_and_check_options(CLI::App& app, CommandLine& c) {
  app.add_flag("--write-frames", c.run.write_frames, "the master writes EXR frames (check them with --check-every N)");
  app.add_option("--check-every", c.check_every, "check every N-th frame pixel by pixel against the simulated tiles")
      ->check(integer(0, kMaxFrames))->type_name("N");
  app.add_flag("--stats", c.run.stats, "the master writes stats.json");
  app.add_option("--churn", c.churn_seed, "faults on a seeded schedule: a tenth of the workers join late, a tenth "
                 "stall past the master's timeout, a tenth die and are replaced")
      ->check(integer<uint64_t>(0, UINT64_MAX))->type_name("SEED");
  app.add_option("--hoarders", c.hoarders, "the last N workers take jobs, heartbeat and never answer")
      ->check(integer(0, kMaxWorkers))->type_name("N");
  app.add_option("--diverging", c.diverging, "the first N workers report another VPL-set hash")
      ->check(integer(0, kMaxWorkers))->type_name("N");
  app.add_option("--nan-every", c.nan_every, "worker 0 sends a NaN pixel in every N-th tile")
      ->check(integer(0, INT_MAX))->type_name("N");
  app.add_option("--wrong-tile-every", c.wrong_tile_every, "worker 0 claims another tile's rectangle in every N-th "
                 "answer")->check(integer(0, INT_MAX))->type_name("N");
  app.add_option("--flood", c.flood, "one more worker, which also sends N results a second for jobs never issued, "
                 "each under 1 KB that unpacks to a 1024 x 1024 float tile with surfaces")
      ->check(integer(0, 100000))->type_name("N");
}

void add_output_options(CLI::App& app, CommandLine& c) {
  app.add_option("--master", c.run.master_binary, "igi-master [next to this program's build tree]")
      ->type_name("PATH");
  app.add_option("--master-arg", c.run.master_args, "one more argument for the master (repeatable)")
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll)->type_name("ARG");
  app.add_option("--dir", c.run.dir, "logs and frames [loadgen-run]")->type_name("DIR");
  app.add_option("--deadline", c.run.deadline_seconds, "[120]")->check(cli::non_negative_number())->type_name("S");
  app.add_option("--csv", c.csv, "append the figures as a row")->type_name("FILE");
  app.add_option("--label", c.label, "its first column")->type_name("TEXT");
}

void declare(CLI::App& app, CommandLine& c) {
  add_load_options(app, c.run);
  add_fault_and_check_options(app, c);
  add_output_options(app, c);
}

// "--master-arg --credits": the master's argument looks like an option of ours, so it is joined to its name.
std::vector<std::string> joined_master_args(const std::vector<std::string>& args) {
  std::vector<std::string> joined;
  for (size_t i = 0; i < args.size(); ++i)
    if (args[i] == "--master-arg" && i + 1 < args.size()) joined.push_back("--master-arg=" + args[++i]);
    else joined.push_back(args[i]);
  return joined;
}

}  // namespace

std::string usage() { return cli::help<CommandLine>(kAbout, "igi-loadgen", declare); }

CommandLine parse_command_line(const std::vector<std::string>& args) {
  CommandLine c;
  c.help = !cli::parse_into(c, declare, joined_master_args(args));
  if (c.help) return c;
  check_liveness(c.run.heartbeat_ms, c.run.timeout_ms);
  if (c.check_every > 0 && !c.run.write_frames) throw cli::OptionError("--check-every needs --write-frames");
  if (c.run.worker_key.empty() != c.run.master_public_key.empty())
    throw cli::OptionError("CURVE needs both --key WORKER.key and --master-key MASTER.pub");
  if ((c.nan_every > 0) && (c.run.pixels == "rgb9e5" || c.run.pixel_codec != "raw"))
    throw cli::OptionError("--nan-every writes a NaN into raw half or float pixels: not with --pixels rgb9e5 (no "
                           "NaN there) or a packing --pixel-codec");
  return c;
}

// The churn schedule: over the run's expected length, a tenth of the workers
// each join late, stall for 1.2 timeouts, or die and are replaced 0.5 s later.
std::vector<SimBehaviour> behaviours(const CommandLine& c) {
  const LoadgenOptions& o = c.run;
  SimBehaviour base;
  base.tile_seconds = paced_tile_seconds(o);
  base.threads = o.threads;
  std::vector<SimBehaviour> all(size_t(o.workers), base);
  for (int i = 0; i < std::min(c.diverging, o.workers); ++i) all[size_t(i)].hash_offset = 1;
  for (int i = 0; i < std::min(c.hoarders, o.workers); ++i) all[all.size() - 1 - size_t(i)].hoard = true;
  all[0].nan_every = c.nan_every;
  all[0].wrong_tile_every = c.wrong_tile_every;
  if (c.flood > 0) {
    all.push_back(base);
    all.back().flood_per_second = c.flood;
  }
  if (c.churn_seed == 0) return all;
  std::mt19937_64 rng(c.churn_seed);
  const double length = o.fps > 0 ? o.frames / o.fps : 10.0;
  std::uniform_real_distribution<double> early(0.0, 0.5 * length), middle(0.25 * length, 0.75 * length);
  const double stall = 1.2 * o.timeout_ms * 1e-3;
  for (size_t i = size_t(c.diverging); i < all.size(); ++i) {
    switch (rng() % 10) {
      case 0: all[i].join_at = early(rng); break;
      case 1: all[i].stall_from = middle(rng), all[i].stall_until = all[i].stall_from + stall; break;
      case 2: all[i].die_at = middle(rng), all[i].rejoin_after = 0.5; break;
      default: break;
    }
  }
  return all;
}

}  // namespace igi::loadgen
