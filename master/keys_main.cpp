// igi-keys: CURVE key pairs for igi-master and igi-worker.
//   igi-keys new NAME    NAME.key (secret, mode 0600) and NAME.pub (public)
//   igi-keys show FILE   the Z85 public key of a NAME.key or NAME.pub file, after checking it
#include <cstdio>
#include <filesystem>
#include <stdexcept>
#include <string>

#include "build_id.h"
#include "protocol/curve.h"

namespace {

const char* kUsage =
    "usage: igi-keys new NAME     write NAME.key (secret, mode 0600: keep it on this machine)\n"
    "                             and NAME.pub (public: give it to the other side)\n"
    "       igi-keys show FILE    check a .key or .pub file and print its Z85 public key\n"
    "The master runs with --key master.key and --authorized-keys DIR (the workers' .pub files);\n"
    "each worker with --key worker.key and --master-key master.pub.\n";

int make_new(const std::string& name) {
  const igi::protocol::CurveKeyPair keys = igi::protocol::make_curve_keypair();
  igi::protocol::write_key_files(name, keys);
  std::printf("wrote %s.key (secret, mode 0600) and %s.pub (public key %s)\n", name.c_str(), name.c_str(),
              keys.public_key.c_str());
  return 0;
}

int show(const std::string& path) {
  const bool is_public = std::filesystem::path(path).extension() == ".pub";
  std::printf("%s\n", is_public ? igi::protocol::read_public_key_file(path).c_str()
                                : igi::protocol::read_secret_key_file(path).public_key.c_str());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  const std::string command = argc > 1 ? argv[1] : "";
  if (command == "--help" || command == "-h") return std::fputs(kUsage, stdout), 0;
  if (command == "--version") return std::printf("%s\n", igi::build_id()), 0;
  if (argc != 3 || (command != "new" && command != "show")) return std::fputs(kUsage, stderr), 2;
  try {
    return command == "new" ? make_new(argv[2]) : show(argv[2]);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "igi-keys: %s\n", e.what());
    return 1;
  }
}
