#include "importance/parallel.h"

#include <algorithm>
#include <atomic>
#include <thread>
#include <vector>

#include "scene/accel.h"

namespace igi::importance {

void parallel_tasks(int count, const std::function<void(int)>& task) {
  if (count <= 0) return;
  const int threads = std::clamp(int(std::thread::hardware_concurrency()), 1, count);
  std::atomic<int> next{0};
  std::vector<std::thread> pool;
  for (int t = 0; t < threads; ++t)
    pool.emplace_back([&] {
      enable_flush_to_zero();
      for (int i = next++; i < count; i = next++) task(i);
    });
  for (std::thread& t : pool) t.join();
}

}  // namespace igi::importance
