#pragma once
// The renderer's one thread pool: TBB's. Every parallel loop in common/ runs
// on it (tiles in frame_renderer, begin_frame's per-set work, photon paths,
// the light tree's build), over independent tasks that each write only their
// own outputs, which the caller combines in task order: a result never
// depends on the thread count nor on which thread ran what. Every task runs
// with flush-to-zero set (Embree asks for it; and begin_frame's work must give
// the same bits whatever the caller's floating-point mode), restored after,
// because TBB's threads run other code too. An exception thrown by a task
// reaches the caller (the first one, once the others have finished).
#include <functional>

namespace igi {

// FTZ/DAZ on the current thread for the scope's life, then the old mode.
class FlushToZeroScope {
 public:
  FlushToZeroScope();
  ~FlushToZeroScope();
  FlushToZeroScope(const FlushToZeroScope&) = delete;
  FlushToZeroScope& operator=(const FlushToZeroScope&) = delete;

 private:
  unsigned saved_;
};

// task(i) for every i in [0, count), one task each, on at most `threads`
// threads (0: as many as TBB runs, one a core); the calling thread takes part.
void parallel_tasks(int count, const std::function<void(int)>& task, int threads = 0);

// first() and second() at once, each with flush-to-zero set.
void parallel_pair(const std::function<void()>& first, const std::function<void()>& second);

}  // namespace igi
