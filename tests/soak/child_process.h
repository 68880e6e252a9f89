#pragma once
// A child process of the soak driver: started with its output in a log file,
// killed and reaped when the object goes, and killed by the kernel when the
// driver dies however it dies (PR_SET_PDEATHSIG), so no run leaves processes behind.
// Call everything from the thread that started it (the death signal follows that thread).
#include <string>
#include <sys/types.h>
#include <vector>

namespace igi::soak {

class Child {
 public:
  Child() = default;
  // argv[0] is the program (searched in PATH); stdout and stderr go to `log_path`;
  // `environment` (NAME=VALUE) is added to the driver's own.
  Child(const std::vector<std::string>& argv, const std::string& log_path,
        const std::vector<std::string>& environment = {});
  Child(Child&& other) noexcept;
  Child& operator=(Child&& other) noexcept;
  Child(const Child&) = delete;
  Child& operator=(const Child&) = delete;
  ~Child();

  pid_t pid() const { return pid_; }
  bool started() const { return pid_ > 0; }
  // Reaps without waiting; true once it has exited (then exit_code/signalled are valid).
  bool exited();
  bool wait_for_exit(double seconds);
  void signal(int sig) const;
  void kill_and_reap();  // SIGCONT first, so a stopped child dies too
  int exit_code() const;        // -1 when killed by a signal
  int exit_signal() const;      // 0 when it exited
  std::string how_it_ended() const;
  std::string log_path() const { return log_; }

 private:
  pid_t pid_ = -1;
  bool reaped_ = false;
  int status_ = 0;
  std::string log_;
};

// From /proc; -1 when the process is gone.
long rss_kib(pid_t pid);
int open_fds(pid_t pid);

}  // namespace igi::soak
