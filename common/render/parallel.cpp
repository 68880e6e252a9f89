#include "render/parallel.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>
#include <tbb/task_arena.h>
#include <xmmintrin.h>

#include "scene/accel.h"

namespace igi {

FlushToZeroScope::FlushToZeroScope() : saved_(_mm_getcsr()) { enable_flush_to_zero(); }
FlushToZeroScope::~FlushToZeroScope() { _mm_setcsr(saved_); }

void parallel_tasks(int count, const std::function<void(int)>& task, int threads) {
  if (count <= 0) return;
  auto run = [&] {
    tbb::parallel_for(
        tbb::blocked_range<int>(0, count, 1),
        [&](const tbb::blocked_range<int>& range) {
          FlushToZeroScope flush_to_zero;
          for (int i = range.begin(); i != range.end(); ++i) task(i);
        },
        tbb::simple_partitioner());
  };
  if (threads <= 0) return run();
  tbb::task_arena arena(threads);
  arena.execute(run);
}

void parallel_pair(const std::function<void()>& first, const std::function<void()>& second) {
  tbb::parallel_invoke(
      [&] {
        FlushToZeroScope flush_to_zero;
        first();
      },
      [&] {
        FlushToZeroScope flush_to_zero;
        second();
      });
}

}  // namespace igi
