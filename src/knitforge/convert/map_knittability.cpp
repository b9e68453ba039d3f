#include "knitforge/convert/map_knittability.h"

#include <fmt/core.h>

#include <cmath>
#include <limits>

#include "knitforge/convert/map_to_stitch_mesh.h"
#include "knitforge/util/errors.h"

namespace knitforge {

namespace {

void check_structure(const KnittingMap& m, const KnitParams& params) {
  check_map_arrays(m);
  if (!(params.stitch_width > 0 && std::isfinite(params.stitch_width)) ||
      !(params.stitch_height > 0 && std::isfinite(params.stitch_height))) {
    throw InvalidInput(fmt::format("stitch size {} x {} mm: both must be positive and finite", params.stitch_width,
                                   params.stitch_height));
  }
}

class MapChecker {
 public:
  MapChecker(const KnittingMap& m, const KnitParams& p) : m_(m), p_(p) {}

  std::vector<KnittabilityViolation> run() {
    if (m_.tubular()) check_tube();
    for (int r = 0; r < m_.rows; ++r) {
      if (m_.closed(r)) check_closed_row(r);
      else check_row(r);
    }
    for (int r = 0; r < m_.rows; ++r) {
      for (int c = 0; c < m_.cols; ++c) {
        if (m_.yarn_at(r, c) < 0) {
          add(KnitRule::InvalidYarn, {{r, c}},
              fmt::format("cell (row {}, column {}) has yarn index {}; yarn indices must be >= 0", r, c,
                          m_.yarn_at(r, c)));
        }
        if (m_.at(r, c) == CellType::Collapsed && inside_row(r, c) && inside_column(r, c)) {
          add(KnitRule::CollapsedCrossing, {{r, c}},
              fmt::format("collapsed cell (row {}, column {}) lies inside both its row and its column: a course "
                          "and a wale would cross without a stitch; make it a stitch or end the row or the wale",
                          r, c));
        }
      }
    }
    return std::move(out_);
  }

 private:
  Vec3 centre(const GridCell& g) const {
    const double col = g.col < 0 ? 0.5 * m_.cols - 0.5 : g.col;
    return {(col + 0.5) * p_.stitch_width, (g.row + 0.5) * p_.stitch_height, 0};
  }

  void add(KnitRule rule, std::vector<GridCell> cells, std::string message) {
    KnittabilityViolation v;
    v.rule = rule;
    v.severity = rule_severity(rule);
    for (const GridCell& g : cells) v.position += centre(g);
    v.position /= static_cast<double>(cells.size());
    v.cells = std::move(cells);
    v.message = std::move(message);
    out_.push_back(std::move(v));
  }

  void check_row(int r) {
    if (m_.direction[r] != 1 && m_.direction[r] != -1) {
      add(KnitRule::InvalidDirection, {{r, -1}},
          fmt::format("row {} has direction {}; it must be +1 (left to right) or -1 (right to left)", r,
                      static_cast<int>(m_.direction[r])));
    }
    int prev = -1;
    bool gap = false;
    for (int c = 0; c < m_.cols; ++c) {
      const CellType t = m_.at(r, c);
      if (t == CellType::Empty) gap = true;
      if (!is_stitch(t)) continue;
      if (prev >= 0) {
        const CellType a = m_.at(r, prev);
        if (gap || !has_side(a, Side::Right) || !has_side(t, Side::Left)) {
          std::string why = gap ? "empty cells lie between them"
                                : fmt::format("a {} cannot continue the course to its {}",
                                              !has_side(a, Side::Right) ? name(a) : name(t),
                                              !has_side(a, Side::Right) ? "right" : "left");
          add(KnitRule::SplitRow, {{r, prev}, {r, c}},
              fmt::format("row {} is split between columns {} and {} ({}); every map row must be one course or "
                          "short row, so move the second run to a row of its own",
                          r, prev, c, why));
        }
      }
      prev = c;
      gap = false;
    }
    if (prev < 0) {
      add(KnitRule::EmptyRow, {{r, -1}},
          fmt::format("row {} holds no stitch; remove the row (every map row is a course knitted in turn)", r));
    }
  }

  // Tubes (docs/tubes.md): the layout of the columns, the first and last
  // rows, and the shaping a round can do.
  void check_tube() {
    const int C = m_.cols, h = m_.tube_half();
    if (C < 4 || C % 2 != 0) {
      add(KnitRule::TubeLayout, {{0, -1}},
          fmt::format("the tube has {} columns; a tube needs an even number, at least 4 (columns 0..n/2-1 the "
                      "front half, n/2..n-1 the back half)",
                      C));
      return;
    }
    if (m_.rows > 0 && !m_.closed(0))
      add(KnitRule::TubeLayout, {{0, -1}},
          "row 0 of the tube is open: a tube starts with a round (its cast-on goes round both beds); give row 0 a "
          "seam");
    if (m_.rows > 0 && !m_.closed(m_.rows - 1))
      add(KnitRule::TubeLayout, {{m_.rows - 1, -1}},
          fmt::format("the last row ({}) of the tube is open: a tube ends with a round (its bind-off goes round both "
                      "beds); give it a seam",
                      m_.rows - 1));
    if (m_.closed_end && m_.rows > 0 && m_.closed(m_.rows - 1) && closing_pairs(m_).empty())
      add(KnitRule::TubeLayout, {{m_.rows - 1, -1}},
          fmt::format("the tube is closed after its last row ({}), whose halves hold different numbers of stitches: "
                      "the closing seam joins each front loop with the back loop opposite it, so give both halves "
                      "the same count (or leave the tube open)",
                      m_.rows - 1));
    for (int r = 0; r < m_.rows; ++r) {
      int lo = -1, hi = -1, front = 0, back = 0;
      for (int c = 0; c < C; ++c) {
        if (!is_stitch(m_.at(r, c))) continue;
        if (lo < 0) lo = c;
        hi = c;
        (c < h ? front : back) += 1;
      }
      if (m_.closed(r) && (front < 2 || back < 2)) {
        add(KnitRule::TubeShaping, {{r, -1}},
            fmt::format("round {} holds {} stitch(es) on the front half and {} on the back half; each half of a "
                        "round keeps at least 2, so that a decrease has a neighbour on its bed to be moved onto",
                        r, front, back));
      }
      if (!m_.closed(r) && lo == 0 && hi == C - 1) {
        add(KnitRule::TubeShaping, {{r, 0}, {r, C - 1}},
            fmt::format("open row {} of the tube runs over the whole round (columns 0 to {}): a short row in a tube "
                        "covers part of the round and leaves the other wales held; make it a round (give it a seam) "
                        "or hold a wale",
                        r, C - 1));
      }
    }
  }
  void check_closed_row(int r) {
    if (m_.direction[r] != 1 && m_.direction[r] != -1) {
      add(KnitRule::InvalidDirection, {{r, -1}},
          fmt::format("row {} has direction {}; it must be +1 (left to right) or -1 (right to left)", r,
                      static_cast<int>(m_.direction[r])));
    }
    bool any = false;
    for (int c = 0; c < m_.cols; ++c) {
      const CellType t = m_.at(r, c);
      any = any || is_stitch(t);
      if (t == CellType::Empty || t == CellType::ShortRowLeft || t == CellType::ShortRowRight) {
        add(KnitRule::ClosedRow, {{r, c}},
            fmt::format("cell (row {}, column {}) is {} but row {} is a round of the tube (closed, seam {}): a round "
                        "knits every wale of the tube, so it holds only knit, increase, decrease and collapsed "
                        "cells; make the row open (seam -) for a short row",
                        r, c, name(t), r, m_.seam[static_cast<size_t>(r)]));
      }
    }
    if (!any) {
      add(KnitRule::EmptyRow, {{r, -1}},
          fmt::format("row {} holds no stitch; remove the row (every map row is a course knitted in turn)", r));
    }
  }
  /// Nearest non-Collapsed cells to the left and right are stitches with
  /// facing Right / Left sides (cyclically in a closed row).
  bool inside_row(int r, int c) const {
    if (m_.closed(r)) {
      int l = c, rr = c;
      for (int k = 1; k < m_.cols; ++k) {
        l = (l - 1 + m_.cols) % m_.cols;
        if (m_.at(r, l) != CellType::Collapsed) break;
      }
      for (int k = 1; k < m_.cols; ++k) {
        rr = (rr + 1) % m_.cols;
        if (m_.at(r, rr) != CellType::Collapsed) break;
      }
      return has_side(m_.at(r, l), Side::Right) && has_side(m_.at(r, rr), Side::Left);
    }
    int l = c - 1, rr = c + 1;
    while (l >= 0 && m_.at(r, l) == CellType::Collapsed) --l;
    while (rr < m_.cols && m_.at(r, rr) == CellType::Collapsed) ++rr;
    return l >= 0 && rr < m_.cols && has_side(m_.at(r, l), Side::Right) && has_side(m_.at(r, rr), Side::Left);
  }

  bool inside_column(int r, int c) const {
    int d = r - 1, u = r + 1;
    while (d >= 0 && m_.at(d, c) == CellType::Collapsed) --d;
    while (u < m_.rows && m_.at(u, c) == CellType::Collapsed) ++u;
    return d >= 0 && u < m_.rows && has_side(m_.at(d, c), Side::Top) && has_side(m_.at(u, c), Side::Bottom);
  }

  const KnittingMap& m_;
  const KnitParams& p_;
  std::vector<KnittabilityViolation> out_;
};

}  // namespace

KnittabilityReport check_knittability(const KnittingMap& map, const KnitParams& params,
                                      const KnittabilityOptions& opt) {
  check_structure(map, params);
  if (opt.max_violations < 0) {
    throw InvalidInput(fmt::format("KnittabilityOptions::max_violations is {}; it must be >= 0", opt.max_violations));
  }
  std::vector<KnittabilityViolation> found = MapChecker(map, params).run();
  if (!found.empty()) return make_knittability_report(std::move(found), opt);

  StitchMesh mesh;
  try {
    mesh = map_to_stitch_mesh_topology(map, params);
  } catch (const Error& e) {
    KnittabilityViolation v;
    v.rule = KnitRule::MapTopology;
    v.message = fmt::format("the map's cells do not form a valid stitch mesh: {}", e.what());
    found.push_back(std::move(v));
    return make_knittability_report(std::move(found), opt);
  }
  // Stitches are numbered in knitting order: row by row, each in its direction.
  std::vector<GridCell> cell_of;
  cell_of.reserve(mesh.stitches.size());
  for (int r = 0; r < map.rows; ++r) {
    for (const int c : row_columns(map, r)) {
      if (is_stitch(map.at(r, c))) cell_of.push_back({r, c});
    }
  }
  if (cell_of.size() != mesh.stitches.size()) {
    throw Error(fmt::format("internal error: the map has {} stitch cells but its mesh {} stitches",
                                   cell_of.size(), mesh.stitches.size()));
  }
  KnittabilityOptions all;
  all.max_violations = std::numeric_limits<int>::max();
  all.closed_courses = map.tubular();
  KnittabilityReport rep = check_knittability(mesh, all);
  for (KnittabilityViolation& v : rep.violations) {
    v.cells.clear();
    for (int s : v.stitches) v.cells.push_back(cell_of[s]);
  }
  return make_knittability_report(std::move(rep.violations), opt);
}

}  // namespace knitforge
