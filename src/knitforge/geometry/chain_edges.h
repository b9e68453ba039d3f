#pragma once
/// \file chain_edges.h
/// Undirected edges between nodes chained into paths: the pieces of a plane
/// section (geodesic_source.h) and the branches of a cut graph
/// (cut_to_disk.h). Deterministic.

#include <utility>
#include <vector>

namespace knitforge {

/// Chains the edges (pairs of nodes in [0, num_nodes)) into paths of nodes,
/// every edge in exactly one path: first the open chains, in node order
/// from every node whose degree is not 2 (one chain per edge still unused
/// there), each running on through nodes of degree 2; then the cycles that
/// remain, in edge order, closed by repeating their first node. With
/// `isolated_nodes`, a node without edges is a path of its own, in node
/// order among the open chains.
/// \pre every node index is in [0, num_nodes) (not checked).
std::vector<std::vector<int>> chain_edges(int num_nodes, const std::vector<std::pair<int, int>>& edges,
                                          bool isolated_nodes = false);

}  // namespace knitforge
