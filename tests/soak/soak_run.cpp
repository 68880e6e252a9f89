#include "soak_run.h"

#include <algorithm>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

namespace igi::soak {

namespace fs = std::filesystem;

// A free port below Linux's ephemeral range (32768-60999): while the master is
// down between a kill and its restart, no outgoing connection on this machine
// can be given its port, so the successor can always bind it again.
static int master_port() {
  for (int k = 0; k < 1000; ++k) {
    const int port = 20000 + int((unsigned(getpid()) * 7919u + unsigned(k) * 131u) % 12000u);
    const int fd = socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
    sockaddr_in a{};
    a.sin_family = AF_INET;
    a.sin_port = htons(uint16_t(port));
    a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    const bool free = bind(fd, reinterpret_cast<sockaddr*>(&a), sizeof a) == 0;
    close(fd);
    if (free) return port;
  }
  throw std::runtime_error("no free port in 20000-31999 on 127.0.0.1");
}

SoakRun::SoakRun(SoakOptions options, const std::atomic<bool>& stop) : o_(std::move(options)), stop_(stop) {
  std::istringstream words(o_.render_args);
  for (std::string w; words >> w;) render_args_.push_back(w);
  std::vector<std::string> args = render_args_;
  args.insert(args.end(), {"--size", std::to_string(o_.width) + "x" + std::to_string(o_.height)});
  render_ = parse_render_options(args);
  if (o_.seed == 0) o_.seed = uint64_t(std::chrono::system_clock::now().time_since_epoch().count()) % 1000000007ull;
  totals_.seed = o_.seed;
  totals_.frames = o_.frames;
}

double SoakRun::seconds_since_start() const { return std::chrono::duration<double>(Clock::now() - start_).count(); }

void SoakRun::prepare() {
  // Emptied first, but only when it is empty or an earlier soak run's folder (it has logs/).
  if (fs::exists(o_.dir) && !fs::is_empty(o_.dir) && !fs::exists(fs::path(o_.dir) / "logs"))
    throw std::runtime_error("--dir " + o_.dir + ": not empty and not a soak run's folder; give another");
  fs::remove_all(o_.dir);
  logs_ = (fs::path(o_.dir) / "logs").string();
  fs::create_directories(logs_);
  port_ = master_port();
  start_ = Clock::now();
  deadline_ = start_ + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(o_.deadline_seconds));
}

// The namespace's worker reaches the master through a relay on the veth address (see tcp_relay.h).
void SoakRun::set_up_namespace() {
  if (o_.netns == "off") {
    totals_.netns = "off (--netns off)";
    return;
  }
  std::string why;
  if (geteuid() == 0) remove_stale_namespaces();
  ns_ = NetNamespace::create(why);
  if (ns_) {
    try {
      relay_ = std::make_unique<TcpRelay>(ns_->host_address(), "127.0.0.1", port_);
    } catch (const std::exception& e) {
      why = e.what();
      ns_.reset();
    }
  }
  if (!ns_) {
    totals_.netns = "skipped (" + why + ")";
    if (o_.netns == "on") totals_.failures.push_back("--netns on, but " + why);
    return;
  }
  totals_.netns = "1 worker in namespace, link " + ns_->host_address() + " <-> namespace, via a relay to the master";
}

bool SoakRun::start_master(int first, bool wait_until_listening) {
  const std::string run = std::to_string(master_runs_);
  std::vector<std::string> argv{o_.master_binary, "--workers", "0", "--listen", "tcp://127.0.0.1:" + std::to_string(port_),
                                "--frames", std::to_string(o_.frames - first), "--first-frame", std::to_string(first),
                                "--camera-path", "swing", "--size", std::to_string(o_.width) + "x" + std::to_string(o_.height),
                                "-o", (fs::path(o_.dir) / "frame.exr").string(),
                                "--stats", (fs::path(o_.dir) / ("stats-" + run + ".json")).string(),
                                "--heartbeat-ms", std::to_string(o_.heartbeat_ms), "--timeout-ms", std::to_string(o_.timeout_ms)};
  argv.insert(argv.end(), render_args_.begin(), render_args_.end());
  // A fixed mmap threshold: glibc's sliding one keeps freed 1-4 MB garbage messages on the heap,
  // which moves RSS in steps of megabytes that say nothing about the master (see memory_monitor.h).
  master_ = Child(argv, (fs::path(logs_) / ("master-" + run + ".log")).string(), {"MALLOC_MMAP_THRESHOLD_=131072"});
  memory_.start_process(master_runs_++);
  segment_first_ = first;
  master_down_ = false;
  if (!wait_until_listening) return true;
  for (int i = 0; i < 1000; ++i) {  // 10 s
    std::ifstream log(master_.log_path());
    std::stringstream text;
    text << log.rdbuf();
    if (text.str().find("listening on") != std::string::npos) return true;
    if (master_.exited()) {
      totals_.failures.push_back("the master did not start (" + master_.how_it_ended() + "): " + text.str());
      return false;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  totals_.failures.push_back("the master did not listen within 10 s; log " + master_.log_path());
  return false;
}

// Frames are written in order by one writer thread, so only the last file on
// disk can be partial: it is deleted and rendered again by the successor.
void SoakRun::kill_master(double restart_delay) {
  master_.kill_and_reap();
  advance_frames();
  int resume = segment_first_;
  if (frames_on_disk_ > segment_first_) {
    resume = frames_on_disk_ - 1;
    fs::remove(frame_file(o_.dir, resume));
    ++totals_.frames_rerendered;
  }
  frames_on_disk_ = segment_first_ = resume;
  master_down_ = true;
  killed_at_ = Clock::now();
  restart_at_ = killed_at_ + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(restart_delay));
  timing_restart_ = true;
}

void SoakRun::advance_frames() {
  while (frames_on_disk_ < o_.frames && fs::exists(frame_file(o_.dir, frames_on_disk_))) ++frames_on_disk_;
  if (timing_restart_ && !master_down_ && frames_on_disk_ > segment_first_) {
    totals_.restart_seconds.push_back(std::chrono::duration<double>(Clock::now() - killed_at_).count());
    timing_restart_ = false;
  }
}

// True when the run is over (the master left); restarts a master that died on its own.
bool SoakRun::master_finished() {
  if (master_down_ || !master_.exited()) return false;
  advance_frames();
  if (master_.exit_code() == 0) {
    if (frames_on_disk_ < o_.frames)
      totals_.failures.push_back("the master finished with frames " + std::to_string(frames_on_disk_) + ".. missing");
    finished_ = true;
    return true;
  }
  totals_.failures.push_back("the master died by itself (" + master_.how_it_ended() + ") at frame " +
                             std::to_string(frames_on_disk_) + "; log " + master_.log_path());
  if (++unexpected_master_exits_ >= 3) return true;
  kill_master(0.0);  // carry on with a successor, to see what else breaks
  return false;
}

// False when the fault must wait: its worker kind is all busy, or the link is already cut.
bool SoakRun::inject(Fault& f) {
  if (f.kind == FaultKind::Garbage) {
    garbage_bursts_.push_back(std::async(std::launch::async, [this, seed = f.seed] { return garbage_->burst(seed); }));
    return true;
  }
  if (f.kind == FaultKind::Hostile) {
    const std::string endpoint = "tcp://127.0.0.1:" + std::to_string(port_);
    const HostileKind kind = HostileKind(f.seed % kHostileKinds);
    hostile_runs_.push_back(
        std::async(std::launch::async, [endpoint, kind, seconds = f.seconds] { return run_hostile(endpoint, kind, seconds); }));
    return true;
  }
  if (f.kind == FaultKind::RestartMaster) {
    if (master_down_) return false;
    kill_master(f.seconds);
    return true;
  }
  f.worker = workers_->apply(f);
  return f.worker >= 0;
}

void SoakRun::fire_due_faults() {
  for (size_t i = 0; i < plan_.size() && plan_[i].at_frame <= frames_on_disk_; ++i) {
    if (injected_[i]) continue;
    Fault f = plan_[i];
    if (!inject(f)) continue;
    injected_[i] = true;
    ++totals_.faults[f.kind];
    std::printf("soak: %6.2f s  %s\n", seconds_since_start(), describe(f).c_str());
    std::fflush(stdout);
  }
}

bool SoakRun::loop_once() {
  if (stop_) {
    totals_.failures.push_back("interrupted at frame " + std::to_string(frames_on_disk_));
    return false;
  }
  if (Clock::now() > deadline_) {
    totals_.failures.push_back("deadline of " + std::to_string(int(o_.deadline_seconds)) + " s passed at frame " +
                               std::to_string(frames_on_disk_) + " of " + std::to_string(o_.frames));
    return false;
  }
  workers_->tick();
  for (const std::string& line : workers_->unexpected_exits()) totals_.failures.push_back(line);
  if (master_down_ && Clock::now() >= restart_at_) start_master(segment_first_, false);
  if (master_finished()) return false;
  advance_frames();
  fire_due_faults();
  if (!master_down_ && Clock::now() >= next_sample_) {
    memory_.sample(master_.pid(), frames_on_disk_ - segment_first_);
    next_sample_ = Clock::now() + std::chrono::milliseconds(50);
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(1));
  return true;
}

// Fakes that answered must have been caught: each connection of a sybil pair
// or a failer that sent a few results is told it is quarantined. (One that
// joined as its frames ended may have had nothing to be judged on.) What the
// hostile peers could not do at all, change a pixel or stall the run, the
// frame check and the deadline judge.
void SoakRun::judge_hostile(const HostileReport& r) {
  std::printf("soak: hostile peer, %s: %d connections, %llu jobs taken, %llu results sent, %d told they are "
              "quarantined\n", hostile_name(r.kind), r.connections, (unsigned long long)r.jobs_taken,
              (unsigned long long)r.results_sent, r.quarantined);
  const bool judged = r.kind == HostileKind::Sybil || r.kind == HostileKind::Failer;
  if (judged && r.results_sent >= uint64_t(4 * r.connections) && r.quarantined < r.connections)
    totals_.failures.push_back(std::string("a ") + hostile_name(r.kind) + " sent " + std::to_string(r.results_sent) +
                               " results and only " + std::to_string(r.quarantined) + " of its " +
                               std::to_string(r.connections) + " connections were quarantined");
}

void SoakRun::corrupt_frame_file(int frame) const {
  const std::string path = frame_file(o_.dir, frame);
  if (!fs::exists(path)) return;
  Image image = read_image(path);
  auto brightest = std::max_element(image.pixels.begin(), image.pixels.end(),
                                    [](const glm::vec3& a, const glm::vec3& b) { return a.y < b.y; });
  brightest->y = std::nextafter(brightest->y, 1e30f);
  write_image(image, path);
  std::printf("soak: self-test: frame %d altered by one ulp in one pixel\n", frame);
}

int SoakRun::run() {
  prepare();
  set_up_namespace();
  std::vector<bool> kinds = parse_fault_kinds(o_.kinds);
  kinds[size_t(FaultKind::CutLink)] = kinds[size_t(FaultKind::CutLink)] && ns_ != nullptr;
  plan_ = plan_faults(o_.seed, o_.frames, o_.faults, o_.workers, o_.timeout_ms * 1e-3, kinds);
  injected_.assign(plan_.size(), false);
  std::printf("soak: seed %llu: %d frames %dx%d (%s), %d workers%s, %zu faults, deadline %.0f s; in %s\n",
              (unsigned long long)o_.seed, o_.frames, o_.width, o_.height, o_.render_args.c_str(), o_.workers,
              ns_ ? " + 1 in a network namespace" : "", plan_.size(), o_.deadline_seconds, o_.dir.c_str());
  std::printf("soak: network namespaces: %s\n", totals_.netns.c_str());
  std::fflush(stdout);
  const std::string endpoint = "tcp://127.0.0.1:" + std::to_string(port_);
  garbage_ = std::make_unique<GarbageClient>("127.0.0.1", port_, o_.real_oversized);
  workers_ = std::make_unique<WorkerPool>(
      std::vector<std::string>{o_.worker_binary, "--threads", "1", "--give-up", "60"}, endpoint, logs_, o_.workers,
      ns_.get(), relay_ ? "tcp://" + ns_->host_address() + ":" + std::to_string(relay_->port()) : "");
  if (start_master(0, true)) {
    workers_->start_all();
    while (loop_once()) {
    }
  }
  GarbageCounts garbage;
  for (auto& burst : garbage_bursts_) garbage.add(burst.get());
  for (auto& run : hostile_runs_) judge_hostile(run.get());
  for (const std::string& line : finished_ ? workers_->finish(5.0) : std::vector<std::string>{})
    totals_.failures.push_back(line);
  workers_->kill_all();
  master_.kill_and_reap();
  relay_.reset();
  ns_.reset();
  totals_.garbage = garbage.sent;
  totals_.garbage_zmq_messages = garbage.zmq_messages;
  for (size_t k = 0; k < plan_.size(); ++k)
    if (!injected_[k]) std::printf("soak: not injected (the run ended first): %s\n", describe(plan_[k]).c_str());
  if (o_.corrupt_frame >= 0) corrupt_frame_file(o_.corrupt_frame);
  if (o_.delete_frame >= 0 && fs::remove(frame_file(o_.dir, o_.delete_frame)))
    std::printf("soak: self-test: frame %d deleted\n", o_.delete_frame);
  std::printf("soak: checking %d frames against the single-process render ...\n", o_.frames);
  std::fflush(stdout);
  CameraPath swing;  // as the master's --camera-path swing over --first-frame + --frames = o_.frames
  swing.kind = CameraPath::Kind::Swing;
  swing.frames = o_.frames;
  const FrameVerdict verdict = check_frames(o_.dir, o_.frames, ReferenceRenderer(render_, swing));
  memory_.write_csv((fs::path(o_.dir) / "master-memory.csv").string());
  totals_.wall_seconds = seconds_since_start();
  std::vector<MemoryMonitor::Verdict> memory = memory_.judge(o_.rss_margin_mib);
  if (!o_.memory_check)
    for (MemoryMonitor::Verdict& v : memory) v.bounded = true, v.text += " (not judged: --memory-check off)";
  return report(totals_, verdict, read_master_figures(o_.dir, master_runs_), memory, memory_.peak_kib(),
                o_.rss_margin_mib);
}

}  // namespace igi::soak
