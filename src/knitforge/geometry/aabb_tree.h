#pragma once
/// \file aabb_tree.h
/// A bounding-volume hierarchy of axis-aligned boxes over items (triangles,
/// swept triangles, segments), for range and nearest queries of moving
/// geometry: built once from the items' boxes by recursive median splits of
/// the box centres along the longest axis (leaves of at most 4 items; ties
/// broken by item index, so the tree is deterministic), then refit() to new
/// boxes of the same items without rebuilding (a body that moves: the tree
/// stays valid, only looser).
///
/// Queries take callables and never allocate:
///  - for_each_overlapping(lo, hi, visit): visit(item) for every item whose
///    box overlaps [lo, hi];
///  - nearest(p, bound2, visit): items in order of increasing box distance
///    from p while their squared box distance is at most the current bound;
///    visit(item, bound2) may lower the bound (the best squared distance so
///    far), pruning the rest.

#include <algorithm>
#include <array>
#include <span>
#include <vector>

#include "knitforge/geometry/vec.h"

namespace knitforge {

struct Aabb {
  Vec3 lo = Vec3::Zero();
  Vec3 hi = Vec3::Zero();
  /// The box of points a, b, c ... (at least one).
  static Aabb of(std::initializer_list<Vec3> points) {
    Aabb b{*points.begin(), *points.begin()};
    for (const Vec3& p : points) b.lo = b.lo.cwiseMin(p), b.hi = b.hi.cwiseMax(p);
    return b;
  }
  Aabb merged(const Aabb& o) const { return {lo.cwiseMin(o.lo), hi.cwiseMax(o.hi)}; }
  Aabb inflated(double r) const { return {lo.array() - r, hi.array() + r}; }
  bool overlaps(const Aabb& o) const { return (lo.array() <= o.hi.array()).all() && (o.lo.array() <= hi.array()).all(); }
  /// Squared distance from p to the box (0 inside).
  double distance2(const Vec3& p) const { return (lo - p).cwiseMax(p - hi).cwiseMax(0.0).squaredNorm(); }
};

class AabbTree {
 public:
  AabbTree() = default;
  /// \pre boxes non-empty, finite.
  explicit AabbTree(std::span<const Aabb> boxes);
  /// New boxes for the same items (same count), same tree.
  void refit(std::span<const Aabb> boxes);

  int num_items() const { return static_cast<int>(items_.size()); }
  bool empty() const { return items_.empty(); }
  /// The box of everything (undefined for an empty tree).
  const Aabb& bounds() const { return nodes_.front().box; }

  template <class Visit>
  void for_each_overlapping(const Aabb& query, Visit&& visit) const {
    if (nodes_.empty()) return;
    int stack[128];
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
      const Node& n = nodes_[stack[--top]];
      if (!n.box.overlaps(query)) continue;
      if (n.left < 0) {
        for (int i = n.first; i < n.first + n.count; ++i) visit(items_[i]);
      } else {
        stack[top++] = n.right;
        stack[top++] = n.left;
      }
    }
  }

  template <class Visit>
  void nearest(const Vec3& p, double bound2, Visit&& visit) const {
    if (nodes_.empty()) return;
    int stack[128];
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
      const Node& n = nodes_[stack[--top]];
      if (n.box.distance2(p) > bound2) continue;
      if (n.left < 0) {
        for (int i = n.first; i < n.first + n.count; ++i) visit(items_[i], bound2);
        continue;
      }
      const double dl = nodes_[n.left].box.distance2(p), dr = nodes_[n.right].box.distance2(p);
      // The nearer child is pushed last, so it is visited first.
      if (dl <= dr) {
        if (dr <= bound2) stack[top++] = n.right;
        if (dl <= bound2) stack[top++] = n.left;
      } else {
        if (dl <= bound2) stack[top++] = n.left;
        if (dr <= bound2) stack[top++] = n.right;
      }
    }
  }

 private:
  struct Node {
    Aabb box;
    int left = -1, right = -1;  ///< children, -1 for a leaf
    int first = 0, count = 0;   ///< leaf: slots in items_
  };
  int build(int first, int count, const std::vector<Vec3>& centres);
  void fit(std::span<const Aabb> boxes);
  std::vector<Node> nodes_;
  std::vector<int> items_;  ///< item index per slot
};

}  // namespace knitforge
