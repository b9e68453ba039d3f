#include "knitforge/util/parallel_ranges.h"

#include <algorithm>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

namespace knitforge {

void parallel_ranges(std::size_t n, std::size_t min_parallel,
                     const std::function<void(std::size_t begin, std::size_t end)>& body) {
  if (n == 0) return;
  if (n < std::max<std::size_t>(min_parallel, 2) || tbb::this_task_arena::max_concurrency() <= 1) {
    body(0, n);
    return;
  }
  const std::size_t grain = std::max<std::size_t>(min_parallel / 2, 1);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, grain),
                    [&](const tbb::blocked_range<std::size_t>& r) { body(r.begin(), r.end()); });
}

}  // namespace knitforge
