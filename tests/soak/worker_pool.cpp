#include "worker_pool.h"

#include <csignal>
#include <filesystem>

namespace igi::soak {

namespace {
constexpr auto kSlowStopped = std::chrono::milliseconds(15);
constexpr auto kSlowRunning = std::chrono::milliseconds(5);
}  // namespace

WorkerPool::WorkerPool(std::vector<std::string> command, std::string endpoint, std::string log_dir,
                       int loopback_workers, NetNamespace* ns, std::string ns_endpoint)
    : command_(std::move(command)), endpoint_(std::move(endpoint)), ns_endpoint_(std::move(ns_endpoint)),
      log_dir_(std::move(log_dir)), ns_(ns) {
  slots_.resize(size_t(loopback_workers + (ns ? 1 : 0)));
  if (ns) slots_.back().in_namespace = true;
}

void WorkerPool::start(int i) {
  Slot& s = slots_[size_t(i)];
  std::vector<std::string> argv = s.in_namespace ? ns_->exec_prefix() : std::vector<std::string>{};
  argv.insert(argv.end(), command_.begin(), command_.end());
  argv.push_back("--connect");
  argv.push_back(s.in_namespace ? ns_endpoint_ : endpoint_);
  argv.push_back("--cache");
  argv.push_back((std::filesystem::path(log_dir_) / ("cache-" + std::to_string(i))).string());
  const std::string log = (std::filesystem::path(log_dir_) /
                           ("worker-" + std::to_string(i) + "." + std::to_string(s.generation++) + ".log")).string();
  s.process = Child(argv, log);
  s.state = State::Running;
  s.paused = false;
}

void WorkerPool::start_all() {
  for (int i = 0; i < size(); ++i) start(i);
}

int WorkerPool::pick(int preferred, bool slow_too) const {
  for (int k = 0; k < size(); ++k) {
    const Slot& s = slots_[size_t((preferred + k) % size())];
    if (!s.in_namespace && (s.state == State::Running || (slow_too && s.state == State::Slow))) return (preferred + k) % size();
  }
  return -1;
}

int WorkerPool::apply(const Fault& f) {
  const auto now = Clock::now();
  const auto later = now + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(f.seconds));
  if (f.kind == FaultKind::CutLink) {
    if (!ns_ || link_down_) return -1;
    link_down_ = ns_->cut();
    link_up_at_ = later;
    return link_down_ ? size() - 1 : -1;
  }
  const int i = pick(f.worker, f.kind != FaultKind::SlowWorker);  // a slow worker can still be killed or stopped
  if (i < 0) return -1;
  Slot& s = slots_[size_t(i)];
  s.until = later;
  if (s.state == State::Slow) s.process.signal(SIGCONT);  // leave the duty cycle first
  if (f.kind == FaultKind::KillWorker) {
    s.process.kill_and_reap();
    s.state = State::Down;
  } else if (f.kind == FaultKind::StopWorker) {
    s.process.signal(SIGSTOP);
    s.state = State::Stopped;
  } else if (f.kind == FaultKind::SlowWorker) {
    s.state = State::Slow;
    s.next_toggle = now;
  }
  return i;
}

void WorkerPool::tick() {
  const auto now = Clock::now();
  if (link_down_ && now >= link_up_at_) link_down_ = !ns_->restore();
  for (int i = 0; i < size(); ++i) {
    Slot& s = slots_[size_t(i)];
    if (s.state == State::Down && now >= s.until) {
      start(i);
    } else if ((s.state == State::Stopped || s.state == State::Slow) && now >= s.until) {
      s.process.signal(SIGCONT);
      s.state = State::Running;
    } else if (s.state == State::Slow && now >= s.next_toggle) {
      s.paused = !s.paused;
      s.process.signal(s.paused ? SIGSTOP : SIGCONT);
      s.next_toggle = now + (s.paused ? kSlowStopped : kSlowRunning);
    }
  }
}

std::vector<std::string> WorkerPool::unexpected_exits() {
  std::vector<std::string> lines;
  for (int i = 0; i < size(); ++i) {
    Slot& s = slots_[size_t(i)];
    if (s.state == State::Down || !s.process.exited()) continue;
    if (s.state != State::Left && s.process.exit_code() == 0) {
      s.state = State::Left;
      s.until = Clock::now() + std::chrono::seconds(5);
      continue;
    }
    if (s.state == State::Left && Clock::now() < s.until) continue;
    lines.push_back("worker " + std::to_string(i) + " ended by itself (" + s.process.how_it_ended() + "); log " +
                    s.process.log_path());
    start(i);
  }
  return lines;
}

std::vector<std::string> WorkerPool::finish(double seconds) {
  for (Slot& s : slots_) {
    if (s.state == State::Down || s.state == State::Left) continue;
    s.process.signal(SIGCONT);
    s.state = State::Running;
  }
  if (link_down_) link_down_ = !ns_->restore();
  const auto end = Clock::now() + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(seconds));
  std::vector<std::string> bad;
  for (int i = 0; i < size(); ++i) {
    Slot& s = slots_[size_t(i)];
    if (s.state == State::Down || s.state == State::Left) continue;
    const double left = std::chrono::duration<double>(end - Clock::now()).count();
    if (!s.process.wait_for_exit(std::max(0.0, left))) continue;  // still waiting for a master: killed below
    if (s.process.exit_signal() || s.process.exit_code() != 0)
      bad.push_back("worker " + std::to_string(i) + " ended " + s.process.how_it_ended() + "; log " + s.process.log_path());
  }
  kill_all();
  return bad;
}

void WorkerPool::kill_all() {
  for (Slot& s : slots_) s.process.kill_and_reap();
  if (link_down_ && ns_) link_down_ = !ns_->restore();
}

}  // namespace igi::soak
