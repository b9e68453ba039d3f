#pragma once
/// \file edge_key.h
/// A hash-map key of an undirected mesh edge.

#include <algorithm>
#include <cstdint>

namespace knitforge {

/// The key of the undirected edge {a, b} (vertex indices >= 0): the same
/// for (a, b) and (b, a).
inline std::uint64_t undirected_edge_key(int a, int b) {
  const auto lo = static_cast<std::uint32_t>(std::min(a, b)), hi = static_cast<std::uint32_t>(std::max(a, b));
  return (static_cast<std::uint64_t>(lo) << 32) | hi;
}

}  // namespace knitforge
