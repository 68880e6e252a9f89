// igi-worker: renders tile jobs for an igi-master.
//   igi-worker --connect tcp://HOST:PORT [--threads T] [--cache DIR] [--scene-dir DIR]... [--give-up S]
//              [--master-key MASTER.pub --key WORKER.key]
#include <cstdio>
#include <stdexcept>
#include <string>
#include <unistd.h>

#include "worker_session.h"

namespace {

const char* kUsage =
    "usage: igi-worker --connect tcp://HOST:PORT [options]\n"
    "  --threads T       render threads, 0 = all [0]\n"
    "  --cache DIR       where scenes received from the master are kept [igi-worker-cache]\n"
    "  --scene-dir DIR   also look here for scene files by name (repeatable) [.]\n"
    "  --give-up S       exit after S seconds without a master [60]\n"
    "  --master-key FILE the master's public key (MASTER.pub) and\n"
    "  --key FILE        this worker's secret key (igi-keys new NAME writes NAME.key): CURVE authentication\n"
    "                    and encryption; the master must list NAME.pub in its --authorized-keys\n"
    "  --curve-fd N      read both keys from file descriptor N (how igi-master passes them to local workers)\n"
    "  --quiet           no log lines\n"
    "exit status: 0 the master said goodbye, 2 bad options or key files, 3 refused (another build or\n"
    "  protocol version, an unknown key), 4 gave up (no master for --give-up seconds), 5 quarantined\n"
    "  (its VPL sets differ from the other workers'), 6 the scene does not load here\n";

// Keys through an inherited descriptor: never on the command line, where any user sees them.
igi::protocol::CurveClientKeys read_keys_from_fd(const std::string& fd_text) {
  const int fd = std::stoi(fd_text);
  const std::string source = "--curve-fd " + fd_text;
  std::string text;
  char buffer[4096];
  ssize_t n;
  while ((n = read(fd, buffer, sizeof buffer)) > 0 && text.size() < 65536) text.append(buffer, size_t(n));
  if (n < 0) throw std::runtime_error(source + ": cannot read the keys");
  close(fd);
  return igi::protocol::parse_client_keys(text, source);
}

igi::WorkerOptions parse(int argc, char** argv) {
  igi::WorkerOptions o;
  std::string master_key, key;
  bool dirs_given = false;
  for (int i = 1; i < argc; ++i) {
    std::string a = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) throw std::invalid_argument(a + ": missing value");
      return argv[++i];
    };
    if (a == "--connect") o.endpoint = value();
    else if (a == "--threads") o.threads = std::stoi(value());
    else if (a == "--cache") o.cache_dir = value();
    else if (a == "--scene-dir") {
      if (!dirs_given) o.search_dirs.clear();
      dirs_given = true;
      o.search_dirs.push_back(value());
    }
    else if (a == "--give-up") o.give_up_seconds = std::stod(value());
    else if (a == "--build-id") o.build_id = value();  // tests: pretend to be another build
    else if (a == "--test-fail-scene-load") o.fail_scene_load = true;  // tests: a scene that does not load here
    else if (a == "--quiet") o.quiet = true;
    else if (a == "--master-key") master_key = value();
    else if (a == "--key") key = value();
    else if (a == "--curve-fd") o.curve = read_keys_from_fd(value());
    else throw std::invalid_argument("unknown option '" + a + "'");
  }
  if (o.endpoint.empty()) throw std::invalid_argument("--connect is required");
  if (master_key.empty() != key.empty())
    throw std::invalid_argument("CURVE needs both --master-key MASTER.pub and --key WORKER.key");
  if (!key.empty())
    o.curve = igi::protocol::CurveClientKeys{igi::protocol::read_public_key_file(master_key),
                                             igi::protocol::read_secret_key_file(key)};
  return o;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    if (argc > 1 && (std::string(argv[1]) == "--help" || std::string(argv[1]) == "-h")) {
      std::fputs(kUsage, stdout);
      return 0;
    }
    igi::WorkerSession session(parse(argc, argv));
    return int(session.run());
  } catch (const std::invalid_argument& e) {
    std::fprintf(stderr, "igi-worker: %s\n%s", e.what(), kUsage);
    return 2;
  } catch (const std::exception& e) {  // a key file, a socket: the message names it
    std::fprintf(stderr, "igi-worker: %s\n", e.what());
    return 2;
  }
}
