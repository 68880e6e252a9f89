#pragma once
// Running the project's programs from tests: bounded in time, output kept.
#include <string>
#include <sys/types.h>

namespace igi::test {

struct RunResult {
  int exit_code = -1;
  std::string output;  // stdout and stderr together
};

// Runs `command` through the shell, killed after `timeout_seconds`.
RunResult run(const std::string& command, int timeout_seconds = 120);
// Starts `command` in the background; returns its pid (a shell that execs it).
pid_t start(const std::string& command);
void stop(pid_t pid);
// The exit status of `pid` (-1: killed by a signal) once it exits; -2 when it
// has not within `seconds`, and then it is stopped.
int wait_exit(pid_t pid, double seconds);
// A TCP port on 127.0.0.1 that was free a moment ago.
int free_port();

}  // namespace igi::test
