#include "local_workers.h"

#include <csignal>
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

void LocalWorkers::start(int count, const std::string& endpoint, int threads_each,
                         const std::vector<std::string>& extra_args) {
  const std::string binary = find_worker_binary();
  const pid_t parent = getpid();
  for (int i = 0; i < count; ++i) {
    std::vector<std::string> args{binary, "--connect", endpoint, "--threads", std::to_string(threads_each), "--quiet"};
    args.insert(args.end(), extra_args.begin(), extra_args.end());
    pid_t pid = fork();
    if (pid < 0) throw std::runtime_error("cannot start a worker: fork failed");
    if (pid == 0) {
      prctl(PR_SET_PDEATHSIG, SIGKILL);
      if (getppid() != parent) _exit(1);  // the master died before prctl took effect
      std::vector<char*> argv;
      for (std::string& a : args) argv.push_back(a.data());
      argv.push_back(nullptr);
      execv(binary.c_str(), argv.data());
      _exit(127);
    }
    pids_.push_back(pid);
  }
}

void LocalWorkers::kill_one(size_t index, int signal) {
  if (index < pids_.size() && pids_[index] > 0) kill(pids_[index], signal);
}

void LocalWorkers::stop_all() {
  for (pid_t pid : pids_)
    if (pid > 0) kill(pid, SIGTERM);
  for (pid_t pid : pids_)
    if (pid > 0) waitpid(pid, nullptr, 0);
  pids_.clear();
}

}  // namespace igi
