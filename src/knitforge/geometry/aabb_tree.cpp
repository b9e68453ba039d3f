#include "knitforge/geometry/aabb_tree.h"

#include <numeric>

#include <fmt/core.h>

#include "knitforge/util/errors.h"

namespace knitforge {

namespace {
constexpr int kLeafSize = 4;
}

AabbTree::AabbTree(std::span<const Aabb> boxes) {
  if (boxes.empty()) throw InvalidInput("AABB tree: no items");
  std::vector<Vec3> centres(boxes.size());
  for (size_t i = 0; i < boxes.size(); ++i) {
    if (!boxes[i].lo.allFinite() || !boxes[i].hi.allFinite()) {
      throw InvalidInput(fmt::format("AABB tree: item {} has a non-finite box", i));
    }
    centres[i] = 0.5 * (boxes[i].lo + boxes[i].hi);
  }
  items_.resize(boxes.size());
  std::iota(items_.begin(), items_.end(), 0);
  nodes_.reserve(2 * boxes.size() / kLeafSize + 2);
  build(0, static_cast<int>(boxes.size()), centres);
  fit(boxes);
}

int AabbTree::build(int first, int count, const std::vector<Vec3>& centres) {
  const int id = static_cast<int>(nodes_.size());
  nodes_.push_back(Node{});
  nodes_[id].first = first;
  nodes_[id].count = count;
  if (count <= kLeafSize) return id;
  Vec3 lo = centres[items_[first]], hi = lo;
  for (int i = first; i < first + count; ++i) lo = lo.cwiseMin(centres[items_[i]]), hi = hi.cwiseMax(centres[items_[i]]);
  int axis = 0;
  (hi - lo).maxCoeff(&axis);
  const int mid = first + count / 2;
  std::nth_element(items_.begin() + first, items_.begin() + mid, items_.begin() + first + count, [&](int a, int b) {
    const double ca = centres[a][axis], cb = centres[b][axis];
    return ca < cb || (ca == cb && a < b);
  });
  const int left = build(first, mid - first, centres);
  const int right = build(mid, first + count - mid, centres);
  nodes_[id].left = left;
  nodes_[id].right = right;
  return id;
}

// Children have larger indices than their parents: fill bottom-up.
void AabbTree::fit(std::span<const Aabb> boxes) {
  for (int n = static_cast<int>(nodes_.size()) - 1; n >= 0; --n) {
    Node& node = nodes_[n];
    if (node.left < 0) {
      node.box = boxes[items_[node.first]];
      for (int i = node.first + 1; i < node.first + node.count; ++i) node.box = node.box.merged(boxes[items_[i]]);
    } else {
      node.box = nodes_[node.left].box.merged(nodes_[node.right].box);
    }
  }
}

void AabbTree::refit(std::span<const Aabb> boxes) {
  if (boxes.size() != items_.size()) {
    throw InvalidInput(fmt::format("AABB tree: refit with {} boxes for {} items", boxes.size(), items_.size()));
  }
  for (size_t i = 0; i < boxes.size(); ++i) {
    if (!boxes[i].lo.allFinite() || !boxes[i].hi.allFinite()) {
      throw InvalidInput(fmt::format("AABB tree: item {} has a non-finite box", i));
    }
  }
  fit(boxes);
}

}  // namespace knitforge
