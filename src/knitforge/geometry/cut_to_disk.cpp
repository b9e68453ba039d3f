#include "knitforge/geometry/cut_to_disk.h"

#include <algorithm>
#include <cstdint>
#include <limits>
#include <queue>
#include <tuple>
#include <unordered_map>
#include <utility>

#include <fmt/format.h>

#include "knitforge/geometry/chain_edges.h"
#include "knitforge/geometry/cut_mesh_along_path.h"
#include "knitforge/geometry/geodesic_path.h"
#include "knitforge/geometry/halfedges.h"
#include "knitforge/geometry/mesh_measures.h"
#include "knitforge/geometry/split_mesh_along_path.h"
#include "knitforge/geometry/surface_checks.h"
#include "knitforge/util/errors.h"
#include "knitforge/util/union_find.h"

namespace knitforge {

const char* to_string(SeamKind kind) {
  switch (kind) {
    case SeamKind::User:
      return "user";
    case SeamKind::Handle:
      return "handle";
    case SeamKind::Loops:
      return "loops";
  }
  return "unknown";
}

double seam_length(const std::vector<Seam>& seams) {
  double s = 0.0;
  for (const Seam& seam : seams) s += seam.length;
  return s;
}

namespace {

std::uint64_t key(int a, int b) {
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(a)) << 32) | static_cast<std::uint32_t>(b);
}

struct Topology {
  int loops = 0, genus = 0, components = 0;
};

Topology topology_of(const TriMesh& mesh, const Halfedges& he) {
  Topology t;
  int used = 0;
  for (int v = 0; v < mesh.num_vertices(); ++v) used += he.is_isolated_vertex(v) ? 0 : 1;
  he.face_components(&t.components);
  t.loops = static_cast<int>(he.boundary_loops().size());
  const int chi = used - he.num_edges() + mesh.num_faces();
  t.genus = (2 * t.components - chi - t.loops) / 2;
  return t;
}

/// A piece of the carried source: a path of mesh vertices (one vertex for a
/// point source); `seam` pieces lie on a lip of a seam (`left` lip or not).
struct Piece {
  std::vector<int> path;
  bool seam = false;
  bool left = true;
};

/// The mesh being cut and everything that has to follow it.
class Cutter {
 public:
  explicit Cutter(const TriMesh& mesh) : mesh_(mesh) {
    origin_.resize(mesh.num_vertices());
    for (int v = 0; v < mesh.num_vertices(); ++v) origin_[v] = v;
  }

  const TriMesh& mesh() const { return mesh_; }
  std::vector<Piece>& pieces() { return pieces_; }
  const std::vector<int>& origin() const { return origin_; }

  /// Splits along `points`; returns the path as mesh vertices.
  std::vector<int> split(const std::vector<MeshPoint>& points) {
    return split(std::vector<std::vector<MeshPoint>>{points})[0];
  }

  /// Splits along several paths at once; returns them as mesh vertices.
  std::vector<std::vector<int>> split(const std::vector<std::vector<MeshPoint>>& paths) {
    SplitMeshResult s = split_mesh_along_paths(mesh_, paths);
    // New vertices on old edges, per edge (lo, hi), sorted along it.
    std::unordered_map<std::uint64_t, std::vector<std::pair<double, int>>> on_edge;
    for (size_t i = 0; i < s.new_vertex_origin.size(); ++i) {
      const MeshPoint& p = s.new_vertex_origin[i];
      if (!p.is_edge()) continue;
      on_edge[key(std::min(p.v0, p.v1), std::max(p.v0, p.v1))].push_back(
          {p.v0 < p.v1 ? p.ratio : 1.0 - p.ratio, s.original_num_vertices + static_cast<int>(i)});
    }
    for (auto& [k, list] : on_edge) std::sort(list.begin(), list.end());
    auto refine = [&](std::vector<int>& path) {
      if (on_edge.empty() || path.size() < 2) return;
      std::vector<int> out{path[0]};
      for (size_t i = 0; i + 1 < path.size(); ++i) {
        const int u = path[i], w = path[i + 1];
        const auto it = on_edge.find(key(std::min(u, w), std::max(u, w)));
        if (it != on_edge.end()) {
          if (u < w) {
            for (const auto& e : it->second) out.push_back(e.second);
          } else {
            for (auto e = it->second.rbegin(); e != it->second.rend(); ++e) out.push_back(e->second);
          }
        }
        out.push_back(w);
      }
      path = std::move(out);
    };
    for (Piece& p : pieces_) refine(p.path);
    for (auto& c : pending_cuts_) refine(c);
    origin_.resize(s.mesh.num_vertices(), -1);
    mesh_ = std::move(s.mesh);
    return s.paths;
  }

  /// Cuts along the vertex paths; carries the pieces to the copies.
  void cut(const std::vector<std::vector<int>>& paths) {
    // Directed edge -> (face, corner of its start) before the cut; faces
    // keep their index and corner order through the cut.
    std::unordered_map<std::uint64_t, std::pair<int, int>> corner;
    corner.reserve(3 * static_cast<size_t>(mesh_.num_faces()));
    for (int f = 0; f < mesh_.num_faces(); ++f)
      for (int k = 0; k < 3; ++k) corner[key(mesh_.faces[f][k], mesh_.faces[f][(k + 1) % 3])] = {f, k};
    const CutMeshResult c = cut_mesh_along_paths(mesh_, paths);
    const TriMesh& out = c.mesh;
    auto side = [&](int u, int w, std::pair<int, int>& pair) {  // copies of u, w in the face of u -> w
      if (const auto it = corner.find(key(u, w)); it != corner.end()) {
        pair = {out.faces[it->second.first][it->second.second],
                out.faces[it->second.first][(it->second.second + 1) % 3]};
        return true;
      }
      if (const auto it = corner.find(key(w, u)); it != corner.end()) {
        pair = {out.faces[it->second.first][(it->second.second + 1) % 3],
                out.faces[it->second.first][it->second.second]};
        return false;
      }
      throw SolverError(
          fmt::format("cut_to_disk: source vertices {} and {} are not joined by an edge", u, w));
    };
    std::vector<Piece> carried;
    for (const Piece& p : pieces_) {
      if (p.path.size() == 1) {
        // A point: the copy in the first face around it.
        const int v = p.path[0];
        int copy = -1;
        for (int f = 0; f < mesh_.num_faces() && copy < 0; ++f)
          for (int k = 0; k < 3; ++k)
            if (mesh_.faces[f][k] == v) copy = out.faces[f][k];
        carried.push_back({{copy}, p.seam, p.left});
        continue;
      }
      const size_t first_carried = carried.size();
      const bool closed = p.path.size() > 2 && p.path.front() == p.path.back();
      Piece cur;
      bool open = false;
      auto flush = [&] {
        if (open && cur.path.size() >= 2) carried.push_back(cur);
        open = false;
      };
      for (size_t i = 0; i + 1 < p.path.size(); ++i) {
        const int u = p.path[i], w = p.path[i + 1];
        std::pair<int, int> a, b;
        const bool has_left = side(u, w, a);
        bool two_sided = false;
        if (has_left && corner.count(key(w, u))) {
          const auto& fc = corner.at(key(w, u));
          b = {out.faces[fc.first][(fc.second + 1) % 3], out.faces[fc.first][fc.second]};
          two_sided = b != a;
        }
        if (!two_sided || p.seam) {
          // An edge that stays (or a lip, which is boundary already).
          if (open && cur.seam == p.seam && cur.path.back() == a.first) {
            cur.path.push_back(a.second);
          } else {
            flush();
            cur = {{a.first, a.second}, p.seam, p.left};
            open = true;
          }
          continue;
        }
        // The edge was cut: the piece continues on both lips.
        flush();
        auto add_lip = [&](const std::pair<int, int>& e, bool left) {
          for (Piece& q : lips_) {
            if (q.left == left && q.path.back() == e.first) {
              q.path.push_back(e.second);
              return;
            }
          }
          lips_.push_back({{e.first, e.second}, true, left});
        };
        add_lip(a, true);
        add_lip(b, false);
      }
      flush();
      // A closed path broken by the cut: its last part runs on into its
      // first (the break is not at its start vertex).
      if (closed && carried.size() > first_carried + 1) {
        Piece& head = carried[first_carried];
        Piece& tail = carried.back();
        if (!head.seam && !tail.seam && tail.path.back() == head.path.front()) {
          tail.path.insert(tail.path.end(), head.path.begin() + 1, head.path.end());
          head = std::move(tail);
          carried.pop_back();
        }
      }
      for (Piece& q : lips_) carried.push_back(std::move(q));
      lips_.clear();
    }
    pieces_ = std::move(carried);
    // Pending user cuts are cut together, so nothing to carry for them.
    const int old = static_cast<int>(origin_.size());
    origin_.resize(out.num_vertices());
    for (int v = old; v < out.num_vertices(); ++v) origin_[v] = origin_[c.vertex_origin[v]];
    components_after_cut_ = c.num_components;
    mesh_ = c.mesh;
  }

  int components_after_cut() const { return components_after_cut_; }
  std::vector<std::vector<int>>& pending_cuts() { return pending_cuts_; }

 private:
  TriMesh mesh_;
  std::vector<int> origin_;
  std::vector<Piece> pieces_;
  std::vector<Piece> lips_;
  std::vector<std::vector<int>> pending_cuts_;
  int components_after_cut_ = 1;
};

MeshPoint to_mesh_point(const SurfacePoint& p) {
  return MeshPoint::in_face(p.face, {p.bary[0], p.bary[1], p.bary[2]});
}

MeshPoint to_mesh_point(const GeodesicPathPoint& p) {
  if (p.is_face_point()) return to_mesh_point(p.point);
  if (p.is_vertex()) return MeshPoint::at_vertex(p.v0);
  return MeshPoint::on_edge(p.v0, p.v1, p.ratio);
}

double path_length(const TriMesh& mesh, const std::vector<int>& path) {
  double len = 0.0;
  for (size_t i = 0; i + 1 < path.size(); ++i)
    len += (mesh.vertices[path[i + 1]] - mesh.vertices[path[i]]).norm();
  return len;
}

std::vector<Vec3> positions(const TriMesh& mesh, const std::vector<int>& path) {
  std::vector<Vec3> out;
  for (int v : path) out.push_back(mesh.vertices[v]);
  return out;
}

/// Per vertex, the index of its boundary loop (Halfedges::boundary_loops()
/// order) or -1.
std::vector<int> loop_ids(const TriMesh& mesh, const Halfedges& he) {
  std::vector<int> id(mesh.num_vertices(), -1);
  const auto loops = he.boundary_loops();
  for (size_t l = 0; l < loops.size(); ++l)
    for (int v : loops[l]) id[v] = static_cast<int>(l);
  return id;
}

/// A piece of the source between two different boundary loops.
struct Candidate {
  std::vector<int> path;
  double length = 0.0;
  size_t piece = 0, start = 0;
};

std::vector<Candidate> source_candidates(const TriMesh& mesh, const Halfedges& he,
                                         const std::vector<Piece>& pieces) {
  const std::vector<int> loop = loop_ids(mesh, he);
  std::vector<Candidate> out;
  for (size_t pi = 0; pi < pieces.size(); ++pi) {
    const Piece& p = pieces[pi];
    if (p.seam) continue;
    int last = -1;  // position of the last boundary vertex
    for (size_t i = 0; i < p.path.size(); ++i) {
      if (loop[p.path[i]] < 0) continue;
      if (last >= 0 && static_cast<int>(i) > last && loop[p.path[i]] != loop[p.path[last]]) {
        Candidate c;
        c.path.assign(p.path.begin() + last, p.path.begin() + static_cast<long>(i) + 1);
        c.length = path_length(mesh, c.path);
        c.piece = pi;
        c.start = static_cast<size_t>(last);
        out.push_back(std::move(c));
      }
      last = static_cast<int>(i);
    }
  }
  std::stable_sort(out.begin(), out.end(), [](const Candidate& a, const Candidate& b) {
    return std::tie(a.length, a.piece, a.start) < std::tie(b.length, b.piece, b.start);
  });
  return out;
}

/// The real edges of a cut graph through the handles (see the header): the
/// greedy system of loops on the mesh with every boundary loop capped by a
/// virtual vertex. Returns the interior edges to cut, as vertex pairs.
std::vector<std::pair<int, int>> handle_cut_graph(const TriMesh& mesh, int genus) {
  const int n = mesh.num_vertices();
  const auto loops = build_halfedges(n, mesh.faces).boundary_loops();
  TriMesh capped = mesh;
  for (size_t l = 0; l < loops.size(); ++l) {
    Vec3 c = Vec3::Zero();
    for (int v : loops[l]) c += mesh.vertices[v];
    capped.vertices.push_back(c / static_cast<double>(loops[l].size()));
    const int cv = n + static_cast<int>(l);
    const auto& lp = loops[l];
    // The loop runs with the surface on its left; the cap on its right.
    for (size_t i = 0; i < lp.size(); ++i) capped.faces.push_back({lp[(i + 1) % lp.size()], lp[i], cv});
  }
  const Halfedges he = build_halfedges(capped.num_vertices(), capped.faces);
  const int nv = capped.num_vertices(), ne = he.num_edges();
  std::vector<int> edge_h(ne, -1);
  for (int h = 0; h < he.num_halfedges(); ++h)
    if (edge_h[he.edge(h)] < 0) edge_h[he.edge(h)] = h;
  auto weight = [&](int e) {
    const int a = he.from(edge_h[e]), b = he.to(edge_h[e]);
    return a >= n || b >= n ? 0.0 : (capped.vertices[a] - capped.vertices[b]).norm();
  };
  // Shortest-path tree (Dijkstra) from the root.
  const int root = loops.empty() ? 0 : n;
  std::vector<double> dist(nv, std::numeric_limits<double>::infinity());
  std::vector<int> parent_edge(nv, -1);
  std::vector<std::vector<std::pair<int, int>>> adj(nv);  // (neighbour, edge)
  for (int e = 0; e < ne; ++e) {
    const int a = he.from(edge_h[e]), b = he.to(edge_h[e]);
    adj[a].push_back({b, e});
    adj[b].push_back({a, e});
  }
  using Item = std::pair<double, int>;
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> queue;
  dist[root] = 0.0;
  queue.push({0.0, root});
  std::vector<char> done(nv, 0);
  while (!queue.empty()) {
    const auto [d, v] = queue.top();
    queue.pop();
    if (done[v]) continue;
    done[v] = 1;
    for (const auto& [w, e] : adj[v]) {
      const double dw = d + weight(e);
      if (dw < dist[w]) {
        dist[w] = dw;
        parent_edge[w] = e;
        queue.push({dw, w});
      }
    }
  }
  std::vector<char> in_tree(ne, 0);
  for (int v = 0; v < nv; ++v)
    if (parent_edge[v] >= 0) in_tree[parent_edge[v]] = 1;
  // Maximum spanning tree of the dual over the other edges, by the length
  // of the loop each edge closes.
  std::vector<std::pair<double, int>> dual;
  for (int e = 0; e < ne; ++e) {
    if (in_tree[e]) continue;
    const int a = he.from(edge_h[e]), b = he.to(edge_h[e]);
    dual.push_back({dist[a] + dist[b] + weight(e), e});
  }
  std::sort(dual.begin(), dual.end(), [](const auto& x, const auto& y) {
    return x.first != y.first ? x.first > y.first : x.second < y.second;
  });
  UnionFind faces(static_cast<size_t>(capped.num_faces()));
  std::vector<int> generators;
  for (const auto& [w, e] : dual) {
    const int h = edge_h[e], o = he.opposite(h);
    const int f = faces.find(he.face(h)), g = faces.find(he.face(o));
    if (f != g) {
      faces.unite(f, g);
    } else {
      generators.push_back(e);
    }
  }
  if (static_cast<int>(generators.size()) != 2 * genus) {
    throw SolverError(fmt::format("cut_to_disk: the cut graph has {} loops for genus {} (expected {})",
                                  generators.size(), genus, 2 * genus));
  }
  std::vector<char> in_graph(ne, 0);
  for (int e : generators) {
    in_graph[e] = 1;
    for (int v : {he.from(edge_h[e]), he.to(edge_h[e])}) {
      while (parent_edge[v] >= 0 && !in_graph[parent_edge[v]]) {
        in_graph[parent_edge[v]] = 1;
        const int h = edge_h[parent_edge[v]];
        v = he.from(h) == v ? he.to(h) : he.from(h);
      }
    }
  }
  std::vector<std::pair<int, int>> out;
  for (int e = 0; e < ne; ++e) {
    if (!in_graph[e]) continue;
    const int a = he.from(edge_h[e]), b = he.to(edge_h[e]);
    if (a >= n || b >= n) continue;  // inside a hole
    // A boundary edge of the mesh (a cap face on one side) cuts nothing.
    const int h = edge_h[e];
    if (he.face(h) >= mesh.num_faces() || he.face(he.opposite(h)) >= mesh.num_faces()) continue;
    out.push_back({std::min(a, b), std::max(a, b)});
  }
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace

CutToDisk cut_to_disk(const TriMesh& mesh, const CutToDiskOptions& options, const std::string& what) {
  Topology top;
  {
    const SurfaceReport r = validate_surface(mesh);
    if (!r.ok() || r.num_faces == 0) require_valid_surface(mesh, what);  // throws, saying why
    top = {r.num_boundary_loops, r.genus, r.num_components};
  }
  if (top.components > 1) {
    throw TopologyError(fmt::format(
        "{} has {} connected components; a knitted piece is one: keep one component (e.g. the largest) or "
        "design each part separately",
        what, top.components));
  }
  CutToDisk out;
  auto add_seam = [&](SeamKind kind, bool on_source, const TriMesh& m, const std::vector<int>& path) {
    Seam s;
    s.kind = kind;
    s.on_source = on_source;
    s.path = positions(m, path);
    s.length = path_length(m, path);
    out.seams.push_back(std::move(s));
  };
  out.input_boundary_loops = top.loops;
  out.input_genus = top.genus;
  const bool disk = top.loops == 1 && top.genus == 0;
  if (disk && options.cuts.empty()) {
    out.mesh = mesh;
    out.vertex_origin.resize(mesh.num_vertices());
    for (int v = 0; v < mesh.num_vertices(); ++v) out.vertex_origin[v] = v;
    out.source = options.source;
    return out;
  }
  if (top.loops == 0 && top.genus == 0) {
    throw TopologyError(fmt::format(
        "{} is a closed surface (no boundary, genus 0): a knitted piece needs an edge to start from; open it "
        "where the garment opens (remove the faces of the neck or wrist opening) and try again",
        what));
  }

  Cutter cutter(mesh);
  // 1. The source becomes paths of mesh vertices.
  {
    std::vector<std::vector<MeshPoint>> lines;
    for (const auto& line : options.source.polylines) {
      if (line.empty()) continue;
      lines.emplace_back();
      for (const SurfacePoint& p : line) lines.back().push_back(to_mesh_point(p));
    }
    if (!lines.empty()) {
      for (std::vector<int>& path : cutter.split(lines))
        if (!path.empty()) cutter.pieces().push_back({std::move(path), false, true});
    }
  }
  // 2. The user's cuts, joined along the surface as split by the source.
  if (!options.cuts.empty()) {
    std::vector<std::vector<MeshPoint>> lines;
    for (const auto& cut : options.cuts) {
      lines.emplace_back();
      for (const SurfacePoint& p : surface_cut_from_polyline(cutter.mesh(), cut))
        lines.back().push_back(to_mesh_point(p));
    }
    for (std::vector<int>& path : cutter.split(lines)) {
      if (path.size() < 2) {
        throw InvalidInput(
            fmt::format("{}: a cut has no length on the surface (all its points fall together)", what));
      }
      cutter.pending_cuts().push_back(std::move(path));
    }
  }
  if (!cutter.pending_cuts().empty()) {
    std::vector<std::vector<int>> cuts = cutter.pending_cuts();
    cutter.pending_cuts().clear();
    for (const auto& c : cuts) add_seam(SeamKind::User, false, cutter.mesh(), c);
    cutter.cut(cuts);
    if (cutter.components_after_cut() > 1) {
      throw TopologyError(fmt::format(
          "{}: the cuts (--cut) separate the surface into {} pieces; a knitted piece is one: cut from a "
          "boundary "
          "to a boundary only where that joins two different boundary loops, or from inside to a boundary",
          what, cutter.components_after_cut()));
    }
  }

  // 3. Handles, then loops, until a disk is left.
  bool first_loop_seam = true;
  for (int step = 0;; ++step) {
    const Halfedges he = build_halfedges(cutter.mesh().num_vertices(), cutter.mesh().faces);
    const Topology t = topology_of(cutter.mesh(), he);
    if (t.components != 1) {
      throw SolverError(fmt::format("cut_to_disk: a seam separated {} into {} pieces", what, t.components));
    }
    if (t.loops == 1 && t.genus == 0) break;
    if (step > 2 * top.genus + top.loops + 4) {
      throw SolverError(fmt::format("cut_to_disk: {} is still not a disk after {} seams ({} loops, genus {})",
                                    what, out.seams.size(), t.loops, t.genus));
    }
    if (t.genus > 0) {
      const auto edges = handle_cut_graph(cutter.mesh(), t.genus);
      std::vector<std::vector<int>> paths = chain_edges(cutter.mesh().num_vertices(), edges);
      for (const auto& p : paths) add_seam(SeamKind::Handle, false, cutter.mesh(), p);
      cutter.cut(paths);
      continue;
    }
    if (t.loops == 0) {
      throw TopologyError(
          fmt::format("{}: cutting the handles left a closed surface; open it where the garment opens "
                      "(remove the faces of "
                      "an opening) and try again",
                      what));
    }
    // Loops: a piece of the source between two loops, or the shortest path.
    std::vector<int> path;
    bool on_source = false;
    if (options.seams_on_source) {
      const std::vector<Candidate> candidates = source_candidates(cutter.mesh(), he, cutter.pieces());
      if (first_loop_seam) out.source_seam_candidates = static_cast<int>(candidates.size());
      if (!candidates.empty()) {
        const bool longest = first_loop_seam && options.longest_source_seam;
        path = longest ? candidates.back().path : candidates.front().path;
        on_source = true;
      }
    }
    if (path.empty()) {
      const auto loops = he.boundary_loops();
      std::vector<int> targets;
      for (size_t l = 1; l < loops.size(); ++l)
        targets.insert(targets.end(), loops[l].begin(), loops[l].end());
      const GeodesicSource from = source_from_boundary(cutter.mesh(), 0.0, 1.0, 0);
      const GeodesicPath g = geodesic_path_from_source(cutter.mesh(), from, targets);
      std::vector<MeshPoint> pts;
      for (const auto& p : g.points) pts.push_back(to_mesh_point(p));
      path = cutter.split(pts);
    }
    first_loop_seam = false;
    if (path.size() < 2) throw SolverError(fmt::format("cut_to_disk: a seam of {} has no length", what));
    add_seam(SeamKind::Loops, on_source, cutter.mesh(), path);
    cutter.cut({path});
  }

  // The loop above left only when the topology (from the half-edges) is a
  // disk's: one component, one boundary loop, genus 0.
  out.mesh = cutter.mesh();
  out.vertex_origin = cutter.origin();
  // The carried source: the pieces off the seams, else the left lips.
  std::vector<std::vector<int>> kept;
  for (const Piece& p : cutter.pieces())
    if (!p.seam) kept.push_back(p.path);
  if (kept.empty()) {
    for (const Piece& p : cutter.pieces())
      if (p.seam && p.left) kept.push_back(p.path);
    out.source_on_seam = !kept.empty();
  }
  if (!kept.empty()) {
    out.source = source_from_vertex_paths(
        out.mesh, kept,
        options.source.description.empty()
            ? std::string("source")
            : options.source.description + (out.source_on_seam ? " (on a seam)" : ""));
    const auto& in_side = options.source.vertex_side;
    auto& side = out.source.vertex_side;
    if (!side.empty() && static_cast<int>(in_side.size()) == mesh.num_vertices()) {
      long agree = 0;
      for (int v = 0; v < out.mesh.num_vertices(); ++v) {
        const int o = out.vertex_origin[v];
        if (o >= 0) agree += static_cast<long>(side[v]) * in_side[o];
      }
      if (agree < 0)
        for (auto& s : side) s = static_cast<signed char>(-s);
    }
  } else {
    out.source.description = options.source.description;
  }
  return out;
}

std::vector<SurfacePoint> surface_cut_from_polyline(const TriMesh& mesh, const std::vector<Vec3>& points) {
  if (points.empty()) throw InvalidInput("cut: the polyline has no points");
  std::vector<Vec3> pts = points;
  const Halfedges he = build_halfedges(mesh.num_vertices(), mesh.faces);
  const double tol = edge_length_stats(mesh).mean;
  for (size_t end : {size_t{0}, pts.size() - 1}) {
    if (!pts[end].allFinite()) break;  // reported below
    double best = std::numeric_limits<double>::infinity();
    Vec3 q = pts[end];
    for (int h = 0; h < he.num_halfedges(); ++h) {
      if (!he.is_boundary_halfedge(h)) continue;
      const Vec3 c = closest_point_on_segment(pts[end], mesh.vertices[he.from(h)], mesh.vertices[he.to(h)]);
      const double d = (c - pts[end]).norm();
      if (d < best) {
        best = d;
        q = c;
      }
    }
    if (best <= tol) pts[end] = q;
  }
  const GeodesicSource s = source_from_polyline(mesh, pts);
  std::vector<SurfacePoint> out;
  for (const auto& line : s.polylines) out.insert(out.end(), line.begin(), line.end());
  return out;
}

}  // namespace knitforge
