#include "knitforge/design/shortrow/order_courses.h"

#include <algorithm>
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

/// Support stitches for the transition e (last of course c) -> f (first of
/// the next course). Appends the new stitches (and vertices) to `mesh` and
/// returns how many were added (0 when the transition cannot be fixed).
int support_transition(StitchMesh& mesh, const StitchAdjacency& adj, const Courses& c, int e, int f,
                       std::vector<int>& new_course) {
  const int cc = c.of[e], dc = c.of[f];
  const int dir = c.direction[cc];
  auto knit = [&](int s) { return s >= 0 && mesh.stitches[s].type == StitchType::Knit; };
  if (!knit(e) || !knit(f) || c.direction[dc] != -dir) return 0;
  const int n0 = mesh.num_stitches();
  const int guard_limit = n0;

  const int top = adj.neighbor(e, Side::Top);
  if (top >= 0 && c.of[top] == dc && top != f) {
    // Extend c: the stitches of d from the one above e back to f, all open below.
    std::vector<int> run;  // from the one next to top (towards f) to f
    int u = top;
    for (int guard = 0; u != f; ++guard) {
      u = adj.previous_in_course(u);
      if (u < 0 || guard > guard_limit || !knit(u) || adj.neighbor(u, Side::Bottom) >= 0) return 0;
      run.push_back(u);
    }
    std::vector<Stitch> added;
    std::vector<Vec3> verts;
    Stitch prev = mesh.stitches[e];
    int next_vertex = mesh.num_vertices();
    for (int s : run) {
      const Stitch& us = mesh.stitches[s];
      Stitch w;
      w.type = StitchType::Knit;
      w.direction = static_cast<int8_t>(dir);
      w.yarn = prev.yarn;
      w.wale = us.wale;  // the column of the stitch it supports
      if (dir > 0) {
        if (prev.v[TR] != us.v[BL]) return 0;
        const Vec3 p = mesh.vertices[prev.v[BR]] + (mesh.vertices[us.v[BR]] - mesh.vertices[us.v[BL]]);
        verts.push_back(p);
        w.v = {prev.v[BR], next_vertex++, us.v[BR], prev.v[TR]};
      } else {
        if (prev.v[TL] != us.v[BR]) return 0;
        const Vec3 p = mesh.vertices[prev.v[BL]] + (mesh.vertices[us.v[BL]] - mesh.vertices[us.v[BR]]);
        verts.push_back(p);
        w.v = {next_vertex++, prev.v[BL], prev.v[TL], us.v[BL]};
      }
      added.push_back(w);
      prev = w;
    }
    mesh.vertices.insert(mesh.vertices.end(), verts.begin(), verts.end());
    mesh.stitches.insert(mesh.stitches.end(), added.begin(), added.end());
    new_course.insert(new_course.end(), added.size(), cc);
    return static_cast<int>(added.size());
  }

  const int below = adj.neighbor(f, Side::Bottom);
  if (top < 0 && below >= 0 && c.of[below] == cc && below != e) {
    // Extend d: the stitches of c after the one below f up to e, all open above.
    std::vector<int> run;
    int v = below;
    for (int guard = 0; v != e; ++guard) {
      v = adj.next_in_course(v);
      if (v < 0 || guard > guard_limit || !knit(v) || adj.neighbor(v, Side::Top) >= 0) return 0;
      run.push_back(v);
    }
    std::vector<Stitch> added;
    std::vector<Vec3> verts;
    Stitch prev = mesh.stitches[f];
    int next_vertex = mesh.num_vertices();
    for (int s : run) {
      const Stitch& vs = mesh.stitches[s];
      Stitch w;
      w.type = StitchType::Knit;
      w.direction = static_cast<int8_t>(-dir);
      w.yarn = prev.yarn;
      w.wale = vs.wale;
      if (dir > 0) {  // e to the right: w right of prev
        if (prev.v[BR] != vs.v[TL]) return 0;
        const Vec3 p = mesh.vertices[prev.v[TR]] + (mesh.vertices[vs.v[TR]] - mesh.vertices[vs.v[TL]]);
        verts.push_back(p);
        w.v = {vs.v[TL], vs.v[TR], next_vertex++, prev.v[TR]};
      } else {  // w left of prev
        if (prev.v[BL] != vs.v[TR]) return 0;
        const Vec3 p = mesh.vertices[prev.v[TL]] + (mesh.vertices[vs.v[TL]] - mesh.vertices[vs.v[TR]]);
        verts.push_back(p);
        w.v = {vs.v[TL], vs.v[TR], prev.v[TL], next_vertex++};
      }
      added.push_back(w);
      prev = w;
    }
    mesh.vertices.insert(mesh.vertices.end(), verts.begin(), verts.end());
    mesh.stitches.insert(mesh.stitches.end(), added.begin(), added.end());
    new_course.insert(new_course.end(), added.size(), dc);
    return static_cast<int>(added.size());
  }
  return 0;
}

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
    for (size_t i = 0; i + 1 < order.size(); ++i) {
      const int e = c.last[order[i]], f = c.first[order[i + 1]];
      if (adj.next_stitch(e) == f) continue;
      const int added = support_transition(mesh, adj, c, e, f, course_of);
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
