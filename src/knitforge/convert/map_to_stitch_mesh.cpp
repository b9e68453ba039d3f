#include "knitforge/convert/map_to_stitch_mesh.h"

#include <cmath>
#include <memory>
#include <numbers>
#include <numeric>
#include <string>

#include <fmt/core.h>

#include "knitforge/core/stitch_adjacency.h"
#include "knitforge/util/errors.h"
#include "knitforge/util/union_find.h"

namespace knitforge {

namespace {

constexpr uint8_t kInRow = 1;
constexpr uint8_t kInCol = 2;

// Per cell: kInRow / kInCol bits for Collapsed cells (0 for all others).
std::vector<uint8_t> classify_collapsed(const KnittingMap& m) {
  const int R = m.rows, C = m.cols;
  std::vector<uint8_t> kind(static_cast<size_t>(R) * C, 0);
  std::vector<uint8_t> ok(static_cast<size_t>(std::max(R, C)), 0);
  for (int r = 0; r < R; ++r) {
    // A closed row is read as a loop: the scans start with the state the
    // row's other end leaves (its last non-Collapsed cell).
    bool open = false;
    if (m.closed(r)) {
      for (int c = C - 1; c >= 0; --c) {
        if (m.at(r, c) != CellType::Collapsed) {
          open = has_side(m.at(r, c), Side::Right);
          break;
        }
      }
    }
    for (int c = 0; c < C; ++c) {
      const CellType t = m.at(r, c);
      if (t == CellType::Collapsed) {
        ok[c] = open;
      } else {
        open = has_side(t, Side::Right);
      }
    }
    open = false;
    if (m.closed(r)) {
      for (int c = 0; c < C; ++c) {
        if (m.at(r, c) != CellType::Collapsed) {
          open = has_side(m.at(r, c), Side::Left);
          break;
        }
      }
    }
    for (int c = C - 1; c >= 0; --c) {
      const CellType t = m.at(r, c);
      if (t == CellType::Collapsed) {
        if (open && ok[c]) kind[static_cast<size_t>(r) * C + c] |= kInRow;
      } else {
        open = has_side(t, Side::Left);
      }
    }
  }
  for (int c = 0; c < C; ++c) {
    bool open = false;
    for (int r = 0; r < R; ++r) {
      const CellType t = m.at(r, c);
      if (t == CellType::Collapsed) {
        ok[r] = open;
      } else {
        open = has_side(t, Side::Top);
      }
    }
    open = false;
    for (int r = R - 1; r >= 0; --r) {
      const CellType t = m.at(r, c);
      if (t == CellType::Collapsed) {
        if (open && ok[r]) {
          uint8_t& k = kind[static_cast<size_t>(r) * C + c];
          k |= kInCol;
          if (k == (kInRow | kInCol)) {
            throw InvalidInput(fmt::format(
                "knitting map cell (row {}, column {}) is Collapsed but lies both between two stitches of its row "
                "and between two stitches of its column: a course and a wale would cross without a stitch; put a "
                "stitch there or make one of the neighbouring cells Empty",
                r, c));
          }
        }
      } else {
        open = has_side(t, Side::Bottom);
      }
    }
  }
  return kind;
}

// The canonical seam of closed row r: the grid line just after the round's
// last stitch in the row's direction ((last + 1) % cols for +1, the line left
// of the last stitch for -1); seams that differ only by non-stitch cells
// between the round's last and first stitch give the same knitting order.
// stitch_mesh_to_map() reads tubes back with this seam. -1 when none.
int canonical_seam(const KnittingMap& m, int r) {
  if (!m.closed(r)) return -1;
  int last = -1;
  for (int c : row_columns(m, r))
    if (is_stitch(m.at(r, c))) last = c;
  if (last < 0) return -1;
  return m.direction[static_cast<size_t>(r)] > 0 ? (last + 1) % m.cols : last;
}

constexpr const char* kCornerNames[4] = {"bottom-left", "bottom-right", "top-right", "top-left"};

// The grid corners V(i, j) = i * (cols + 1) + j merged cell by cell
// (docs/representations.md).
UnionFind merge_corners(const KnittingMap& map) {
  const int R = map.rows, C = map.cols;
  const std::vector<uint8_t> kind = classify_collapsed(map);
  const int VC = C + 1;
  auto V = [VC](int i, int j) { return i * VC + j; };
  UnionFind uf(static_cast<size_t>(R + 1) * VC);
  for (int r = 0; r < R; ++r) {
    for (int c = 0; c < C; ++c) {
      const int bl = V(r, c), br = V(r, c + 1), tr = V(r + 1, c + 1), tl = V(r + 1, c);
      switch (map.at(r, c)) {
        case CellType::ShortRowLeft: uf.unite(bl, tl); break;
        case CellType::ShortRowRight: uf.unite(br, tr); break;
        case CellType::Increase: uf.unite(bl, br); break;
        case CellType::Decrease: uf.unite(tl, tr); break;
        case CellType::Collapsed: {
          const uint8_t k = kind[static_cast<size_t>(r) * C + c];
          if (k & kInRow) {
            uf.unite(bl, br);
            uf.unite(tl, tr);
          }
          if (k & kInCol) {
            uf.unite(bl, tl);
            uf.unite(br, tr);
          }
          break;
        }
        default: break;
      }
    }
    // A closed row's last column meets its first: the grid line cols is line 0.
    if (map.closed(r)) {
      uf.unite(V(r, C), V(r, 0));
      uf.unite(V(r + 1, C), V(r + 1, 0));
    }
  }
  return uf;
}

}  // namespace

std::vector<int> map_corner_classes(const KnittingMap& map) {
  check_map_arrays(map);
  UnionFind uf = merge_corners(map);
  std::vector<int> out(uf.size());
  for (size_t i = 0; i < out.size(); ++i) out[i] = static_cast<int>(uf.find(static_cast<int>(i)));
  return out;
}

KnittingMap canonical_cells(const KnittingMap& map) {
  check_map_arrays(map);
  const std::vector<uint8_t> kind = classify_collapsed(map);
  KnittingMap out = map;
  for (size_t i = 0; i < out.cells.size(); ++i) {
    if (out.cells[i] == CellType::Collapsed && kind[i] == 0) out.cells[i] = CellType::Empty;
  }
  for (int r = 0; r < out.rows; ++r) {
    if (out.closed(r) && (out.direction[static_cast<size_t>(r)] == 1 || out.direction[static_cast<size_t>(r)] == -1)) {
      const int s = canonical_seam(out, r);
      if (s >= 0) out.seam[static_cast<size_t>(r)] = s;
    }
  }
  return out;
}

StitchMesh map_to_stitch_mesh_topology(const KnittingMap& map, const KnitParams& params) {
  check_map_arrays(map);
  if (!(std::isfinite(params.stitch_width) && params.stitch_width > 0 && std::isfinite(params.stitch_height) &&
        params.stitch_height > 0)) {
    throw InvalidInput(fmt::format("stitch size {} x {} mm: both must be finite and > 0", params.stitch_width,
                                   params.stitch_height));
  }
  const int R = map.rows, C = map.cols;
  if (R == 0 || C == 0) throw InvalidInput("knitting map is empty (no rows or no columns)");

  // Rows: direction, one run of stitches.
  std::vector<int> lo_stitch(R), hi_stitch(R);
  for (int r = 0; r < R; ++r) {
    if (map.direction[r] != 1 && map.direction[r] != -1) {
      throw InvalidInput(fmt::format("knitting map row {} has direction {}; it must be +1 (left to right) or -1",
                                     r, static_cast<int>(map.direction[r])));
    }
    int lo = -1, hi = -1;
    for (int c = 0; c < C; ++c) {
      if (is_stitch(map.at(r, c))) {
        if (lo < 0) lo = c;
        hi = c;
      }
    }
    if (lo < 0) {
      throw InvalidInput(fmt::format("knitting map row {} holds no stitch; every row must hold one course or short "
                                     "row (remove the row)",
                                     r));
    }
    if (map.closed(r)) {
      for (int c = 0; c < C; ++c) {
        const CellType t = map.at(r, c);
        if (t == CellType::Empty || t == CellType::ShortRowLeft || t == CellType::ShortRowRight) {
          throw InvalidInput(fmt::format(
              "knitting map row {} is a closed row (a round of the tube) but cell (row {}, column {}) is {}: a round "
              "holds only knit, increase, decrease and collapsed cells; make the row open (a short row) or fill "
              "the cell",
              r, r, c, name(t)));
        }
      }
      lo_stitch[r] = lo;
      hi_stitch[r] = hi;
      continue;
    }
    for (int c = lo; c <= hi; ++c) {
      const CellType t = map.at(r, c);
      const bool splits = t == CellType::Empty || (c > lo && is_stitch(t) && !has_side(t, Side::Left)) ||
                          (c < hi && is_stitch(t) && !has_side(t, Side::Right));
      if (splits) {
        throw InvalidInput(fmt::format(
            "knitting map row {} holds two separate runs of stitches: cell (row {}, column {}) is {} and splits "
            "the row between columns {} and {}; a map row must hold one course or short row",
            r, r, c, name(t), lo, hi));
      }
    }
    lo_stitch[r] = lo;
    hi_stitch[r] = hi;
  }
  const int VC = C + 1;
  auto V = [VC](int i, int j) { return i * VC + j; };
  UnionFind uf = merge_corners(map);

  StitchMesh mesh;
  mesh.stitches.reserve(static_cast<size_t>(map.num_stitches()));
  std::vector<int> vertex_of_root(uf.size(), -1);
  std::vector<std::pair<int, int>> cell_of_stitch;
  for (int r = 0; r < R; ++r) {
    const int d = map.direction[r];
    for (const int c : row_columns(map, r)) {
      const CellType t = map.at(r, c);
      if (!is_stitch(t)) continue;
      Stitch s;
      s.type = to_stitch_type(t);
      s.direction = static_cast<int8_t>(d);
      s.course = r;
      s.wale = c;
      s.yarn = map.yarn_at(r, c);
      const int grid[4] = {V(r, c), V(r, c + 1), V(r + 1, c + 1), V(r + 1, c)};
      int roots[4];
      for (int q = 0; q < 4; ++q) roots[q] = uf.find(grid[q]);
      for (int q = 0; q < 4; ++q) {
        for (int p = 0; p < q; ++p) {
          // The corner pair a shaping stitch collapses by definition is its apex.
          const bool apex_pair = (s.type == StitchType::ShortRowLeft && p == 0 && q == 3) ||
                                 (s.type == StitchType::ShortRowRight && p == 1 && q == 2) ||
                                 (s.type == StitchType::Increase && p == 0 && q == 1) ||
                                 (s.type == StitchType::Decrease && p == 2 && q == 3);
          if (roots[p] == roots[q] && !apex_pair) {
            throw InvalidInput(fmt::format(
                "knitting map cell (row {}, column {}), a {} stitch, degenerates: its {} and {} corners are merged "
                "by the collapsed or shaping cells around it; check the cells next to it",
                r, c, name(t), kCornerNames[p], kCornerNames[q]));
          }
        }
      }
      int corners[4];
      int n = 0;
      switch (s.type) {
        case StitchType::Knit: corners[0] = roots[0], corners[1] = roots[1], corners[2] = roots[2], corners[3] = roots[3], n = 4; break;
        case StitchType::ShortRowLeft: corners[0] = roots[0], corners[1] = roots[1], corners[2] = roots[2], n = 3; break;
        case StitchType::ShortRowRight: corners[0] = roots[0], corners[1] = roots[1], corners[2] = roots[3], n = 3; break;
        case StitchType::Increase: corners[0] = roots[0], corners[1] = roots[2], corners[2] = roots[3], n = 3; break;
        case StitchType::Decrease: corners[0] = roots[0], corners[1] = roots[1], corners[2] = roots[2], n = 3; break;
      }
      for (int q = 0; q < n; ++q) {
        int& vi = vertex_of_root[corners[q]];
        if (vi < 0) vi = static_cast<int>(mesh.vertices.size()), mesh.vertices.push_back(Vec3::Zero());
        s.v[q] = vi;
      }
      mesh.stitches.push_back(s);
      cell_of_stitch.emplace_back(r, c);
    }
  }
  // Positions: mean of the merged grid corners; a tube's corners lie on a
  // cylinder of circumference cols * stitch_width round the y axis (the front
  // half facing +z), so the wrap's two grid lines are one place.
  std::vector<int> count(mesh.vertices.size(), 0);
  const double radius = C * params.stitch_width / (2 * std::numbers::pi);
  for (int i = 0; i <= R; ++i) {
    for (int j = 0; j <= C; ++j) {
      const int vi = vertex_of_root[uf.find(V(i, j))];
      if (vi < 0) continue;
      if (map.tubular()) {
        const double a = 2 * std::numbers::pi * j / C;
        mesh.vertices[vi] += Vec3(-radius * std::cos(a), i * params.stitch_height, radius * std::sin(a));
      } else {
        mesh.vertices[vi] += Vec3(j * params.stitch_width, i * params.stitch_height, 0);
      }
      ++count[vi];
    }
  }
  for (size_t v = 0; v < mesh.vertices.size(); ++v) mesh.vertices[v] /= count[v];

  std::unique_ptr<StitchAdjacency> adj;
  try {
    adj = std::make_unique<StitchAdjacency>(mesh);
  } catch (const TopologyError& e) {
    std::string msg = fmt::format("knitting map does not give a manifold stitch mesh: {}", e.what());
    // Name the map cells of the faces the message mentions ("face 12",
    // "faces 3 and 7").
    const std::string what = e.what();
    std::string cells;
    auto add_face = [&](size_t f) {
      if (f < cell_of_stitch.size()) {
        cells += fmt::format("{}face {} is cell (row {}, column {})", cells.empty() ? "" : ", ", f,
                             cell_of_stitch[f].first, cell_of_stitch[f].second);
      }
    };
    auto read_number = [&](size_t& i, size_t* out) {
      const size_t b = i;
      size_t v = 0;
      while (i < what.size() && what[i] >= '0' && what[i] <= '9') v = v * 10 + static_cast<size_t>(what[i++] - '0');
      *out = v;
      return i > b;
    };
    for (size_t pos = what.find("face"); pos != std::string::npos; pos = what.find("face", pos + 4)) {
      size_t i = pos + 4;
      if (i < what.size() && what[i] == 's') ++i;
      if (i >= what.size() || what[i] != ' ') continue;
      ++i;
      size_t f = 0;
      if (!read_number(i, &f)) continue;
      add_face(f);
      if (what.compare(i, 5, " and ") == 0) {
        i += 5;
        if (read_number(i, &f)) add_face(f);
      }
    }
    if (!cells.empty()) msg += " (" + cells + ")";
    throw InvalidInput(msg);
  }
  const int S = mesh.num_stitches();
  for (int s = 0; s < S; ++s) {
    for (int k = 0; k < 4; ++k) {
      const Side side = static_cast<Side>(k);
      const int t = adj->neighbor(s, side);
      if (t >= 0 && adj->neighbor_side(s, side) != opposite_side(side)) {
        throw InvalidInput(fmt::format(
            "knitting map cells (row {}, column {}) and (row {}, column {}) become neighbours across sides that "
            "are not opposite; check the collapsed cells around them",
            cell_of_stitch[s].first, cell_of_stitch[s].second, cell_of_stitch[t].first, cell_of_stitch[t].second));
      }
    }
  }

  // Boundary roles.
  const std::vector<uint8_t> kind = classify_collapsed(map);
  std::vector<int> lo_ext(R, -1), hi_ext(R, -1);
  for (int r = 0; r < R; ++r) {
    for (int c = 0; c < C; ++c) {
      const CellType t = map.at(r, c);
      const bool fabric = is_stitch(t) || (t == CellType::Collapsed && kind[static_cast<size_t>(r) * C + c] != 0);
      if (!fabric) continue;
      if (lo_ext[r] < 0) lo_ext[r] = c;
      hi_ext[r] = c;
    }
  }
  for (int s = 0; s < S; ++s) {
    Stitch& st = mesh.stitches[s];
    const int r = st.course, c = st.wale;
    uint8_t roles = 0;
    if (edge_of_side(st.type, Side::Bottom) >= 0 && adj->neighbor(s, Side::Bottom) < 0) roles |= kRoleCastOn;
    if (edge_of_side(st.type, Side::Top) >= 0 && adj->neighbor(s, Side::Top) < 0) roles |= kRoleBindOff;
    if (map.closed_end && r == map.rows - 1) roles |= kRoleClosingSeam;
    if (r > 0 && !map.closed(r) && !map.closed(r - 1)) {
      if (c == lo_stitch[r] && c == lo_ext[r]) {
        if (lo_ext[r] < lo_ext[r - 1]) roles |= kRoleOutsideIncrease;
        if (lo_ext[r] > lo_ext[r - 1]) roles |= kRoleOutsideDecrease;
      }
      if (c == hi_stitch[r] && c == hi_ext[r]) {
        if (hi_ext[r] > hi_ext[r - 1]) roles |= kRoleOutsideIncrease;
        if (hi_ext[r] < hi_ext[r - 1]) roles |= kRoleOutsideDecrease;
      }
    }
    st.roles = roles;
  }
  return mesh;
}

StitchMesh map_to_stitch_mesh(const KnittingMap& map, const KnitParams& params, const RelaxOptions& options) {
  const StitchMesh mesh = map_to_stitch_mesh_topology(map, params);
  return relax_stitch_mesh(mesh, params, options).mesh;
}

}  // namespace knitforge
