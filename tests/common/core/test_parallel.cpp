// The shared pool (core/parallel.h): every task once, on any thread count
// the same outputs, flush-to-zero inside a task and the caller's mode after,
// and a task's exception at the caller instead of std::terminate.
#include <atomic>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>
#include <xmmintrin.h>

#include "core/parallel.h"
#include "sampling/hash.h"

namespace igi {
namespace {

constexpr unsigned kFlushToZero = _MM_FLUSH_ZERO_ON | 0x0040u /* DAZ */;

std::vector<uint32_t> outputs(int threads) {
  std::vector<uint32_t> out(257);
  parallel_tasks(int(out.size()), [&](int i) { out[size_t(i)] = hash(uint32_t(i), 7u); }, threads);
  return out;
}

TEST(Parallel, EveryTaskRunsOnceAndOutputsDoNotDependOnTheThreadCount) {
  std::vector<std::atomic<int>> runs(1000);
  parallel_tasks(int(runs.size()), [&](int i) { ++runs[size_t(i)]; });
  for (const auto& r : runs) ASSERT_EQ(r.load(), 1);
  const std::vector<uint32_t> all = outputs(0);
  EXPECT_EQ(outputs(1), all);
  EXPECT_EQ(outputs(3), all);
  parallel_tasks(0, [](int) { FAIL() << "no task for a count of 0"; });
}

TEST(Parallel, TasksFlushDenormalsToZeroAndTheCallersModeIsKept) {
  const unsigned saved = _mm_getcsr();
  _mm_setcsr(saved & ~kFlushToZero);
  std::atomic<int> flushed{0};
  auto check = [&] { flushed += (_mm_getcsr() & kFlushToZero) == kFlushToZero; };
  parallel_tasks(8, [&](int) { check(); }, 2);
  parallel_pair(check, check);
  EXPECT_EQ(flushed.load(), 10);
  EXPECT_EQ(_mm_getcsr() & kFlushToZero, 0u);  // the calling thread ran tasks too, and got its mode back
  _mm_setcsr(saved);
}

TEST(Parallel, ATasksExceptionReachesTheCaller) {
  EXPECT_THROW(parallel_tasks(16, [](int i) { if (i == 11) throw std::runtime_error("task 11"); }), std::runtime_error);
  EXPECT_THROW(parallel_pair([] {}, [] { throw std::invalid_argument("second"); }), std::invalid_argument);
}

}  // namespace
}  // namespace igi
