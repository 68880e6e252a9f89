#include "core/parallel.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>
#include <tbb/task_arena.h>
#include <xmmintrin.h>

#include "scene/accel.h"

// ThreadSanitizer cannot see TBB's own synchronisation (libtbb is not built
// with it), so a task's reads of what the caller wrote before the loop, and
// the caller's reads of what the tasks wrote, look like races: suppressed as
// TBB's (tests/sanitizers/tsan.supp), but each one symbolised first, which
// made a 70,000-leaf light tree take more than ten minutes under TSan. The
// hand-offs are declared to it instead: the caller releases before the loop
// and acquires after it, each task acquires at its start and releases at its end.
#if defined(__has_feature)
#if __has_feature(thread_sanitizer)
#define IGI_TSAN 1
#endif
#endif
#if defined(__SANITIZE_THREAD__)
#define IGI_TSAN 1
#endif
#ifdef IGI_TSAN
extern "C" void __tsan_acquire(void* address);
extern "C" void __tsan_release(void* address);
#endif

namespace igi {
namespace {

// The happens-before edges of one parallel loop, for ThreadSanitizer; nothing otherwise.
class HandOff {
 public:
#ifdef IGI_TSAN
  HandOff() { __tsan_release(&start_); }
  ~HandOff() { __tsan_acquire(&end_); }
  // A task's scope: it sees what the caller wrote; the caller sees what it wrote, also when it throws.
  struct Task {
    explicit Task(HandOff& h) : h_(h) { __tsan_acquire(&h_.start_); }
    ~Task() { __tsan_release(&h_.end_); }
    HandOff& h_;
  };

 private:
  char start_ = 0, end_ = 0;
#else
  struct Task {
    explicit Task(HandOff&) {}
  };
#endif
};

}  // namespace

FlushToZeroScope::FlushToZeroScope() : saved_(_mm_getcsr()) { enable_flush_to_zero(); }
FlushToZeroScope::~FlushToZeroScope() { _mm_setcsr(saved_); }

void parallel_tasks(int count, const std::function<void(int)>& task, int threads) {
  if (count <= 0) return;
  HandOff hand_off;
  auto run = [&] {
    tbb::parallel_for(
        tbb::blocked_range<int>(0, count, 1),
        [&](const tbb::blocked_range<int>& range) {
          HandOff::Task seen(hand_off);
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
  HandOff hand_off;
  tbb::parallel_invoke(
      [&] {
        HandOff::Task seen(hand_off);
        FlushToZeroScope flush_to_zero;
        first();
      },
      [&] {
        HandOff::Task seen(hand_off);
        FlushToZeroScope flush_to_zero;
        second();
      });
}

}  // namespace igi
