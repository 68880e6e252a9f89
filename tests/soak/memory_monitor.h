#pragma once
// The master's memory over a soak run, sampled from /proc every 50 ms.
//
// Bounded means: for each master process that rendered at least kMinFrames
// frames, its typical RSS (the median of the samples) while it rendered the
// second half of its frames is no more than `margin` above that of the first
// half (after a warm-up of max(5, frames/10) frames). Medians, because 1-4 MB
// garbage messages in flight make the peak jump by megabytes either way; a
// leak lifts the whole curve. Leaking L bytes a frame moves the median by
// about L x (frames - warm-up)/2: with the default 2 MiB (the medians move by
// less than 0.5 MiB without a leak), a process of 60 frames is caught leaking
// 76 KiB a frame (half a 128x96 float frame), one of 250 frames 18 KiB a
// frame. The master runs with glibc's mmap threshold fixed (MALLOC_MMAP_THRESHOLD_=131072): the sliding
// default keeps freed multi-megabyte messages on the heap and moves RSS in
// steps of megabytes that say nothing about the master's own memory.
// Open file descriptors are judged on their floor (the fewest open in each
// half), since garbage connections come and go above it: the second half's
// may exceed the first's by at most 8 (a descriptor leaked per frame or per
// connection lifts the floor; a worker more or less moves it by one).
#include <string>
#include <sys/types.h>
#include <vector>

namespace igi::soak {

class MemoryMonitor {
 public:
  static constexpr int kMinFrames = 40;

  void start_process(int run);  // a new master process, numbered from 0
  void sample(pid_t pid, int frames_done_by_this_process);
  struct Verdict {
    int run = 0, frames = 0;
    long first_kib = 0, second_kib = 0;  // median RSS of each half
    long peak_kib = 0;
    int first_fds = 0, second_fds = 0;
    bool judged = false, bounded = true;
    std::string text;
  };
  std::vector<Verdict> judge(double margin_mib) const;
  long peak_kib() const;
  // Every sample as CSV (run, frames, rss_kib, fds), for plotting a suspicious run.
  void write_csv(const std::string& path) const;

 private:
  struct Sample {
    int frames = 0;
    long rss_kib = 0;
    int fds = 0;
  };
  std::vector<std::vector<Sample>> runs_;
};

}  // namespace igi::soak
