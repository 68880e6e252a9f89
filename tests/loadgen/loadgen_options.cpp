#include "loadgen_options.h"

#include <random>
#include <stdexcept>

namespace igi::loadgen {

std::string usage() {
  return "usage: igi-loadgen [options]\n"
         "  Runs igi-master with --workers 0 and simulated workers over real ZeroMQ sockets, each\n"
         "  answering its jobs with pre-rendered tiles, and measures the master from outside.\n"
         "  --workers N         simulated workers [8]\n"
         "  --size WxH          frame size [640x480]     --tile T  tile side [32]\n"
         "  --pixels F          half or float [half]     --frames F [300]  --warmup F [10]\n"
         "  --fps F             pace the workers for F frames a second [30]\n"
         "  --tile-ms MS        render time per tile instead (0: answer at once, flat out)\n"
         "  --threads T         tiles a simulated worker renders at once [1]\n"
         "  --pools P           threads driving the simulated workers [2]\n"
         "  --io-threads N      the master's ZeroMQ I/O threads [1]\n"
         "  --heartbeat-ms MS   [250]   --timeout-ms MS [1500]\n"
         "  --write-frames      the master writes EXR frames (check them with --check-every N)\n"
         "  --check-every N     check every N-th frame pixel by pixel against the simulated tiles\n"
         "  --stats             the master writes stats.json\n"
         "  --churn SEED        faults on a seeded schedule: a tenth of the workers join late, a tenth\n"
         "                      stall past the master's timeout, a tenth die and are replaced\n"
         "  --diverging N       the first N workers report another VPL-set hash\n"
         "  --nan-every N       worker 0 sends a NaN pixel in every N-th tile\n"
         "  --wrong-tile-every N  worker 0 claims another tile's rectangle in every N-th answer\n"
         "  --master PATH       igi-master [next to this program's build tree]\n"
         "  --master-arg ARG    one more argument for the master (repeatable)\n"
         "  --dir DIR           logs and frames [loadgen-run]   --deadline S [120]\n"
         "  --csv FILE          append the figures as a row   --label TEXT  its first column\n";
}

static int to_int(const std::string& option, const std::string& value) {
  try {
    size_t end = 0;
    const int v = std::stoi(value, &end);
    if (end == value.size() && v >= 0) return v;
  } catch (const std::exception&) {
  }
  throw std::invalid_argument(option + ": expected a non-negative integer, got '" + value + "'");
}

static double to_double(const std::string& option, const std::string& value) {
  try {
    size_t end = 0;
    const double v = std::stod(value, &end);
    if (end == value.size() && v >= 0) return v;
  } catch (const std::exception&) {
  }
  throw std::invalid_argument(option + ": expected a number >= 0, got '" + value + "'");
}

CommandLine parse_command_line(const std::vector<std::string>& args) {
  CommandLine c;
  LoadgenOptions& o = c.run;
  for (size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    auto value = [&]() -> const std::string& {
      if (i + 1 >= args.size()) throw std::invalid_argument(a + ": missing value");
      return args[++i];
    };
    if (a == "--help" || a == "-h") c.help = true;
    else if (a == "--workers") o.workers = std::max(1, to_int(a, value()));
    else if (a == "--size") {
      const std::string v = value();
      const size_t x = v.find('x');
      if (x == std::string::npos) throw std::invalid_argument("--size: expected WxH, got '" + v + "'");
      o.width = std::max(1, to_int(a, v.substr(0, x)));
      o.height = std::max(1, to_int(a, v.substr(x + 1)));
    }
    else if (a == "--tile") o.tile = std::max(1, to_int(a, value()));
    else if (a == "--pixels") o.pixels = value();
    else if (a == "--frames") o.frames = std::max(1, to_int(a, value()));
    else if (a == "--warmup") o.warmup_frames = to_int(a, value());
    else if (a == "--fps") o.fps = to_double(a, value());
    else if (a == "--tile-ms") o.tile_ms = to_double(a, value());
    else if (a == "--threads") o.threads = std::max(1, to_int(a, value()));
    else if (a == "--pools") o.pools = std::max(1, to_int(a, value()));
    else if (a == "--io-threads") o.io_threads = std::max(1, to_int(a, value()));
    else if (a == "--heartbeat-ms") o.heartbeat_ms = to_int(a, value());
    else if (a == "--timeout-ms") o.timeout_ms = to_int(a, value());
    else if (a == "--write-frames") o.write_frames = true;
    else if (a == "--check-every") c.check_every = to_int(a, value());
    else if (a == "--stats") o.stats = true;
    else if (a == "--churn") c.churn_seed = uint64_t(std::stoull(value()));
    else if (a == "--diverging") c.diverging = to_int(a, value());
    else if (a == "--nan-every") c.nan_every = to_int(a, value());
    else if (a == "--wrong-tile-every") c.wrong_tile_every = to_int(a, value());
    else if (a == "--master") o.master_binary = value();
    else if (a == "--master-arg") o.master_args.push_back(value());
    else if (a == "--dir") o.dir = value();
    else if (a == "--deadline") o.deadline_seconds = to_double(a, value());
    else if (a == "--csv") c.csv = value();
    else if (a == "--label") c.label = value();
    else throw std::invalid_argument("unknown option '" + a + "' (see --help)");
  }
  if (o.pixels != "half" && o.pixels != "float")
    throw std::invalid_argument("--pixels: expected half or float, got '" + o.pixels + "'");
  if (c.check_every > 0 && !o.write_frames) throw std::invalid_argument("--check-every needs --write-frames");
  if (o.write_frames && o.pixels != "float" && c.check_every > 0)
    throw std::invalid_argument("--check-every compares exactly: use --pixels float");
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
  all[0].nan_every = c.nan_every;
  all[0].wrong_tile_every = c.wrong_tile_every;
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
