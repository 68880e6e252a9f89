// igi-io-bench: how fast a scene file is read and hashed, against the
// byte-at-a-time code they replaced (kept here as the baseline). Prints
// figures; asserts nothing.
//
//   igi-io-bench [MiB] [runs]   (default 64 MiB, 9 runs)
//
// A file of MiB pseudo-random bytes is written to the temporary folder, read
// once to warm the page cache, then each way is timed `runs` times,
// alternating, so that load from other processes falls on both alike. Every
// figure is the median; "cpu" divides by the CPU time the process received.
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <optional>
#include <string>
#include <unistd.h>
#include <vector>

#include "bench/bench_clock.h"
#include "io/file_bytes.h"
#include "sampling/content_hash.h"
#include "sampling/hash.h"

namespace {

using igi::bench::Clock;
using igi::bench::median;

// The baselines: what igi used before XXH3 and read-by-size.
uint64_t fnv1a64(const uint8_t* p, size_t size) {
  uint64_t h = 0xcbf29ce484222325ull;
  for (size_t i = 0; i < size; ++i) { h ^= p[i]; h *= 0x100000001b3ull; }
  return h;
}

std::vector<uint8_t> read_by_iterator(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::vector<uint8_t>((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

struct Rate {
  std::vector<double> wall, cpu;  // MB/s of each run
  void add(const Clock& d, size_t bytes) {
    wall.push_back(double(bytes) / 1e6 / d.wall);
    cpu.push_back(double(bytes) / 1e6 / d.cpu);
  }
};

template <class F>
void time_into(Rate& rate, size_t bytes, F&& work) {
  const Clock start = Clock::now();
  work();
  rate.add(Clock::now() - start, bytes);
}

void print(const char* what, const Rate& before, const Rate& after) {
  const double b = median(before.wall), a = median(after.wall);
  std::printf("%-6s | %10.0f %10.0f | %10.0f %10.0f | %7.1fx\n", what, b, median(before.cpu), a, median(after.cpu),
              a / b);
}

}  // namespace

int main(int argc, char** argv) {
  const size_t mib = argc > 1 ? size_t(std::max(1, std::atoi(argv[1]))) : 64;
  const int runs = argc > 2 ? std::max(1, std::atoi(argv[2])) : 9;
  const size_t size = mib << 20;
  std::vector<uint8_t> bytes(size);
  for (size_t i = 0; i < size; ++i) bytes[i] = uint8_t(igi::mix32(uint32_t(i)));
  const std::string path =
      (std::filesystem::temp_directory_path() / ("igi-io-bench-" + std::to_string(getpid()))).string();
  igi::write_new_file(path, bytes.data(), bytes.size(), 0600, igi::Umask::applies);
  if (read_by_iterator(path) != bytes || igi::read_file_bytes(path) != bytes) {
    std::fprintf(stderr, "igi-io-bench: %s did not read back\n", path.c_str());
    return 1;
  }

  Rate read_before, read_after, hash_before, hash_after;
  uint64_t sink = 0;  // keeps the work from being optimised away
  for (int r = 0; r < runs; ++r) {
    time_into(read_before, size, [&] { sink += read_by_iterator(path).size(); });
    time_into(read_after, size, [&] { sink += igi::read_file_bytes(path)->size(); });
    time_into(hash_before, size, [&] { sink += fnv1a64(bytes.data(), size); });
    time_into(hash_after, size, [&] { sink += igi::content_hash(bytes.data(), size); });
  }
  std::filesystem::remove(path);

  std::printf("%zu MiB file (page cache warm), median of %d runs, MB/s\n", mib, runs);
  std::printf("%-6s | %21s | %21s |\n", "", "before", "after");
  std::printf("%-6s | %10s %10s | %10s %10s | %8s\n", "", "wall", "cpu", "wall", "cpu", "speed-up");
  print("read", read_before, read_after);
  print("hash", hash_before, hash_after);
  std::printf("(before: istreambuf_iterator, FNV-1a byte by byte; after: read by size, XXH3-64)  [%llx]\n",
              static_cast<unsigned long long>(sink & 0xf));
  return 0;
}
