#include "knitforge/geometry/split_mesh_along_path.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <unordered_map>
#include <utility>

#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <Eigen/Geometry>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_face_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>
#include <fmt/core.h>

#include "knitforge/geometry/edge_key.h"
#include "knitforge/geometry/halfedges.h"
#include "knitforge/util/errors.h"

namespace knitforge {

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Vb = CGAL::Triangulation_vertex_base_with_info_2<int, Kernel>;
using Fb0 = CGAL::Constrained_triangulation_face_base_2<Kernel>;
using Fb = CGAL::Triangulation_face_base_with_info_2<int, Kernel, Fb0>;
using Tds = CGAL::Triangulation_data_structure_2<Vb, Fb>;
using Cdt = CGAL::Constrained_Delaunay_triangulation_2<Kernel, Tds, CGAL::No_constraint_intersection_tag>;
using Point2 = Kernel::Point_2;

enum class Kind { Vertex, Edge, Face };

// A path point after validation and snapping. Edge parameters s run from the
// smaller to the larger vertex index of the edge.
struct Ref {
  Kind kind = Kind::Vertex;
  int v = -1;
  int e = -1;
  double s = 0.0;
  int f = -1;
  std::array<double, 3> b{0.0, 0.0, 0.0};
  int cluster = -1;  // edge or face cluster id
};

struct EdgeCluster {
  int e = -1;
  double s = 0.0;
  int vid = -1;
};

struct FaceCluster {
  int f = -1;
  std::array<double, 3> b{0.0, 0.0, 0.0};
  int vid = -1;
};

class Splitter {
 public:
  Splitter(const TriMesh& mesh, const std::vector<MeshPoint>& path, std::vector<int> path_start,
           const SplitOptions& options)
      : mesh_(mesh), path_(path), path_start_(std::move(path_start)), snap_(options.snap),
        he_(build_halfedges(mesh.num_vertices(), mesh.faces)) {
    edge_lo_.assign(he_.num_edges(), -1);
    edge_hi_.assign(he_.num_edges(), -1);
    edge_h_.assign(he_.num_edges(), -1);
    out_h_.assign(mesh.num_vertices(), -1);
    for (int h = 0; h < he_.num_halfedges(); ++h) {
      const int e = he_.edge(h);
      if (edge_h_[e] < 0) {
        edge_h_[e] = h;
        edge_lo_[e] = std::min(he_.from(h), he_.to(h));
        edge_hi_[e] = std::max(he_.from(h), he_.to(h));
      }
      const int v = he_.from(h);
      if (out_h_[v] < 0 || he_.opposite(h) < 0) out_h_[v] = h;
    }
  }

  SplitMeshResult run();

 private:
  // The edge joining a and b, or -1 (a search around a, then around b).
  int find_edge(int a, int b) const {
    for (int pass = 0; pass < 2; ++pass) {
      const int h0 = out_h_[a];
      int h = h0;
      while (h >= 0) {
        if (he_.to(h) == b) return he_.edge(h);
        h = he_.opposite(he_.prev(h));
        if (h == h0) break;
      }
      std::swap(a, b);
    }
    return -1;
  }
  Ref normalize(int i) const;
  Ref snap_edge(int e, double s) const;
  std::vector<int> faces_of(const Ref& r) const;
  void triangulate_face(int f, const std::vector<std::pair<int, int>>& chords);
  bool triangulate_simple(const std::array<std::vector<int>, 3>& sides,
                          const std::vector<std::pair<int, int>>& chords, int f);
  void triangulate_constrained(int f, const std::vector<int>& polygon,
                               const std::vector<Vec2>& polygon_2d, const std::vector<int>& interior,
                               const std::vector<Vec2>& interior_2d,
                               const std::vector<std::pair<int, int>>& chords);

  const TriMesh& mesh_;
  // The points of all paths, one after the other; path k is
  // path_[path_start_[k] .. path_start_[k + 1]).
  const std::vector<MeshPoint>& path_;
  std::vector<int> path_start_;
  // "path point i" (one path) or "point j of path k" (several), for messages.
  std::string point_name(int i) const {
    if (path_start_.size() <= 2) return fmt::format("path point {}", i);
    const int k = static_cast<int>(std::upper_bound(path_start_.begin(), path_start_.end(), i) - path_start_.begin()) - 1;
    return fmt::format("point {} of path {}", i - path_start_[k], k);
  }
  double snap_;
  Halfedges he_;
  std::vector<int> edge_lo_, edge_hi_, edge_h_;
  std::vector<int> out_h_;  // an outgoing half-edge per vertex (the boundary one if any)

  std::vector<EdgeCluster> edge_clusters_;
  std::unordered_map<int, std::vector<int>> clusters_on_edge_;  // edge -> cluster ids sorted by s
  std::vector<FaceCluster> face_clusters_;
  std::unordered_map<int, std::vector<int>> clusters_in_face_;  // face -> cluster ids

  SplitMeshResult out_;
};

Ref Splitter::snap_edge(int e, double s) const {
  Ref r;
  if (s <= snap_) {
    r.kind = Kind::Vertex;
    r.v = edge_lo_[e];
  } else if (s >= 1.0 - snap_) {
    r.kind = Kind::Vertex;
    r.v = edge_hi_[e];
  } else {
    r.kind = Kind::Edge;
    r.e = e;
    r.s = s;
  }
  return r;
}

Ref Splitter::normalize(int i) const {
  const MeshPoint& p = path_[i];
  const int nv = mesh_.num_vertices();
  if (p.face >= 0) {
    if (p.face >= mesh_.num_faces()) {
      throw InvalidInput(fmt::format("split_mesh_along_path: {} lies in face {}, but the "
                                     "mesh has {} faces",
                                     point_name(i), p.face, mesh_.num_faces()));
    }
    std::array<double, 3> b = p.bary;
    double sum = 0.0;
    for (double x : b) {
      if (!std::isfinite(x) || x < -1e-9) {
        throw InvalidInput(fmt::format("split_mesh_along_path: {} in face {} has invalid "
                                       "barycentric coordinates ({}, {}, {}); they must be >= 0",
                                       point_name(i), p.face, b[0], b[1], b[2]));
      }
      sum += x;
    }
    if (std::abs(sum - 1.0) > 1e-6) {
      throw InvalidInput(fmt::format("split_mesh_along_path: the barycentric coordinates of {} in face {} "
                                     "sum to {}, not 1",
                                     point_name(i), p.face, sum));
    }
    for (double& x : b) x = std::max(x, 0.0) / sum;
    const auto& t = mesh_.faces[p.face];
    int small = 0;
    for (double x : b) small += x < snap_ ? 1 : 0;
    if (small >= 2) {
      const int k = static_cast<int>(std::max_element(b.begin(), b.end()) - b.begin());
      Ref r;
      r.v = t[k];
      return r;
    }
    if (small == 1) {
      const int k = static_cast<int>(std::min_element(b.begin(), b.end()) - b.begin());
      const int a = t[(k + 1) % 3], c = t[(k + 2) % 3];
      const double ta = b[(k + 1) % 3], tc = b[(k + 2) % 3];
      const int e = find_edge(a, c);
      const double along = tc / (ta + tc);  // ratio from a to c
      return snap_edge(e, a < c ? along : 1.0 - along);
    }
    Ref r;
    r.kind = Kind::Face;
    r.f = p.face;
    r.b = b;
    return r;
  }
  if (p.v0 < 0 || p.v0 >= nv || p.v1 < 0 || p.v1 >= nv) {
    throw InvalidInput(fmt::format("split_mesh_along_path: {} refers to vertices ({}, {}), "
                                   "but the mesh has {} vertices",
                                   point_name(i), p.v0, p.v1, nv));
  }
  if (p.v0 == p.v1) {
    Ref r;
    r.v = p.v0;
    return r;
  }
  const int e = find_edge(p.v0, p.v1);
  if (e < 0) {
    throw InvalidInput(fmt::format("split_mesh_along_path: {} lies on ({}, {}), which is "
                                   "not an edge of the mesh",
                                   point_name(i), p.v0, p.v1));
  }
  if (!std::isfinite(p.ratio) || p.ratio < -1e-9 || p.ratio > 1.0 + 1e-9) {
    throw InvalidInput(fmt::format("split_mesh_along_path: {} on edge ({}, {}) has ratio "
                                   "{}; it must be in [0, 1]",
                                   point_name(i), p.v0, p.v1, p.ratio));
  }
  const double t = std::clamp(p.ratio, 0.0, 1.0);
  return snap_edge(e, p.v0 < p.v1 ? t : 1.0 - t);
}

std::vector<int> Splitter::faces_of(const Ref& r) const {
  switch (r.kind) {
    case Kind::Vertex: {
      std::vector<int> fs = he_.vertex_faces(r.v);
      std::sort(fs.begin(), fs.end());
      return fs;
    }
    case Kind::Edge: {
      const int h = edge_h_[r.e];
      const int o = he_.opposite(h);
      std::vector<int> fs{he_.face(h)};
      if (o >= 0) fs.push_back(he_.face(o));
      std::sort(fs.begin(), fs.end());
      return fs;
    }
    case Kind::Face:
      return {r.f};
  }
  return {};
}

bool Splitter::triangulate_simple(const std::array<std::vector<int>, 3>& sides,
                                  const std::vector<std::pair<int, int>>& chords, int f) {
  // Algorithm 2.1: split the face at the points of each side in turn.
  const auto& t = mesh_.faces[f];
  std::vector<std::array<int, 3>> tris{t};
  for (int k = 0; k < 3; ++k) {
    int x = t[k];
    const int y = t[(k + 1) % 3];
    for (int q : sides[k]) {
      bool done = false;
      for (size_t i = 0; i < tris.size() && !done; ++i) {
        for (int c = 0; c < 3; ++c) {
          if (tris[i][c] == x && tris[i][(c + 1) % 3] == y) {
            const int z = tris[i][(c + 2) % 3];
            tris[i] = {x, q, z};
            tris.push_back({q, y, z});
            done = true;
            break;
          }
        }
      }
      if (!done) return false;  // cannot happen for a proper triangle; be safe
      x = q;
    }
  }
  auto has_edge = [&](int a, int b) {
    for (const auto& tri : tris)
      for (int c = 0; c < 3; ++c)
        if ((tri[c] == a && tri[(c + 1) % 3] == b) || (tri[c] == b && tri[(c + 1) % 3] == a)) return true;
    return false;
  };
  for (const auto& [a, b] : chords)
    if (!has_edge(a, b)) return false;
  for (const auto& tri : tris) {
    out_.mesh.faces.push_back(tri);
    out_.face_origin.push_back(f);
  }
  ++out_.faces_split_simple;
  return true;
}

void Splitter::triangulate_constrained(int f, const std::vector<int>& polygon,
                                       const std::vector<Vec2>& polygon_2d,
                                       const std::vector<int>& interior,
                                       const std::vector<Vec2>& interior_2d,
                                       const std::vector<std::pair<int, int>>& chords) {
  Cdt cdt;
  std::unordered_map<int, Cdt::Vertex_handle> handle;
  auto add = [&](int vid, const Vec2& p) {
    const auto before = cdt.number_of_vertices();
    auto vh = cdt.insert(Point2(p.x(), p.y()));
    if (cdt.number_of_vertices() == before) {
      throw InvalidInput(fmt::format("split_mesh_along_path: path vertices {} and {} coincide inside "
                                     "face {}; remove the repeated point from the path",
                                     vh->info() - 1, vid, f));
    }
    vh->info() = vid + 1;  // 0 would mark the infinite vertex
    handle[vid] = vh;
  };
  for (size_t i = 0; i < polygon.size(); ++i) add(polygon[i], polygon_2d[i]);
  for (size_t i = 0; i < interior.size(); ++i) add(interior[i], interior_2d[i]);
  const int nb = static_cast<int>(polygon.size());
  std::unordered_map<std::uint64_t, char> boundary;
  try {
    for (int i = 0; i < nb; ++i) {
      const int a = polygon[i], b = polygon[(i + 1) % nb];
      boundary[undirected_edge_key(a, b)] = 1;
      cdt.insert_constraint(handle.at(a), handle.at(b));
    }
    for (const auto& [a, b] : chords) {
      if (boundary.count(undirected_edge_key(a, b))) continue;
      cdt.insert_constraint(handle.at(a), handle.at(b));
    }
  } catch (const Cdt::Intersection_of_constraints_exception&) {
    throw InvalidInput(fmt::format("split_mesh_along_path: path segments cross each other inside face "
                                   "{} of the input mesh; the path must not intersect itself",
                                   f));
  }
  // Flood the outside from the infinite faces without crossing the polygon
  // boundary; what remains is the face's interior.
  for (auto fh = cdt.all_faces_begin(); fh != cdt.all_faces_end(); ++fh) fh->info() = 0;
  std::vector<Cdt::Face_handle> stack;
  for (auto fh = cdt.all_faces_begin(); fh != cdt.all_faces_end(); ++fh) {
    if (cdt.is_infinite(fh)) {
      fh->info() = 1;
      stack.push_back(fh);
    }
  }
  while (!stack.empty()) {
    auto fh = stack.back();
    stack.pop_back();
    for (int i = 0; i < 3; ++i) {
      auto nb_face = fh->neighbor(i);
      if (nb_face->info() != 0) continue;
      const auto va = fh->vertex(Cdt::cw(i)), vb = fh->vertex(Cdt::ccw(i));
      if (!cdt.is_infinite(va) && !cdt.is_infinite(vb) &&
          boundary.count(undirected_edge_key(va->info() - 1, vb->info() - 1))) {
        continue;
      }
      nb_face->info() = 1;
      stack.push_back(nb_face);
    }
  }
  std::vector<std::array<int, 3>> tris;
  for (auto fh = cdt.finite_faces_begin(); fh != cdt.finite_faces_end(); ++fh) {
    if (fh->info() != 0) continue;
    tris.push_back({fh->vertex(0)->info() - 1, fh->vertex(1)->info() - 1, fh->vertex(2)->info() - 1});
  }
  const int expected = nb + 2 * static_cast<int>(interior.size()) - 2;
  bool ok = static_cast<int>(tris.size()) == expected &&
            static_cast<int>(cdt.number_of_vertices()) == nb + static_cast<int>(interior.size());
  for (const auto& tri : tris)
    if (tri[0] < 0 || tri[1] < 0 || tri[2] < 0) ok = false;
  if (!ok) {
    throw SolverError(fmt::format("split_mesh_along_path: the constrained triangulation of face {} "
                                  "gave {} triangles instead of {}; the face may be degenerate",
                                  f, tris.size(), expected));
  }
  for (const auto& [a, b] : chords) {
    bool found = false;
    for (const auto& tri : tris)
      for (int c = 0; c < 3 && !found; ++c)
        found = (tri[c] == a && tri[(c + 1) % 3] == b) || (tri[c] == b && tri[(c + 1) % 3] == a);
    if (!found) {
      throw InvalidInput(fmt::format("split_mesh_along_path: the path segment between vertices {} and "
                                     "{} passes through another path point inside face {}; the path "
                                     "must not touch itself",
                                     a, b, f));
    }
  }
  // Deterministic order: sort the triangles (rotated to start at their
  // smallest vertex, which keeps the orientation).
  for (auto& tri : tris) std::rotate(tri.begin(), std::min_element(tri.begin(), tri.end()), tri.end());
  std::sort(tris.begin(), tris.end());
  for (const auto& tri : tris) {
    out_.mesh.faces.push_back(tri);
    out_.face_origin.push_back(f);
  }
  ++out_.faces_split_constrained;
}

void Splitter::triangulate_face(int f, const std::vector<std::pair<int, int>>& chords) {
  const auto& t = mesh_.faces[f];
  std::array<std::vector<int>, 3> sides;
  std::array<std::vector<double>, 3> side_s;  // ratio along the half-edge
  std::vector<int> polygon;
  for (int k = 0; k < 3; ++k) {
    const int a = t[k], b = t[(k + 1) % 3];
    polygon.push_back(a);
    const int e = find_edge(a, b);
    const auto it = clusters_on_edge_.find(e);
    if (it == clusters_on_edge_.end()) continue;
    std::vector<int> ids = it->second;
    if (a > b) std::reverse(ids.begin(), ids.end());
    for (int c : ids) {
      sides[k].push_back(edge_clusters_[c].vid);
      side_s[k].push_back(a < b ? edge_clusters_[c].s : 1.0 - edge_clusters_[c].s);
      polygon.push_back(edge_clusters_[c].vid);
    }
  }
  std::vector<int> interior;
  std::vector<std::array<double, 3>> interior_b;
  if (const auto it = clusters_in_face_.find(f); it != clusters_in_face_.end()) {
    for (int c : it->second) {
      interior.push_back(face_clusters_[c].vid);
      interior_b.push_back(face_clusters_[c].b);
    }
  }
  if (interior.empty() && triangulate_simple(sides, chords, f)) return;

  // Plane frame of the face (isometric); the affine frame of the reference
  // triangle for degenerate faces.
  const Vec3& pa = mesh_.vertices[t[0]];
  const Vec3& pb = mesh_.vertices[t[1]];
  const Vec3& pc = mesh_.vertices[t[2]];
  const Vec3 n = (pb - pa).cross(pc - pa);
  const double longest2 =
      std::max({(pb - pa).squaredNorm(), (pc - pb).squaredNorm(), (pa - pc).squaredNorm()});
  std::array<Vec2, 3> c2;
  if (n.norm() > 1e-12 * longest2 && longest2 > 0.0) {
    const Vec3 ex = (pb - pa).normalized();
    const Vec3 ey = n.normalized().cross(ex);
    c2 = {Vec2(0.0, 0.0), Vec2((pb - pa).norm(), 0.0), Vec2((pc - pa).dot(ex), (pc - pa).dot(ey))};
  } else {
    c2 = {Vec2(0.0, 0.0), Vec2(1.0, 0.0), Vec2(0.0, 1.0)};
  }
  std::vector<Vec2> polygon_2d;
  for (int k = 0; k < 3; ++k) {
    polygon_2d.push_back(c2[k]);
    for (double s : side_s[k]) polygon_2d.push_back((1.0 - s) * c2[k] + s * c2[(k + 1) % 3]);
  }
  std::vector<Vec2> interior_2d;
  for (const auto& b : interior_b) interior_2d.push_back(b[0] * c2[0] + b[1] * c2[1] + b[2] * c2[2]);
  triangulate_constrained(f, polygon, polygon_2d, interior, interior_2d, chords);
}

SplitMeshResult Splitter::run() {
  const int n = static_cast<int>(path_.size());
  const int nv = mesh_.num_vertices();
  out_.original_num_vertices = nv;
  out_.mesh.vertices = mesh_.vertices;

  std::vector<Ref> refs(n);
  for (int i = 0; i < n; ++i) refs[i] = normalize(i);

  // Cluster the points of each edge (sorted by parameter) and each face.
  {
    std::unordered_map<int, std::vector<int>> on_edge, in_face;
    std::vector<int> edges_used, faces_used;
    for (int i = 0; i < n; ++i) {
      if (refs[i].kind == Kind::Edge) {
        auto& v = on_edge[refs[i].e];
        if (v.empty()) edges_used.push_back(refs[i].e);
        v.push_back(i);
      } else if (refs[i].kind == Kind::Face) {
        auto& v = in_face[refs[i].f];
        if (v.empty()) faces_used.push_back(refs[i].f);
        v.push_back(i);
      }
    }
    for (int e : edges_used) {
      auto& pts = on_edge[e];
      std::stable_sort(pts.begin(), pts.end(), [&](int a, int b) { return refs[a].s < refs[b].s; });
      auto& ids = clusters_on_edge_[e];
      for (int i : pts) {
        if (ids.empty() || refs[i].s - edge_clusters_[ids.back()].s >= snap_) {
          ids.push_back(static_cast<int>(edge_clusters_.size()));
          edge_clusters_.push_back(EdgeCluster{e, refs[i].s, -1});
        }
        refs[i].cluster = ids.back();
      }
    }
    for (int f : faces_used) {
      auto& ids = clusters_in_face_[f];
      for (int i : in_face[f]) {
        int found = -1;
        for (int c : ids) {
          const auto& b = face_clusters_[c].b;
          if (std::abs(b[0] - refs[i].b[0]) < snap_ && std::abs(b[1] - refs[i].b[1]) < snap_ &&
              std::abs(b[2] - refs[i].b[2]) < snap_) {
            found = c;
            break;
          }
        }
        if (found < 0) {
          found = static_cast<int>(face_clusters_.size());
          ids.push_back(found);
          face_clusters_.push_back(FaceCluster{f, refs[i].b, -1});
        }
        refs[i].cluster = found;
      }
    }
  }

  // New vertices in path order.
  out_.point_vertices.resize(n);
  for (int i = 0; i < n; ++i) {
    Ref& r = refs[i];
    if (r.kind == Kind::Vertex) {
      out_.point_vertices[i] = r.v;
      continue;
    }
    int* vid = r.kind == Kind::Edge ? &edge_clusters_[r.cluster].vid : &face_clusters_[r.cluster].vid;
    if (*vid < 0) {
      *vid = out_.mesh.num_vertices();
      MeshPoint sp;
      if (r.kind == Kind::Edge) {
        const EdgeCluster& c = edge_clusters_[r.cluster];
        sp = MeshPoint::on_edge(edge_lo_[c.e], edge_hi_[c.e], c.s);
      } else {
        const FaceCluster& c = face_clusters_[r.cluster];
        sp = MeshPoint::in_face(c.f, c.b);
      }
      out_.mesh.vertices.push_back(mesh_point_position(mesh_, sp));
      out_.new_vertex_origin.push_back(sp);
    }
    out_.point_vertices[i] = *vid;
  }

  // Path segments: along an edge (through the points on it) or across a face.
  std::unordered_map<int, std::vector<std::pair<int, int>>> chords;
  std::vector<char> touched(mesh_.num_faces(), 0);
  for (const auto& c : edge_clusters_) {
    const int h = edge_h_[c.e];
    touched[he_.face(h)] = 1;
    if (he_.opposite(h) >= 0) touched[he_.face(he_.opposite(h))] = 1;
  }
  for (const auto& c : face_clusters_) touched[c.f] = 1;

  auto edge_param = [&](const Ref& r, int e) {  // parameter of r along edge e (r on e)
    if (r.kind == Kind::Edge) return edge_clusters_[r.cluster].s;
    return r.v == edge_lo_[e] ? 0.0 : 1.0;
  };
  const int num_paths = static_cast<int>(path_start_.size()) - 1;
  out_.paths.resize(num_paths);
  for (int k = 0; k < num_paths; ++k) {
  std::vector<int>& out_path = out_.paths[k];
  if (path_start_[k + 1] > path_start_[k]) out_path.push_back(out_.point_vertices[path_start_[k]]);
  for (int i = path_start_[k]; i + 1 < path_start_[k + 1]; ++i) {
    const Ref& p = refs[i];
    const Ref& q = refs[i + 1];
    const int vp = out_.point_vertices[i], vq = out_.point_vertices[i + 1];
    if (vp == vq) continue;
    int along = -1;
    if (p.kind == Kind::Vertex && q.kind == Kind::Vertex) {
      along = find_edge(p.v, q.v);
    } else if (p.kind == Kind::Edge && q.kind == Kind::Edge) {
      if (p.e == q.e) along = p.e;
    } else if (p.kind == Kind::Vertex && q.kind == Kind::Edge) {
      if (edge_lo_[q.e] == p.v || edge_hi_[q.e] == p.v) along = q.e;
    } else if (p.kind == Kind::Edge && q.kind == Kind::Vertex) {
      if (edge_lo_[p.e] == q.v || edge_hi_[p.e] == q.v) along = p.e;
    }
    if (along >= 0) {
      const double sp = edge_param(p, along), sq = edge_param(q, along);
      if (const auto it = clusters_on_edge_.find(along); it != clusters_on_edge_.end()) {
        std::vector<int> ids = it->second;
        if (sq < sp) std::reverse(ids.begin(), ids.end());
        for (int c : ids) {
          const double s = edge_clusters_[c].s;
          if ((s - sp) * (sq - s) > 0.0 && edge_clusters_[c].vid != vp && edge_clusters_[c].vid != vq)
            out_path.push_back(edge_clusters_[c].vid);
        }
      }
      out_path.push_back(vq);
      continue;
    }
    const std::vector<int> fp = faces_of(p), fq = faces_of(q);
    std::vector<int> common;
    std::set_intersection(fp.begin(), fp.end(), fq.begin(), fq.end(), std::back_inserter(common));
    if (common.empty()) {
      const std::string which = num_paths > 1 ? fmt::format(" of path {}", k) : "";
      const int i0 = i - path_start_[k];
      throw InvalidInput(fmt::format("split_mesh_along_path: {} {} and {}{} do not lie on a "
                                     "common face; consecutive points must share a face (insert the "
                                     "points where the path crosses the edges in between)",
                                     num_paths > 1 ? "points" : "path points", i0, i0 + 1, which));
    }
    const int f = common.front();
    auto& list = chords[f];
    const auto key = std::minmax(vp, vq);
    if (std::find(list.begin(), list.end(), std::pair<int, int>(key.first, key.second)) == list.end())
      list.emplace_back(key.first, key.second);
    touched[f] = 1;
    out_path.push_back(vq);
  }
  }
  if (num_paths > 0) out_.path = out_.paths[0];

  static const std::vector<std::pair<int, int>> kNoChords;
  for (int f = 0; f < mesh_.num_faces(); ++f) {
    if (!touched[f]) {
      out_.mesh.faces.push_back(mesh_.faces[f]);
      out_.face_origin.push_back(f);
      continue;
    }
    const auto it = chords.find(f);
    triangulate_face(f, it == chords.end() ? kNoChords : it->second);
  }
  return std::move(out_);
}

}  // namespace

SplitMeshResult split_mesh_along_path(const TriMesh& mesh, const std::vector<MeshPoint>& path,
                                      const SplitOptions& options) {
  return split_mesh_along_paths(mesh, {path}, options);
}

SplitMeshResult split_mesh_along_paths(const TriMesh& mesh, const std::vector<std::vector<MeshPoint>>& paths,
                                       const SplitOptions& options) {
  if (!std::isfinite(options.snap) || options.snap < 0.0 || options.snap >= 0.25) {
    throw InvalidInput(fmt::format("split_mesh_along_path: snap must be in [0, 0.25), got {}", options.snap));
  }
  std::vector<MeshPoint> points;
  std::vector<int> start{0};
  for (const auto& path : paths) {
    points.insert(points.end(), path.begin(), path.end());
    start.push_back(static_cast<int>(points.size()));
  }
  Splitter splitter(mesh, points, std::move(start), options);
  return splitter.run();
}

std::vector<double> carry_vertex_scalar(const TriMesh& original, const SplitMeshResult& split,
                                        const std::vector<double>& values) {
  if (static_cast<int>(values.size()) != split.original_num_vertices ||
      original.num_vertices() != split.original_num_vertices) {
    throw InvalidInput(fmt::format("carry_vertex_scalar: {} values for a mesh of {} vertices (the "
                                   "split was made from a mesh of {} vertices)",
                                   values.size(), original.num_vertices(), split.original_num_vertices));
  }
  std::vector<double> out(values);
  out.reserve(values.size() + split.new_vertex_origin.size());
  for (const MeshPoint& p : split.new_vertex_origin) out.push_back(mesh_point_value(original, values, p));
  return out;
}

}  // namespace knitforge
