#pragma once
/// \file counting_sort.h
/// Stable counting sort by a small integer key (a vertex index): the tool
/// for ordering mesh elements by their vertices in linear time. Sorting by
/// the last key first and the first key last (LSD radix) gives the
/// lexicographic order with ties in the original order, the same result as a
/// comparison sort on (keys..., original position).

#include <cstddef>
#include <vector>

namespace knitforge {

/// Reorders `items` stably by key(item), which must lie in [0, n).
template <class T, class Key>
void counting_sort_by(std::vector<T>& items, int n, Key key) {
  std::vector<size_t> start(static_cast<size_t>(n) + 1, 0);
  for (const T& x : items) ++start[static_cast<size_t>(key(x)) + 1];
  for (int i = 0; i < n; ++i) start[i + 1] += start[i];
  std::vector<T> sorted(items.size());
  for (const T& x : items) sorted[start[static_cast<size_t>(key(x))]++] = x;
  items.swap(sorted);
}

}  // namespace knitforge
