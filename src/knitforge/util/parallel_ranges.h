#pragma once
/// \file parallel_ranges.h
/// Work split over the machine's hardware threads (oneTBB's pool), with
/// results that do not depend on the split: body(begin, end) is called on
/// contiguous ranges that cover [0, n) once, concurrently. A body that
/// writes only the entries of its own indices (and reads shared data) gives
/// the same bits as a serial loop; sums over the indices are then taken by
/// the caller, in index order.

#include <cstddef>
#include <functional>

namespace knitforge {

/// Calls body over [0, n) as above: one call body(0, n) on the calling thread
/// when n < min_parallel or the machine has one hardware thread; else ranges
/// of at least min_parallel / 4 indices, as TBB's partitioner splits [0, n)
/// to balance them over its threads. An exception thrown by a range is
/// rethrown here (the ranges not yet started are then skipped).
void parallel_ranges(std::size_t n, std::size_t min_parallel,
                     const std::function<void(std::size_t begin, std::size_t end)>& body);

}  // namespace knitforge
