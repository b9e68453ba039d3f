#include "knitforge/geometry/surface_checks.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <tuple>

#include <Eigen/Geometry>
#include <fmt/core.h>

#include "knitforge/geometry/halfedges.h"
#include "knitforge/util/counting_sort.h"
#include "knitforge/util/errors.h"
#include "knitforge/util/union_find.h"

namespace knitforge {

namespace {

void add(SurfaceReport& r, SurfaceIssue issue) {
  if (issue.is_error) {
    ++r.num_errors;
  } else {
    ++r.num_warnings;
  }
  r.issues.push_back(std::move(issue));
}

std::string face_list(const std::vector<int>& faces) {
  std::string s;
  // At most 8 named: a message stays one short line however many faces there are.
  for (size_t i = 0; i < faces.size() && i < 8; ++i) s += fmt::format("{}{}", i ? ", " : "", faces[i]);
  if (faces.size() > 8) s += fmt::format(" and {} more", faces.size() - 8);
  return s;
}

}  // namespace

std::string_view to_string(SurfaceIssueKind kind) {
  switch (kind) {
    case SurfaceIssueKind::NonFiniteVertex: return "non-finite vertex";
    case SurfaceIssueKind::IndexOutOfRange: return "vertex index out of range";
    case SurfaceIssueKind::RepeatedVertex: return "face with a repeated vertex";
    case SurfaceIssueKind::DegenerateFace: return "degenerate face";
    case SurfaceIssueKind::ShortEdge: return "near-zero edge";
    case SurfaceIssueKind::DuplicateFace: return "duplicate face";
    case SurfaceIssueKind::NonManifoldEdge: return "non-manifold edge";
    case SurfaceIssueKind::NonManifoldVertex: return "non-manifold vertex";
    case SurfaceIssueKind::InconsistentOrientation: return "inconsistent orientation";
    case SurfaceIssueKind::IsolatedVertex: return "isolated vertex";
  }
  return "unknown issue";
}

int SurfaceReport::count(SurfaceIssueKind kind) const {
  return static_cast<int>(
      std::count_if(issues.begin(), issues.end(), [&](const SurfaceIssue& i) { return i.kind == kind; }));
}

std::string SurfaceReport::summary() const {
  std::string s = fmt::format(
      "{} vertices, {} faces, {} edges, {} component(s), {} boundary loop(s), Euler characteristic "
      "{}, genus {}{}",
      num_vertices, num_faces, num_edges, num_components, num_boundary_loops, euler_characteristic,
      genus, is_disk ? " (a disk)" : "");
  s += fmt::format("; {} error(s), {} warning(s)", num_errors, num_warnings);
  for (int k = 0; k <= static_cast<int>(SurfaceIssueKind::IsolatedVertex); ++k) {
    const auto kind = static_cast<SurfaceIssueKind>(k);
    const int n = count(kind);
    if (n > 0) s += fmt::format(", {} {}", n, to_string(kind));
  }
  return s;
}

SurfaceReport validate_surface(const TriMesh& mesh, const SurfaceCheckOptions& options) {
  SurfaceReport r;
  const int nv = mesh.num_vertices();
  const int nf = mesh.num_faces();

  std::vector<char> finite(nv, 1);
  for (int v = 0; v < nv; ++v) {
    if (!mesh.vertices[v].allFinite()) {
      finite[v] = 0;
      add(r, {SurfaceIssueKind::NonFiniteVertex, true, v, -1, -1, -1,
              fmt::format("vertex {} has a non-finite coordinate ({}, {}, {}); fix or remove it", v,
                          mesh.vertices[v].x(), mesh.vertices[v].y(), mesh.vertices[v].z())});
    }
  }

  // Per-face index checks; `counted` faces enter the topology analysis.
  std::vector<char> counted(nf, 1);
  std::vector<char> used(nv, 0);
  for (int f = 0; f < nf; ++f) {
    const auto& t = mesh.faces[f];
    bool in_range = true;
    for (int v : t) {
      if (v < 0 || v >= nv) {
        in_range = false;
        add(r, {SurfaceIssueKind::IndexOutOfRange, true, f, -1, -1, -1,
                fmt::format("face {} uses vertex {}, but the vertex indices are 0..{}", f, v, nv - 1)});
        break;
      }
    }
    if (!in_range) {
      counted[f] = 0;
      continue;
    }
    for (int v : t) used[v] = 1;
    if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2]) {
      counted[f] = 0;
      const int v = t[0] == t[1] || t[0] == t[2] ? t[0] : t[1];
      add(r, {SurfaceIssueKind::RepeatedVertex, true, f, -1, -1, -1,
              fmt::format("face {} ({}, {}, {}) uses vertex {} twice; remove the face", f, t[0], t[1],
                          t[2], v)});
    }
  }

  // Duplicate faces: same vertex set as an earlier face (either orientation).
  {
    std::vector<std::pair<std::array<int, 3>, int>> keys;
    for (int f = 0; f < nf; ++f) {
      if (!counted[f]) continue;
      auto k = mesh.faces[f];
      std::sort(k.begin(), k.end());
      keys.emplace_back(k, f);
    }
    // Lexicographic by the sorted vertices, ties by face (linear time).
    for (int c = 2; c >= 0; --c)
      counting_sort_by(keys, nv, [c](const std::pair<std::array<int, 3>, int>& k) { return k.first[c]; });
    std::vector<std::pair<int, int>> dups;  // (face, earlier face)
    for (size_t i = 1; i < keys.size(); ++i) {
      size_t j = i;
      while (j > 0 && keys[j - 1].first == keys[i].first) --j;
      if (j < i) dups.emplace_back(keys[i].second, keys[j].second);
    }
    std::sort(dups.begin(), dups.end());
    for (const auto& [f, g] : dups) {
      counted[f] = 0;
      add(r, {SurfaceIssueKind::DuplicateFace, true, f, g, -1, -1,
              fmt::format("face {} has the same vertices as face {}; remove the duplicate", f, g)});
    }
  }

  // Undirected edges of the counted faces: (min, max, face, forward?) sorted.
  struct Side {
    int a, b, face, from;
  };
  std::vector<Side> sides;
  sides.reserve(3 * static_cast<size_t>(nf));
  for (int f = 0; f < nf; ++f) {
    if (!counted[f]) continue;
    const auto& t = mesh.faces[f];
    for (int k = 0; k < 3; ++k) {
      const int u = t[k], w = t[(k + 1) % 3];
      sides.push_back({std::min(u, w), std::max(u, w), f, u});
    }
  }
  // By (a, b), ties in face order (a counted face has each edge once), i.e.
  // by (a, b, face, from), in linear time.
  counting_sort_by(sides, nv, [](const Side& x) { return x.b; });
  counting_sort_by(sides, nv, [](const Side& x) { return x.a; });

  // Mean edge length (finite edges) sets the scale of the warnings.
  double length_sum = 0.0;
  int length_count = 0;
  for (size_t i = 0; i < sides.size(); ++i) {
    if (i > 0 && sides[i].a == sides[i - 1].a && sides[i].b == sides[i - 1].b) continue;
    if (!finite[sides[i].a] || !finite[sides[i].b]) continue;
    length_sum += (mesh.vertices[sides[i].a] - mesh.vertices[sides[i].b]).norm();
    ++length_count;
  }
  const double mean_length = length_count > 0 ? length_sum / length_count : 0.0;

  for (int f = 0; f < nf; ++f) {
    if (!counted[f]) continue;
    const auto& t = mesh.faces[f];
    if (!finite[t[0]] || !finite[t[1]] || !finite[t[2]]) continue;
    const Vec3& p0 = mesh.vertices[t[0]];
    const Vec3& p1 = mesh.vertices[t[1]];
    const Vec3& p2 = mesh.vertices[t[2]];
    const double twice_area = (p1 - p0).cross(p2 - p0).norm();
    const double longest =
        std::max({(p1 - p0).squaredNorm(), (p2 - p1).squaredNorm(), (p0 - p2).squaredNorm()});
    if (twice_area <= options.degenerate_face_ratio * longest || longest == 0.0) {
      add(r, {SurfaceIssueKind::DegenerateFace, false, f, -1, -1, -1,
              fmt::format("face {} ({}, {}, {}) has (near-)zero area {:.3g} mm^2", f, t[0], t[1], t[2],
                          0.5 * twice_area)});
    }
  }

  UnionFind face_uf(std::max(nf, 1));
  UnionFind corner_uf(std::max(3 * nf, 1));
  auto corner_of = [&](int f, int v) {
    const auto& t = mesh.faces[f];
    return 3 * f + (t[0] == v ? 0 : t[1] == v ? 1 : 2);
  };
  int num_edges = 0;
  bool edge_problem = false;
  for (size_t i = 0; i < sides.size();) {
    size_t j = i + 1;
    while (j < sides.size() && sides[j].a == sides[i].a && sides[j].b == sides[i].b) ++j;
    const int a = sides[i].a, b = sides[i].b;
    ++num_edges;
    for (size_t k = i + 1; k < j; ++k) {
      face_uf.unite(sides[i].face, sides[k].face);
      corner_uf.unite(corner_of(sides[i].face, a), corner_of(sides[k].face, a));
      corner_uf.unite(corner_of(sides[i].face, b), corner_of(sides[k].face, b));
    }
    if (finite[a] && finite[b] && mean_length > 0.0) {
      const double len = (mesh.vertices[a] - mesh.vertices[b]).norm();
      if (len <= options.short_edge_ratio * mean_length) {
        add(r, {SurfaceIssueKind::ShortEdge, false, sides[i].face, -1, a, b,
                fmt::format("edge ({}, {}) of face {} has (near-)zero length {:.3g} mm (mean edge "
                            "length {:.3g} mm)",
                            a, b, sides[i].face, len, mean_length)});
      }
    }
    if (j - i > 2) {
      edge_problem = true;
      std::vector<int> faces;
      for (size_t k = i; k < j; ++k) faces.push_back(sides[k].face);
      add(r, {SurfaceIssueKind::NonManifoldEdge, true, -1, -1, a, b,
              fmt::format("edge ({}, {}) is shared by {} faces ({}); a surface has at most 2 faces "
                          "per edge: remove the extra faces or split the edge",
                          a, b, j - i, face_list(faces))});
    } else if (j - i == 2 && sides[i].from == sides[i + 1].from) {
      edge_problem = true;
      add(r, {SurfaceIssueKind::InconsistentOrientation, true, sides[i].face, sides[i + 1].face, a, b,
              fmt::format("faces {} and {} both use edge ({} -> {}) in the same direction: flip one "
                          "of them so that all faces are ordered counter-clockwise",
                          sides[i].face, sides[i + 1].face, sides[i].from,
                          sides[i].from == a ? b : a)});
    }
    i = j;
  }

  // Vertex fans: corners of one vertex linked through shared edges.
  {
    std::vector<std::vector<int>> roots(nv);
    for (int f = 0; f < nf; ++f) {
      if (!counted[f]) continue;
      for (int k = 0; k < 3; ++k) {
        const int v = mesh.faces[f][k];
        const int root = corner_uf.find(3 * f + k);
        if (std::find(roots[v].begin(), roots[v].end(), root) == roots[v].end()) roots[v].push_back(root);
      }
    }
    for (int v = 0; v < nv; ++v) {
      if (roots[v].size() > 1) {
        edge_problem = true;
        add(r, {SurfaceIssueKind::NonManifoldVertex, true, v, -1, -1, -1,
                fmt::format("vertex {} is non-manifold: its faces form {} separate fans (surfaces "
                            "touch at a single vertex); split the vertex or remove one of the parts",
                            v, roots[v].size())});
      }
    }
  }

  for (int v = 0; v < nv; ++v) {
    if (!used[v]) {
      add(r, {SurfaceIssueKind::IsolatedVertex, false, v, -1, -1, -1,
              fmt::format("vertex {} is used by no face", v)});
    }
  }

  // Topology summary of the counted faces.
  std::vector<char> counted_vertex(nv, 0);
  std::vector<std::array<int, 3>> faces;
  for (int f = 0; f < nf; ++f) {
    if (!counted[f]) continue;
    faces.push_back(mesh.faces[f]);
    for (int v : mesh.faces[f]) counted_vertex[v] = 1;
  }
  r.num_faces = static_cast<int>(faces.size());
  r.num_vertices = static_cast<int>(std::count(counted_vertex.begin(), counted_vertex.end(), 1));
  r.num_edges = num_edges;
  r.euler_characteristic = r.num_vertices - r.num_edges + r.num_faces;
  {
    std::vector<int> face_roots;
    for (int f = 0; f < nf; ++f) {
      if (counted[f]) face_roots.push_back(face_uf.find(f));
    }
    std::sort(face_roots.begin(), face_roots.end());
    r.num_components =
        static_cast<int>(std::unique(face_roots.begin(), face_roots.end()) - face_roots.begin());
  }
  r.manifold = !edge_problem;
  if (r.manifold) {
    try {
      const Halfedges he = build_halfedges(nv, faces);
      r.num_boundary_loops = static_cast<int>(he.boundary_loops().size());
      r.genus = (2 * r.num_components - r.euler_characteristic - r.num_boundary_loops) / 2;
    } catch (const Error&) {
      // Unreachable when the checks above agree with build_halfedges(); keep the
      // promise not to throw and report the mesh as non-manifold instead.
      r.manifold = false;
    }
  }
  r.is_disk = r.manifold && r.num_errors == 0 && r.num_components == 1 &&
              r.num_boundary_loops == 1 && r.genus == 0;
  return r;
}

namespace {

[[noreturn]] void throw_errors(const SurfaceReport& r, std::string_view what) {
  std::string msg = fmt::format("{} is not a valid surface: {} error(s)", what, r.num_errors);
  int shown = 0;
  bool non_finite_only = true;
  for (const SurfaceIssue& i : r.issues) {
    if (!i.is_error) continue;
    if (i.kind != SurfaceIssueKind::NonFiniteVertex) non_finite_only = false;
    if (shown < 3) msg += fmt::format("{} {}", shown ? ";" : ":", i.message);
    ++shown;
  }
  if (shown > 3) msg += fmt::format("; and {} more", shown - 3);
  if (non_finite_only) throw InvalidInput(msg);
  throw TopologyError(msg);
}

}  // namespace

void require_valid_surface(const TriMesh& mesh, std::string_view what) {
  const SurfaceReport r = validate_surface(mesh);
  if (!r.ok()) throw_errors(r, what);
  if (r.num_faces == 0) throw TopologyError(fmt::format("{} has no faces", what));
}

void require_disk(const TriMesh& mesh, std::string_view what, std::string_view cut_hint) {
  const std::string or_hint = cut_hint.empty() ? std::string() : fmt::format(", or {}", cut_hint);
  const SurfaceReport r = validate_surface(mesh);
  if (!r.ok()) throw_errors(r, what);
  if (r.is_disk) return;
  if (r.num_faces == 0) throw TopologyError(fmt::format("{} has no faces; a disk-shaped surface is needed", what));
  if (r.num_components > 1) {
    throw TopologyError(fmt::format(
        "{} has {} connected components; a disk is one piece: keep one component (e.g. the "
        "largest) or design each part separately",
        what, r.num_components));
  }
  const int b = r.num_boundary_loops, g = r.genus;
  if (b == 0) {
    throw TopologyError(fmt::format(
        "{} is a closed surface (no boundary, genus {}): cut it open into a disk along a path{}{}",
        what, g, g > 0 ? " that also cuts every handle" : "", or_hint));
  }
  if (g == 0) {
    throw TopologyError(fmt::format(
        "{} has {} boundary loops and genus 0 (a {}): cut it into a disk along a path between the "
        "loops{}",
        what, b, b == 2 ? "cylinder/annulus" : "disk with holes", or_hint));
  }
  throw TopologyError(fmt::format(
      "{} has {} boundary loop(s) and genus {} (it has handles): cut it into a disk along paths "
      "through every handle{}",
      what, b, g, or_hint));
}

}  // namespace knitforge
