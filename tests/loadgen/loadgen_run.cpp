#include "loadgen_run.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>
#include <unistd.h>

#include "child_process.h"
#include "image/image.h"
#include "sim_pool.h"

namespace igi::loadgen {
namespace {

namespace fs = std::filesystem;

struct Sample {
  double t = 0.0;          // seconds since the start
  int frames = 0;          // completed, by the master's log
  double cpu = 0.0;        // the master process, every thread
  double session_cpu = 0.0;  // its main thread (the session loop)
  long rss_kib = 0;
};

// utime + stime of /proc/PID/stat or /proc/PID/task/TID/stat, in seconds; -1 when gone.
double cpu_seconds(const std::string& stat_path) {
  std::ifstream in(stat_path);
  std::string line;
  if (!std::getline(in, line)) return -1.0;
  const size_t close = line.rfind(')');
  if (close == std::string::npos) return -1.0;
  std::istringstream fields(line.substr(close + 2));
  std::string field;
  double ticks = 0.0;
  for (int i = 0; i < 13 && fields >> field; ++i)
    if (i == 11 || i == 12) ticks += std::stod(field);  // fields 14 and 15: utime, stime
  return ticks / double(sysconf(_SC_CLK_TCK));
}

int free_port() {
  zmq::context_t context;
  zmq::socket_t socket(context, zmq::socket_type::router);
  socket.bind("tcp://127.0.0.1:0");
  const std::string endpoint = socket.get(zmq::sockopt::last_endpoint);
  return std::stoi(endpoint.substr(endpoint.rfind(':') + 1));
}

// The master's log, read as it grows: "frame N: X ms, ..." lines count frames and give latencies.
class LogFollower {
 public:
  explicit LogFollower(std::string path) : path_(std::move(path)) {}
  void poll() {
    std::ifstream in(path_, std::ios::binary);
    if (!in) return;
    in.seekg(std::streamoff(offset_));
    std::string chunk((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    offset_ += chunk.size();
    pending_ += chunk;
    for (size_t end; (end = pending_.find('\n')) != std::string::npos; pending_.erase(0, end + 1)) {
      const std::string line = pending_.substr(0, end);
      if (line.rfind("frame ", 0) != 0) continue;
      const size_t colon = line.find(": ");
      latencies_ms_.push_back(colon == std::string::npos ? 0.0 : std::atof(line.c_str() + colon + 2));
    }
  }
  int frames() const { return int(latencies_ms_.size()); }
  const std::vector<double>& latencies_ms() const { return latencies_ms_; }

 private:
  std::string path_;
  size_t offset_ = 0;
  std::string pending_;
  std::vector<double> latencies_ms_;
};

std::string tail(const std::string& path, size_t bytes) {
  std::ifstream in(path, std::ios::binary);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  return text.size() > bytes ? text.substr(text.size() - bytes) : text;
}

double quantile(std::vector<double> v, double q) {
  if (v.empty()) return 0.0;
  const size_t k = std::min(v.size() - 1, size_t(q * double(v.size())));
  std::nth_element(v.begin(), v.begin() + long(k), v.end());
  return v[k];
}

std::vector<std::string> master_command(const LoadgenOptions& o, const std::string& endpoint) {
  std::vector<std::string> args{o.master_binary, "--workers", "0", "--listen", endpoint, "--frames",
                                std::to_string(o.frames), "--size",
                                std::to_string(o.width) + "x" + std::to_string(o.height), "--tile",
                                std::to_string(o.tile), "--pixels", o.pixels, "--pixel-codec", o.pixel_codec,
                                "--scene", "cornell", "--method", "igi",
                                "--io-threads", std::to_string(o.io_threads), "--heartbeat-ms",
                                std::to_string(o.heartbeat_ms), "--timeout-ms", std::to_string(o.timeout_ms)};
  if (o.write_frames) args.insert(args.end(), {"-o", (fs::path(o.dir) / "frame.exr").string()});
  else args.insert(args.end(), {"--no-write", "-o", (fs::path(o.dir) / "unused.exr").string()});
  if (o.stats) args.insert(args.end(), {"--stats", (fs::path(o.dir) / "stats.json").string()});
  args.insert(args.end(), o.master_args.begin(), o.master_args.end());
  return args;
}

void measure(const LoadgenOptions& o, const std::vector<Sample>& samples, const std::vector<double>& latencies,
             LoadgenReport& r) {
  auto first = std::find_if(samples.begin(), samples.end(), [&](const Sample& s) { return s.frames >= o.warmup_frames; });
  if (first == samples.end()) return;
  auto last = std::max_element(samples.begin(), samples.end(), [](const Sample& a, const Sample& b) {
    return a.frames < b.frames || (a.frames == b.frames && a.t > b.t);  // the earliest sample with the most frames
  });
  const int frames = last->frames - first->frames;
  r.wall_seconds = last->t - first->t;
  if (frames <= 0 || r.wall_seconds <= 0) return;
  const double tiles = double(frames) * r.tiles_per_frame;
  r.fps = frames / r.wall_seconds;
  r.tiles_per_second = tiles / r.wall_seconds;
  r.master_cpu_seconds = last->cpu - first->cpu;
  r.session_cpu_seconds = last->session_cpu - first->session_cpu;
  r.cpu_us_per_tile = 1e6 * r.master_cpu_seconds / tiles;
  r.session_us_per_tile = 1e6 * r.session_cpu_seconds / tiles;
  r.cores = r.master_cpu_seconds / r.wall_seconds;
  std::vector<double> measured(latencies.begin() + std::min<long>(o.warmup_frames, long(latencies.size())), latencies.end());
  r.latency_median_ms = quantile(measured, 0.5);
  r.latency_p95_ms = quantile(measured, 0.95);
  // Memory: the frames after the warm-up, in two halves by frame count.
  const int from = o.warmup_frames, to = last->frames, middle = from + (to - from) / 2;
  std::vector<double> halves[2];
  for (const Sample& s : samples) {
    if (s.rss_kib <= 0) continue;
    r.rss_peak_mib = std::max(r.rss_peak_mib, s.rss_kib / 1024.0);
    if (s.frames >= from && s.frames <= to) halves[s.frames >= middle ? 1 : 0].push_back(s.rss_kib / 1024.0);
  }
  r.rss_first_mib = quantile(halves[0], 0.5);
  r.rss_second_mib = quantile(halves[1], 0.5);
}

}  // namespace

int tiles_per_frame(int width, int height, int tile) {
  return ((width + tile - 1) / tile) * ((height + tile - 1) / tile);
}

double paced_tile_seconds(const LoadgenOptions& o) {
  if (o.tile_ms >= 0) return o.tile_ms * 1e-3;
  // The master keeps two frames open: more workers than two frames' tiles cannot all be busy.
  const int tiles = tiles_per_frame(o.width, o.height, o.tile);
  const double busy = std::min(double(o.workers) * std::max(1, o.threads), 2.0 * tiles);
  return busy / (o.fps * tiles);
}

int LoadgenReport::quarantined_workers() const {
  return int(std::count_if(workers.begin(), workers.end(), [](const SimOutcome& w) { return w.quarantined; }));
}

int LoadgenReport::welcomed_workers() const {
  return int(std::count_if(workers.begin(), workers.end(), [](const SimOutcome& w) { return w.welcomed; }));
}

LoadgenReport run_loadgen(const LoadgenOptions& o, const std::vector<SimBehaviour>& behaviours) {
  fs::create_directories(o.dir);
  LoadgenReport report;
  report.tiles_per_frame = tiles_per_frame(o.width, o.height, o.tile);
  report.tile_seconds = paced_tile_seconds(o);
  const std::string endpoint = o.endpoint.empty() ? "tcp://127.0.0.1:" + std::to_string(free_port()) : o.endpoint;
  SimConnection connection{endpoint, std::nullopt};
  if (!o.worker_key.empty())
    connection.curve = protocol::CurveClientKeys{protocol::read_public_key_file(o.master_public_key),
                                                 protocol::read_secret_key_file(o.worker_key)};
  const std::string log = (fs::path(o.dir) / "master.log").string();
  fs::remove(log);
  // A fixed mmap threshold, as in the soak test: glibc's sliding one keeps freed large buffers on the heap.
  std::vector<std::string> environment{"MALLOC_MMAP_THRESHOLD_=131072"};
  environment.insert(environment.end(), o.master_env.begin(), o.master_env.end());
  soak::Child master(master_command(o, endpoint), log, environment);
  const std::string stat = "/proc/" + std::to_string(master.pid()) + "/stat";
  const std::string main_stat = "/proc/" + std::to_string(master.pid()) + "/task/" + std::to_string(master.pid()) + "/stat";

  zmq::context_t context(2);
  TileCache tiles = make_tile_cache(o);
  const Clock::time_point start = Clock::now();
  std::vector<std::unique_ptr<SimPool>> pools;
  const int n_pools = std::max(1, std::min<int>(o.pools, int(behaviours.size())));
  for (int p = 0; p < n_pools; ++p) {
    std::vector<SimBehaviour> mine;
    for (size_t i = size_t(p); i < behaviours.size(); i += size_t(n_pools)) mine.push_back(behaviours[i]);
    pools.push_back(std::make_unique<SimPool>(context, connection, mine, tiles, start));
  }
  LogFollower follower(log);
  std::vector<Sample> samples;
  while (!master.exited()) {
    const double t = std::chrono::duration<double>(Clock::now() - start).count();
    if (t > o.deadline_seconds) {
      master.kill_and_reap();
      break;
    }
    follower.poll();
    Sample s{t, follower.frames(), cpu_seconds(stat), cpu_seconds(main_stat),
             o.sample_memory ? soak::rss_kib(master.pid()) : 0};
    if (s.cpu >= 0) samples.push_back(s);
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  follower.poll();
  {  // every sample, for plotting a run whose memory or rate looks odd
    std::ofstream csv(fs::path(o.dir) / "samples.csv");
    csv << "seconds,frames,cpu_seconds,session_cpu_seconds,rss_kib\n";
    for (const Sample& s : samples) csv << s.t << "," << s.frames << "," << s.cpu << "," << s.session_cpu << "," << s.rss_kib << "\n";
  }
  std::vector<std::vector<SimOutcome>> by_pool;
  for (auto& pool : pools) {
    pool->stop();
    by_pool.push_back(pool->outcomes());
  }
  for (size_t i = 0; i < behaviours.size(); ++i) report.workers.push_back(by_pool[i % by_pool.size()][i / by_pool.size()]);
  report.exit_code = master.exit_code();
  report.frames_done = follower.frames();
  report.master_log = tail(log, 4000);
  measure(o, samples, follower.latencies_ms(), report);
  // The master's last line: "... tiles copied N, reissued M, verification copies K, ...".
  const std::string text = tail(log, 4000);
  auto figure = [&](const std::string& name) -> long {
    const size_t at = text.rfind(name + " ");
    return at == std::string::npos ? -1 : std::atol(text.c_str() + at + name.size() + 1);
  };
  report.duplicated = figure("tiles copied");
  report.reissued = figure("reissued");
  report.verified = figure("verification copies");
  return report;
}

}  // namespace igi::loadgen

namespace igi::loadgen {

TileCache make_tile_cache(const LoadgenOptions& o) {
  if (o.picture.empty()) return TileCache();
  Image picture = read_image(o.picture);
  if (picture.width < o.width || picture.height < o.height)
    throw std::runtime_error(o.picture + ": " + std::to_string(picture.width) + "x" + std::to_string(picture.height) +
                             ", smaller than the frames (" + std::to_string(o.width) + "x" + std::to_string(o.height) + ")");
  return TileCache(std::move(picture));
}

std::vector<std::string> check_written_frames(const LoadgenOptions& o, int every) {
  const TileCache tiles = make_tile_cache(o);
  const PixelFormat format = o.pixels == "float" ? PixelFormat::Float32
                             : o.pixels == "rgb9e5" ? PixelFormat::Rgb9e5 : PixelFormat::Float16;
  Image expected(o.width, o.height);
  for (int y = 0; y < o.height; ++y)
    for (int x = 0; x < o.width; ++x) expected.at(x, y) = tiles.sent_pixel(x, y, format);
  std::vector<std::string> problems;
  for (int f = 0; f < o.frames; f += std::max(1, every)) {
    char name[32];
    std::snprintf(name, sizeof name, "frame-%04d.exr", f);
    const fs::path path = fs::path(o.dir) / (o.frames > 1 ? name : "frame.exr");
    Image image;
    try {
      image = read_image(path.string());
    } catch (const std::exception& e) {
      problems.push_back(path.string() + ": " + e.what());
      continue;
    }
    int wrong = 0;
    for (int y = 0; y < image.height; ++y)
      for (int x = 0; x < image.width; ++x) wrong += image.at(x, y) != expected.at(x, y);
    if (image.width != o.width || image.height != o.height || wrong > 0)
      problems.push_back(path.string() + ": " + std::to_string(wrong) + " pixels differ from the simulated tiles'");
  }
  return problems;
}

}  // namespace igi::loadgen
