// igi-worker: renders tile jobs for an igi-master.
//   igi-worker --connect tcp://HOST:PORT [--threads T] [--cache DIR] [--scene-dir DIR]... [--give-up S]
#include <cstdio>
#include <string>

#include "worker_session.h"

namespace {

const char* kUsage =
    "usage: igi-worker --connect tcp://HOST:PORT [options]\n"
    "  --threads T       render threads, 0 = all [0]\n"
    "  --cache DIR       where scenes received from the master are kept [igi-worker-cache]\n"
    "  --scene-dir DIR   also look here for scene files by name (repeatable) [.]\n"
    "  --give-up S       exit after S seconds without a master [60]\n"
    "  --quiet           no log lines\n";

igi::WorkerOptions parse(int argc, char** argv) {
  igi::WorkerOptions o;
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
    else if (a == "--quiet") o.quiet = true;
    else throw std::invalid_argument("unknown option '" + a + "'");
  }
  if (o.endpoint.empty()) throw std::invalid_argument("--connect is required");
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
  } catch (const std::exception& e) {
    std::fprintf(stderr, "igi-worker: %s\n%s", e.what(), kUsage);
    return 2;
  }
}
