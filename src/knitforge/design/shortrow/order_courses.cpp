#include "knitforge/design/shortrow/order_courses.h"

#include <algorithm>
#include <array>
#include <limits>
#include <set>

#include <fmt/format.h>

#include "knitforge/core/stitch_adjacency.h"
#include "knitforge/util/errors.h"
#include "knitforge/util/union_find.h"

namespace knitforge {

namespace {

// Knit corners.
constexpr int BL = 0, BR = 1, TR = 2, TL = 3;

struct Courses {
  std::vector<int> of;           // course id per stitch
  std::vector<int> first, last;  // per course, in knitting order
  std::vector<int> direction;
  int count = 0;
};

Courses flood_courses(const StitchMesh& mesh, const StitchAdjacency& adj) {
  const int n = mesh.num_stitches();
  UnionFind uf(n);
  for (int s = 0; s < n; ++s) {
    const int r = adj.neighbor(s, Side::Right);
    if (r >= 0 && adj.neighbor_side(s, Side::Right) == Side::Left) uf.unite(s, r);
  }
  Courses c;
  c.of.assign(n, -1);
  std::vector<int> id(n, -1);
  for (int s = 0; s < n; ++s) {
    const int root = uf.find(s);
    if (id[root] < 0) {
      id[root] = c.count++;
      c.direction.push_back(mesh.stitches[s].direction);
      c.first.push_back(-1);
      c.last.push_back(-1);
    }
    const int k = id[root];
    c.of[s] = k;
    if (mesh.stitches[s].direction != c.direction[k]) {
      throw InvalidInput(
          fmt::format("course ordering: stitch {} is knitted in direction {} but lies in one course with "
                      "stitches knitted "
                      "in direction {}; the tessellation is inconsistent",
                      s, static_cast<int>(mesh.stitches[s].direction), c.direction[k]));
    }
    if (adj.previous_in_course(s) < 0 && c.first[k] < 0) c.first[k] = s;
    if (adj.next_in_course(s) < 0 && c.last[k] < 0) c.last[k] = s;
  }
  for (int k = 0; k < c.count; ++k) {
    if (c.first[k] < 0 || c.last[k] < 0) {
      throw InvalidInput(fmt::format("course ordering: course {} closes on itself (a ring of stitches)", k));
    }
  }
  return c;
}

/// Greedy topological order of the courses (see the header).
std::vector<int> greedy_order(const StitchMesh& mesh, const StitchAdjacency& adj, const Courses& c,
                              int& cyclic_edges) {
  const int n = mesh.num_stitches();
  std::vector<std::set<int>> succ(c.count);
  std::vector<int> indegree(c.count, 0);
  for (int s = 0; s < n; ++s) {
    const int t = adj.neighbor(s, Side::Top);
    if (t < 0 || c.of[t] == c.of[s]) continue;
    if (succ[c.of[s]].insert(c.of[t]).second) ++indegree[c.of[t]];
  }
  std::vector<Vec3> centre(n);
  for (int s = 0; s < n; ++s) centre[s] = stitch_centroid(mesh, s);

  std::set<int> ready;
  for (int k = 0; k < c.count; ++k) {
    if (indegree[k] == 0) ready.insert(k);
  }
  std::vector<int> order;
  std::vector<char> placed(c.count, 0);
  int current = -1;
  while (static_cast<int>(order.size()) < c.count) {
    if (ready.empty()) {
      // A cycle: take the unplaced course with the smallest id and count the
      // edges into it from unplaced courses.
      int k = 0;
      while (placed[k]) ++k;
      ready.insert(k);
      for (int j = 0; j < c.count; ++j) {
        if (!placed[j] && succ[j].count(k)) ++cyclic_edges;
      }
    }
    int next = -1;
    if (current < 0) {
      for (int k : ready) {
        if (c.direction[k] > 0) {
          next = k;
          break;
        }
      }
      if (next < 0) next = *ready.begin();
    } else {
      const int e = c.last[current];
      const int straight = adj.next_stitch(e);
      if (straight >= 0 && ready.count(c.of[straight]) && c.first[c.of[straight]] == straight) {
        next = c.of[straight];
      } else {
        double best = std::numeric_limits<double>::infinity();
        for (int k : ready) {
          const double d = (centre[c.first[k]] - centre[e]).squaredNorm();
          if (d < best) {
            best = d;
            next = k;
          }
        }
      }
    }
    ready.erase(next);
    placed[next] = 1;
    order.push_back(next);
    current = next;
    for (int k : succ[next]) {
      if (--indegree[k] == 0 && !placed[k]) ready.insert(k);
    }
  }
  return order;
}

/// Map-space state for the support stitches: every stitch sits in the cell
/// (row = position of its course in the order, column = Stitch::wale); the
/// support stitches of a transition fill free cells of the row of one of the
/// two courses (seed §3.2.3, Fig. 3.5(b): "a few support stitches as
/// accessory" in the next course, or under it in the previous one).
class Supporter {
 public:
  Supporter(StitchMesh& mesh, const StitchAdjacency& adj, const std::vector<int>& course_of,
            const std::vector<int>& position, int num_rows)
      : mesh_(mesh), course_of_(course_of) {
    const int n = mesh.num_stitches();
    int hi = -1;
    usable_ = true;
    for (const Stitch& st : mesh.stitches) {
      if (st.wale < 0) usable_ = false;
      hi = std::max(hi, st.wale);
    }
    nb_.assign(n, {-1, -1, -1, -1});
    row_.assign(n, -1);
    for (int s = 0; s < n; ++s) {
      for (int k = 0; k < 4; ++k) nb_[s][k] = adj.neighbor(s, static_cast<Side>(k));
      row_[s] = position[course_of[s]];
    }
    if (!usable_) return;
    rows_ = num_rows;
    cols_ = hi + 1;
    cell_.assign(static_cast<size_t>(rows_) * cols_, -1);
    through_.assign(cell_.size(), 0);
    for (int s = 0; s < n && usable_; ++s) {
      int& c = cell_[index(row_[s], mesh.stitches[s].wale)];
      if (c >= 0) usable_ = false;  // two stitches in one cell: the wale labels cannot be columns
      c = s;
    }
    for (int s = 0; s < n && usable_; ++s) {
      const int k = mesh.stitches[s].wale;
      const int top = nb_[s][static_cast<int>(Side::Top)];
      if (top >= 0) {
        if (mesh.stitches[top].wale != k || row_[top] <= row_[s]) usable_ = false;
        for (int r = row_[s] + 1; usable_ && r < row_[top]; ++r) through_[index(r, k)] = 1;
      }
      const int right = nb_[s][static_cast<int>(Side::Right)];
      if (right >= 0) {
        if (mesh.stitches[right].wale <= k) usable_ = false;
        for (int c = k + 1; usable_ && c < mesh.stitches[right].wale; ++c) through_[index(row_[s], c)] = 1;
      }
    }
  }

  bool usable() const { return usable_; }

  /// Support stitches that make the last stitch e of course c (knitted in
  /// direction dir) continue into the first stitch f of the next course d.
  /// Returns the number added (0 when no valid support exists).
  int support(int e, int f, int dir, std::vector<int>& new_course) {
    if (!usable_) return 0;
    const Stitch& se = mesh_.stitches[e];
    const Stitch& sf = mesh_.stitches[f];
    if (sf.direction != -dir || row_[f] != row_[e] + 1) return 0;
    const int ke = se.wale, kf = sf.wale;
    if (ke == kf) return 0;
    // d reaches beyond e on the side where c ends: c is continued under d
    // (new stitches in c's row, from e outwards to below f); otherwise d is
    // started above e (new stitches in d's row, from f outwards to above e).
    const bool extend_c = dir > 0 ? kf > ke : kf < ke;
    const int anchor = extend_c ? e : f;
    const int row = extend_c ? row_[e] : row_[f];
    const int k0 = mesh_.stitches[anchor].wale;
    const int k1 = extend_c ? kf : ke;  // column of the last new stitch
    const int sigma = k1 > k0 ? 1 : -1;  // chain direction in the map
    const int cc = course_of_[anchor];
    const int8_t course_dir = mesh_.stitches[anchor].direction;
    const Side out_side = sigma > 0 ? Side::Right : Side::Left;
    const Side in_side = sigma > 0 ? Side::Left : Side::Right;
    if (side_vertices(anchor, out_side).first < 0 || nb_[anchor][static_cast<int>(out_side)] >= 0) return 0;

    const Vec3 wvec = across(anchor, Side::Left, Side::Right);
    const Vec3 hvec = across(anchor, Side::Bottom, Side::Top);
    std::vector<Stitch> added;
    std::vector<Vec3> new_positions;
    std::vector<std::array<int, 4>> added_nb;
    const int n0 = mesh_.num_stitches();
    const int v0 = mesh_.num_vertices();
    auto position = [&](int v) -> const Vec3& { return v < v0 ? mesh_.vertices[v] : new_positions[v - v0]; };
    int prev = anchor;
    for (int k = k0 + sigma;; k += sigma) {
      if (k < 0 || k >= cols_ || cell_[index(row, k)] >= 0 || through_[index(row, k)]) return 0;
      std::array<int, 4> corner = {-1, -1, -1, -1};  // BL BR TR TL
      std::array<int, 4> w_nb = {-1, -1, -1, -1};
      auto assign = [&](int c, int v) {
        if (corner[c] >= 0 && corner[c] != v) return false;
        corner[c] = v;
        return true;
      };
      // Horizontal: the previous stitch of the chain.
      {
        const auto [a, b] = prev < n0 ? side_vertices(prev, out_side) : new_side(added[prev - n0], out_side);
        if (a < 0) return 0;
        const bool ok = sigma > 0 ? assign(BL, a) && assign(TL, b) : assign(TR, a) && assign(BR, b);
        if (!ok) return 0;
        w_nb[static_cast<int>(in_side)] = prev;
      }
      // Vertical: whatever the map puts right below and right above.
      const int below = row > 0 ? cell_[index(row - 1, k)] : -1;
      const int above = row + 1 < rows_ ? cell_[index(row + 1, k)] : -1;
      if (below >= 0) {
        const auto [a, b] = side_vertices(below, Side::Top);
        if (a < 0 || nb_[below][static_cast<int>(Side::Top)] >= 0) return 0;
        if (!assign(BR, a) || !assign(BL, b)) return 0;
        w_nb[static_cast<int>(Side::Bottom)] = below;
      }
      if (above >= 0) {
        const auto [a, b] = side_vertices(above, Side::Bottom);
        if (a < 0 || nb_[above][static_cast<int>(Side::Bottom)] >= 0) return 0;
        if (!assign(TL, a) || !assign(TR, b)) return 0;
        w_nb[static_cast<int>(Side::Top)] = above;
      }
      const bool last = k == k1;
      if (last) {
        // The transition itself: e below the new first stitch of d, or f
        // above the new last stitch of c.
        if (extend_c ? above != f : below != e) return 0;
      }
      // New corners: translated copies (a parallelogram on its neighbours).
      std::array<Vec3, 4> p;
      std::array<char, 4> known{};
      for (int c = 0; c < 4; ++c) {
        if (corner[c] >= 0) {
          p[c] = position(corner[c]);
          known[c] = 1;
        }
      }
      for (int pass = 0; pass < 3; ++pass) {
        const std::array<std::pair<int, int>, 4> horiz = {{{BL, BR}, {TL, TR}, {BR, BL}, {TR, TL}}};
        for (const auto& [from, to] : horiz) {
          if (known[from] && !known[to]) {
            p[to] = p[from] + ((to == BR || to == TR) ? wvec : Vec3(-wvec));
            known[to] = 1;
          }
        }
        const std::array<std::pair<int, int>, 4> vert = {{{BL, TL}, {BR, TR}, {TL, BL}, {TR, BR}}};
        for (const auto& [from, to] : vert) {
          if (known[from] && !known[to]) {
            p[to] = p[from] + ((to == TL || to == TR) ? hvec : Vec3(-hvec));
            known[to] = 1;
          }
        }
      }
      for (int c = 0; c < 4; ++c) {
        if (corner[c] < 0) {
          corner[c] = v0 + static_cast<int>(new_positions.size());
          new_positions.push_back(p[c]);
        }
      }
      Stitch w;
      w.type = StitchType::Knit;
      w.direction = course_dir;
      w.yarn = mesh_.stitches[anchor].yarn;
      w.wale = k;
      w.v = {corner[0], corner[1], corner[2], corner[3]};
      added.push_back(w);
      added_nb.push_back(w_nb);
      prev = n0 + static_cast<int>(added.size()) - 1;
      if (last) break;
    }
    // Commit.
    mesh_.vertices.insert(mesh_.vertices.end(), new_positions.begin(), new_positions.end());
    for (size_t j = 0; j < added.size(); ++j) {
      const int id = n0 + static_cast<int>(j);
      mesh_.stitches.push_back(added[j]);
      nb_.push_back(added_nb[j]);
      row_.push_back(row);
      new_course.push_back(cc);
      cell_[index(row, added[j].wale)] = id;
      for (int k = 0; k < 4; ++k) {
        const int other = added_nb[j][k];
        if (other >= 0 && other < n0) nb_[other][static_cast<int>(opposite_side(static_cast<Side>(k)))] = id;
      }
    }
    return static_cast<int>(added.size());
  }

 private:
  size_t index(int r, int c) const { return static_cast<size_t>(r) * cols_ + c; }

  /// The two vertices of side `side` of stitch s in counter-clockwise order,
  /// {-1, -1} when its type has no such side.
  std::pair<int, int> side_vertices(int s, Side side) const { return new_side(mesh_.stitches[s], side); }
  static std::pair<int, int> new_side(const Stitch& st, Side side) {
    const int k = edge_of_side(st.type, side);
    if (k < 0) return {-1, -1};
    return {st.v[k], st.v[(k + 1) % st.corners()]};
  }

  /// From the middle of side `from` (or the apex when missing) to the middle of side `to`.
  Vec3 across(int s, Side from, Side to) const {
    auto mid = [&](Side side) {
      const auto [a, b] = side_vertices(s, side);
      if (a < 0) return Vec3(mesh_.vertices[mesh_.stitches[s].v[apex_corner(mesh_.stitches[s].type)]]);
      return Vec3(0.5 * (mesh_.vertices[a] + mesh_.vertices[b]));
    };
    return mid(to) - mid(from);
  }

  StitchMesh& mesh_;
  const std::vector<int>& course_of_;
  std::vector<std::array<int, 4>> nb_;
  std::vector<int> row_;
  int rows_ = 0, cols_ = 0;
  std::vector<int> cell_;
  std::vector<char> through_;
  bool usable_ = false;
};

}  // namespace

CourseOrder order_courses(StitchMesh& mesh) {
  CourseOrder out;
  if (mesh.stitches.empty()) return out;
  std::vector<int> order, course_of;
  {
    const StitchAdjacency adj(mesh);
    const Courses c = flood_courses(mesh, adj);
    order = greedy_order(mesh, adj, c, out.cyclic_edges);
    course_of = c.of;
    std::vector<int> position(c.count);
    for (size_t i = 0; i < order.size(); ++i) position[order[i]] = static_cast<int>(i);
    Supporter supporter(mesh, adj, c.of, position, c.count);
    for (size_t i = 0; i + 1 < order.size(); ++i) {
      const int e = c.last[order[i]], f = c.first[order[i + 1]];
      if (adj.next_stitch(e) == f) continue;
      const int added = supporter.support(e, f, c.direction[order[i]], course_of);
      if (added > 0) {
        out.support_stitches += added;
        ++out.fixed_breaks;
      }
    }
    out.num_courses = c.count;
  }
  std::vector<int> position(out.num_courses);
  for (size_t i = 0; i < order.size(); ++i) position[order[i]] = static_cast<int>(i);
  for (int s = 0; s < mesh.num_stitches(); ++s) mesh.stitches[s].course = position[course_of[s]];

  // What is still broken, in the final mesh.
  const StitchAdjacency adj(mesh);
  std::vector<int> first(out.num_courses, -1), last(out.num_courses, -1);
  for (int s = 0; s < mesh.num_stitches(); ++s) {
    const int k = mesh.stitches[s].course;
    if (adj.previous_in_course(s) < 0 && first[k] < 0) first[k] = s;
    if (adj.next_in_course(s) < 0 && last[k] < 0) last[k] = s;
  }
  for (int k = 0; k + 1 < out.num_courses; ++k) {
    if (adj.next_stitch(last[k]) != first[k + 1]) out.breaks.emplace_back(last[k], first[k + 1]);
  }
  return out;
}

}  // namespace knitforge
