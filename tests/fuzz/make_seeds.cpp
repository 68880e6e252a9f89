// igi-fuzz-seeds DIR: writes the seed corpora of seeds.h as DIR/decode/* and
// DIR/scene/* (scratch files of the glTF writer go to DIR/scratch/).
#include <cstdio>
#include <exception>
#include <filesystem>
#include <fstream>

#include "fuzz/seeds.h"

namespace fs = std::filesystem;

static void write_all(const fs::path& dir, const std::vector<igi::fuzz::Seed>& seeds) {
  fs::create_directories(dir);
  for (const igi::fuzz::Seed& seed : seeds) {
    std::ofstream out(dir / seed.name, std::ios::binary);
    out.write(reinterpret_cast<const char*>(seed.bytes.data()), std::streamsize(seed.bytes.size()));
    if (!out) throw std::runtime_error("cannot write " + (dir / seed.name).string());
  }
  std::printf("%zu seeds in %s\n", seeds.size(), dir.c_str());
}

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s DIR\n", argv[0]);
    return 2;
  }
  try {
    const fs::path dir = argv[1];
    write_all(dir / "decode", igi::fuzz::decode_seeds());
    write_all(dir / "decode", igi::fuzz::display_seeds());
    write_all(dir / "scene", igi::fuzz::scene_seeds((dir / "scratch").string()));
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "igi-fuzz-seeds: %s\n", e.what());
    return 1;
  }
}
