#include "knitforge/util/parallel_ranges.h"

#include <gtest/gtest.h>

#include <mutex>
#include <set>
#include <stdexcept>
#include <thread>
#include <utility>
#include <vector>

namespace knitforge {
namespace {

// Every index is visited exactly once, in contiguous ranges; a large n is
// split, a small one runs as one call on the calling thread.
TEST(ParallelRanges, CoversEveryIndexOnceInContiguousRanges) {
  for (const std::size_t n : {1u, 7u, 100u, 5000u, 100003u}) {
    std::vector<int> seen(n, 0);
    std::mutex m;
    std::set<std::pair<std::size_t, std::size_t>> ranges;
    std::set<std::thread::id> threads;
    parallel_ranges(n, 1000, [&](std::size_t begin, std::size_t end) {
      for (std::size_t i = begin; i < end; ++i) ++seen[i];
      std::lock_guard<std::mutex> lock(m);
      ranges.insert({begin, end});
      threads.insert(std::this_thread::get_id());
    });
    for (std::size_t i = 0; i < n; ++i) ASSERT_EQ(seen[i], 1) << "n " << n << ", index " << i;
    std::size_t next = 0;
    for (const auto& [b, e] : ranges) {
      EXPECT_EQ(b, next);
      EXPECT_LT(b, e);
      next = e;
    }
    EXPECT_EQ(next, n);
    if (n < 1000) {
      EXPECT_EQ(ranges.size(), 1u) << n;
      EXPECT_EQ(*threads.begin(), std::this_thread::get_id());
    } else if (std::thread::hardware_concurrency() > 1) {
      EXPECT_GE(ranges.size(), 2u) << n;
    }
  }
  int calls = 0;
  parallel_ranges(0, 1, [&](std::size_t, std::size_t) { ++calls; });
  EXPECT_EQ(calls, 0);
}

// An exception of a range reaches the caller, as itself.
TEST(ParallelRanges, RethrowsARangesException) {
  EXPECT_THROW(parallel_ranges(10000, 100,
                               [&](std::size_t begin, std::size_t) {
                                 if (begin > 0) throw std::runtime_error("late range");
                               }),
               std::runtime_error);
  EXPECT_THROW(parallel_ranges(5, 100, [](std::size_t, std::size_t) { throw std::logic_error("serial"); }),
               std::logic_error);
}

}  // namespace
}  // namespace knitforge
