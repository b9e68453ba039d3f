#pragma once
// Helpers shared by the convert tests: knitting maps drawn as text and
// knittability checks written independently of the code under test.

#include <string>
#include <vector>

#include "knitforge/convert/map_to_stitch_mesh.h"
#include "knitforge/convert/sample_knitting_map.h"
#include "knitforge/core/knitting_map.h"
#include "knitforge/core/stitch_adjacency.h"
#include "knitforge/util/errors.h"

namespace knitforge::test {

// A map drawn top row first. K knit, L short-row-left, R short-row-right,
// I increase, D decrease, '.' collapsed, '_' empty. Directions alternate,
// row 0 (the last string) left to right.
inline KnittingMap parse_map(const std::vector<std::string>& top_first) {
  const int R = static_cast<int>(top_first.size());
  const int C = R ? static_cast<int>(top_first[0].size()) : 0;
  KnittingMap m(R, C);
  for (int i = 0; i < R; ++i) {
    const std::string& s = top_first[R - 1 - i];
    if (static_cast<int>(s.size()) != C) throw std::logic_error("ragged test map");
    for (int c = 0; c < C; ++c) {
      CellType t = CellType::Empty;
      switch (s[c]) {
        case 'K': t = CellType::Knit; break;
        case 'L': t = CellType::ShortRowLeft; break;
        case 'R': t = CellType::ShortRowRight; break;
        case 'I': t = CellType::Increase; break;
        case 'D': t = CellType::Decrease; break;
        case '.': t = CellType::Collapsed; break;
        case '_': t = CellType::Empty; break;
        default: throw std::logic_error("bad test map character");
      }
      m.at(i, c) = t;
    }
  }
  return m;
}

// A map drawn top row first with arrows for the short-row ends: K knit,
// < short-row-left, > short-row-right, I increase, D decrease, . collapsed,
// space empty. Directions alternate, row 0 (the last string) left to right.
inline KnittingMap make_map(const std::vector<std::string>& top_first) {
  const int rows = static_cast<int>(top_first.size()), cols = static_cast<int>(top_first[0].size());
  KnittingMap m(rows, cols);
  for (int r = 0; r < rows; ++r) {
    const std::string& line = top_first[static_cast<size_t>(rows - 1 - r)];
    for (int c = 0; c < cols; ++c) {
      CellType t = CellType::Empty;
      switch (line[static_cast<size_t>(c)]) {
        case 'K': t = CellType::Knit; break;
        case '<': t = CellType::ShortRowLeft; break;
        case '>': t = CellType::ShortRowRight; break;
        case 'I': t = CellType::Increase; break;
        case 'D': t = CellType::Decrease; break;
        case '.': t = CellType::Collapsed; break;
        default: break;
      }
      m.at(r, c) = t;
    }
  }
  return m;
}

inline std::string draw_map(const KnittingMap& m) {
  static const char kChars[] = "KLRID._";
  std::string out;
  for (int r = m.rows - 1; r >= 0; --r) {
    out += m.direction[r] > 0 ? "> " : "< ";
    for (int c = 0; c < m.cols; ++c) out += kChars[static_cast<int>(m.at(r, c))];
    out += '\n';
  }
  return out;
}

// True when next_stitch() visits the stitches 0, 1, ..., n-1 in that order.
inline bool one_stroke_in_index_order(const StitchMesh& mesh) {
  const StitchAdjacency adj(mesh);
  for (int s = 0; s < mesh.num_stitches(); ++s) {
    const int expect = s + 1 < mesh.num_stitches() ? s + 1 : -1;
    if (adj.next_stitch(s) != expect) return false;
  }
  return true;
}

inline int count_boundary_apexes(const StitchMesh& mesh) {
  const StitchAdjacency adj(mesh);
  int n = 0;
  for (const Stitch& s : mesh.stitches) {
    const int v = apex_vertex(s);
    if (v >= 0 && adj.is_boundary_vertex(v)) ++n;
  }
  return n;
}

// A tube of 16 stitches round, 8 rounds, narrowing to 8 in two decrease
// rounds (3 and 6), seam 0.
inline KnittingMap small_tapered_tube() {
  return tube_knitting_map({.round = 16, .rows = 8, .decrease_rounds = 2, .every = 3});
}

// Eight rows of a tube of 12 columns: rounds 0-1 (seam `seam_before`),
// short rows 2-5 on columns lo[r]..hi[r], rounds 6-7 (seam `seam_after`).
inline KnittingMap tube_with_short_rows(int seam_before, int seam_after, const int (&lo)[8], const int (&hi)[8]) {
  KnittingMap m(8, 12, CellType::Knit);
  m.direction = {1, 1, -1, 1, -1, 1, 1, 1};
  m.seam = {seam_before, seam_before, -1, -1, -1, -1, seam_after, seam_after};
  for (int r = 2; r <= 5; ++r) {
    for (int c = 0; c < 12; ++c)
      if (c < lo[r] || c > hi[r]) m.at(r, c) = CellType::Collapsed;
    m.at(r, lo[r]) = CellType::ShortRowLeft;
    m.at(r, hi[r]) = CellType::ShortRowRight;
  }
  return m;
}

// A round of 12 with a short-row wedge on the back half (a small heel):
// rounds 0-1, short rows 2-5 on columns 8..11 turning two in and back out,
// rounds 6-7. The first short row turns back at the seam where round 1
// ended; the last one ends there and round 6 goes on.
inline KnittingMap heel_tube() {
  return tube_with_short_rows(0, 0, {0, 0, 8, 8, 9, 9, 0, 0}, {11, 11, 11, 10, 10, 11, 11, 11});
}

}  // namespace knitforge::test
