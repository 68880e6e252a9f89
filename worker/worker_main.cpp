// igi-worker: renders tile jobs for an igi-master.
//   igi-worker --connect tcp://HOST:PORT [--threads T] [--cache DIR] [--scene-dir DIR]... [--give-up S]
//              [--master-key MASTER.pub --key WORKER.key]
#include <CLI/CLI.hpp>
#include <climits>
#include <iostream>
#include <optional>
#include <stdexcept>
#include <string>
#include <unistd.h>

#include "cli/option_checks.h"
#include "worker_session.h"

namespace {

constexpr int kUsageStatus = 2;  // bad options or key files

const char* kExitStatus =
    "exit status: 0 the master said goodbye, 2 bad options or key files, 3 refused (another build or\n"
    "  protocol version, an unknown key), 4 gave up (no master for --give-up seconds), 5 quarantined\n"
    "  (its VPL sets differ from the master's own, or its results keep failing validation), 6 the scene\n"
    "  or its environment map does not load here, 7 a frame needs more memory than this machine has";

// Keys through an inherited descriptor: never on the command line, where any user sees them.
igi::protocol::CurveClientKeys read_keys_from_fd(int fd) {
  const std::string source = "--curve-fd " + std::to_string(fd);
  std::string text;
  char buffer[4096];
  ssize_t n;
  while ((n = read(fd, buffer, sizeof buffer)) > 0 && text.size() < 65536) text.append(buffer, size_t(n));
  if (n < 0) throw std::runtime_error(source + ": cannot read the keys");
  close(fd);
  return igi::protocol::parse_client_keys(text, source);
}

// The key files named on the command line (after the parse: reading them is no option error).
struct KeyFiles {
  std::string master_key, key;
  int fd = -1;
};

void declare(CLI::App& app, igi::WorkerOptions& o, KeyFiles& keys) {
  using igi::cli::integer;
  igi::cli::take_last_by_default(app);
  igi::cli::add_version_flag(app);
  app.footer(kExitStatus);
  app.add_option("--connect", o.endpoint, "the master's endpoint")->required()->type_name("tcp://HOST:PORT");
  app.add_option("--threads", o.threads, "render threads, 0 = all [0]")
      ->check(integer(0, igi::cli::kMaxThreads))->type_name("T");
  app.add_option("--cache", o.cache_dir, "where scenes received from the master are kept [igi-worker-cache]")
      ->type_name("DIR");
  app.add_option_function<std::vector<std::string>>(
         "--scene-dir", [&o](const std::vector<std::string>& dirs) { o.search_dirs = dirs; },
         "also look here for scene files by name (repeatable) [.]")
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll)->type_name("DIR");
  app.add_option("--give-up", o.give_up_seconds, "exit after S seconds without a master [60]")
      ->check(igi::cli::non_negative_number())->type_name("S");
  app.add_option("--master-key", keys.master_key, "the master's public key (MASTER.pub), with --key")
      ->type_name("FILE");
  app.add_option("--key", keys.key, "this worker's secret key (igi-keys new NAME writes NAME.key): CURVE "
                 "authentication and encryption; the master must list NAME.pub in its --authorized-keys")
      ->type_name("FILE");
  app.add_option("--curve-fd", keys.fd, "read both keys from file descriptor N (how igi-master passes them to local "
                 "workers)")->check(integer(0, INT_MAX))->type_name("N");
  app.add_flag("--quiet", o.quiet, "no log lines");
  app.add_option("--build-id", o.build_id)->group("");  // tests: pretend to be another build
  app.add_flag("--test-fail-scene-load", o.fail_scene_load)->group("");  // tests: a scene that does not load here
  app.add_option("--test-memory-bytes", o.memory_bytes)->group("");  // tests: a machine with this much memory
}

// Empty when --help was asked.
std::optional<igi::WorkerOptions> parse(int argc, char** argv) {
  igi::WorkerOptions o;
  KeyFiles keys;
  CLI::App app("igi-worker: renders tile jobs for an igi-master", "igi-worker");
  declare(app, o, keys);
  if (!igi::cli::parse(app, {argv + 1, argv + argc})) {
    std::cout << app.help();
    return std::nullopt;
  }
  if (keys.master_key.empty() != keys.key.empty())
    throw igi::cli::OptionError("CURVE needs both --master-key MASTER.pub and --key WORKER.key");
  if (keys.fd >= 0) o.curve = read_keys_from_fd(keys.fd);
  if (!keys.key.empty())
    o.curve = igi::protocol::CurveClientKeys{igi::protocol::read_public_key_file(keys.master_key),
                                             igi::protocol::read_secret_key_file(keys.key)};
  return o;
}

}  // namespace

int main(int argc, char** argv) {
  // A bad command line, a key file or a socket: the message names it, status 2.
  return igi::cli::run_program("igi-worker", kUsageStatus, kUsageStatus, [&] {
    std::optional<igi::WorkerOptions> options = parse(argc, argv);
    if (!options) return 0;
    igi::WorkerSession session(std::move(*options));
    return int(session.run());
  });
}
