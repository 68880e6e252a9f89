#pragma once
// Per-frame work split into independent tasks (one per VPL set, or per chunk
// of estimate paths) on threads of its own, so begin_frame() does not leave a
// many-core worker idle. Each task writes only its own outputs, which the
// caller combines in task order: the result never depends on the thread
// count. Every task runs on a spawned thread with flush-to-zero set (as the
// render threads do), whatever the caller's floating-point mode.
#include <functional>

namespace igi::importance {

void parallel_tasks(int count, const std::function<void(int)>& task);

}  // namespace igi::importance
