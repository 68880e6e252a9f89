#include "cluster/local_workers.h"

#include <chrono>
#include <csignal>
#include <thread>
#include <fcntl.h>
#include <filesystem>
#include <stdexcept>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

namespace igi {

std::string find_worker_binary() {
  if (const char* env = std::getenv("IGI_WORKER_BINARY")) return env;
  const std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe").parent_path();
  for (const auto& candidate : {self / "igi-worker", self / ".." / "worker" / "igi-worker"})
    if (std::filesystem::exists(candidate)) return candidate.lexically_normal().string();
  throw std::runtime_error("cannot find igi-worker next to " + self.string() + " (set IGI_WORKER_BINARY)");
}

namespace {

constexpr int kCurveFd = 3;

// A pipe holding `text` (a few hundred bytes: well under a pipe's buffer);
// returns its read end. Both ends close on exec unless moved to kCurveFd.
int pipe_with(const std::string& text) {
  int fds[2];
  if (pipe2(fds, O_CLOEXEC) != 0) throw std::runtime_error("cannot start a worker: pipe failed");
  const bool written = write(fds[1], text.data(), text.size()) == ssize_t(text.size());
  close(fds[1]);
  if (!written) {
    close(fds[0]);
    throw std::runtime_error("cannot start a worker: cannot pass its keys");
  }
  return fds[0];
}

}  // namespace

void LocalWorkers::start(int count, const std::string& endpoint, int threads_each,
                         const std::vector<std::string>& extra_args, const protocol::CurveClientKeys* curve) {
  const std::string binary = find_worker_binary();
  const pid_t parent = getpid();
  for (int i = 0; i < count; ++i) {
    std::vector<std::string> args{binary, "--connect", endpoint, "--threads", std::to_string(threads_each), "--quiet"};
    if (curve) args.insert(args.end(), {"--curve-fd", std::to_string(kCurveFd)});
    args.insert(args.end(), extra_args.begin(), extra_args.end());
    const int keys_fd = curve ? pipe_with(protocol::format_client_keys(*curve)) : -1;
    pid_t pid = fork();
    if (pid < 0) throw std::runtime_error("cannot start a worker: fork failed");
    if (pid == 0) {
      prctl(PR_SET_PDEATHSIG, SIGKILL);
      if (getppid() != parent) _exit(1);  // the master died before prctl took effect
      // dup2 onto itself would keep close-on-exec, hence the explicit clear.
      if (keys_fd >= 0 && (dup2(keys_fd, kCurveFd) < 0 || fcntl(kCurveFd, F_SETFD, 0) != 0)) _exit(1);
      std::vector<char*> argv;
      for (std::string& a : args) argv.push_back(a.data());
      argv.push_back(nullptr);
      execv(binary.c_str(), argv.data());
      _exit(127);
    }
    if (keys_fd >= 0) close(keys_fd);
    pids_.push_back(pid);
  }
}

void LocalWorkers::kill_one(size_t index, int signal) {
  if (index < pids_.size() && pids_[index] > 0) kill(pids_[index], signal);
}

// SIGTERM, and SIGCONT so that a stopped worker can act on it; whatever has
// not ended within the grace period gets SIGKILL, which ends even a stopped one.
void LocalWorkers::stop_all(std::chrono::milliseconds grace) {
  std::vector<pid_t> running;
  for (pid_t pid : pids_)
    if (pid > 0 && kill(pid, SIGTERM) == 0) {
      kill(pid, SIGCONT);
      running.push_back(pid);
    }
  pids_.clear();
  const auto deadline = std::chrono::steady_clock::now() + grace;
  while (!running.empty() && std::chrono::steady_clock::now() < deadline) {
    std::erase_if(running, [](pid_t pid) { return waitpid(pid, nullptr, WNOHANG) != 0; });
    if (!running.empty()) std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  for (pid_t pid : running) {
    kill(pid, SIGKILL);
    waitpid(pid, nullptr, 0);
  }
}

}  // namespace igi
