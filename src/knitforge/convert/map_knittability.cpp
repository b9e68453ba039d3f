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
    for (int r = 0; r < m_.rows; ++r) check_row(r);
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

  /// Nearest non-Collapsed cells to the left and right are stitches with
  /// facing Right / Left sides.
  bool inside_row(int r, int c) const {
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
    for (int k = 0; k < map.cols; ++k) {
      const int c = map.direction[r] > 0 ? k : map.cols - 1 - k;
      if (is_stitch(map.at(r, c))) cell_of.push_back({r, c});
    }
  }
  if (cell_of.size() != mesh.stitches.size()) {
    throw Error(fmt::format("internal error: the map has {} stitch cells but its mesh {} stitches",
                                   cell_of.size(), mesh.stitches.size()));
  }
  KnittabilityOptions all;
  all.max_violations = std::numeric_limits<int>::max();
  KnittabilityReport rep = check_knittability(mesh, all);
  for (KnittabilityViolation& v : rep.violations) {
    v.cells.clear();
    for (int s : v.stitches) v.cells.push_back(cell_of[s]);
  }
  return make_knittability_report(std::move(rep.violations), opt);
}

}  // namespace knitforge
