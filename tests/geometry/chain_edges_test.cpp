#include "knitforge/geometry/chain_edges.h"

#include <gtest/gtest.h>

namespace knitforge {
namespace {

// A path 0-1-2 with two branches 2-3 and 2-8 (node 2 has degree 3), a cycle
// 4-5-6 and an isolated node 7: the open chains first, from the nodes of
// degree != 2 in node order, then the cycle closed on its first node; node 7
// only when isolated nodes are asked for.
TEST(ChainEdges, OpenChainsThenCyclesEveryEdgeOnce) {
  const std::vector<std::pair<int, int>> edges = {{1, 2}, {0, 1}, {2, 3}, {4, 5}, {5, 6}, {6, 4}, {8, 2}};
  const auto paths = chain_edges(9, edges);
  ASSERT_EQ(paths.size(), 4u);
  EXPECT_EQ(paths[0], (std::vector<int>{0, 1, 2}));
  EXPECT_EQ(paths[1], (std::vector<int>{2, 3}));
  EXPECT_EQ(paths[2], (std::vector<int>{2, 8}));
  EXPECT_EQ(paths[3], (std::vector<int>{4, 5, 6, 4}));
  const auto with = chain_edges(9, edges, true);
  ASSERT_EQ(with.size(), 5u);
  EXPECT_EQ(with[3], (std::vector<int>{7}));
  EXPECT_EQ(with[4], paths[3]);
  EXPECT_TRUE(chain_edges(3, {}).empty());
}

}  // namespace
}  // namespace knitforge
