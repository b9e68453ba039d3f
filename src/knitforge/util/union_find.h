#pragma once
/// \file union_find.h
/// Disjoint sets over 0..n-1 with path halving. The representative of a set
/// is always its smallest element, so results do not depend on merge order.

#include <algorithm>
#include <numeric>
#include <vector>

namespace knitforge {

class UnionFind {
 public:
  explicit UnionFind(size_t n) : parent_(n) { std::iota(parent_.begin(), parent_.end(), 0); }

  /// The smallest element of a's set.
  int find(int a) {
    while (parent_[a] != a) {
      parent_[a] = parent_[parent_[a]];
      a = parent_[a];
    }
    return a;
  }

  /// Number of elements.
  size_t size() const { return parent_.size(); }

  /// Merges the sets of a and b.
  void unite(int a, int b) {
    a = find(a);
    b = find(b);
    if (a != b) parent_[std::max(a, b)] = std::min(a, b);
  }

 private:
  std::vector<int> parent_;
};

}  // namespace knitforge
