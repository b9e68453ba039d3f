#include "knitforge/geometry/cut_mesh_along_path.h"

#include <algorithm>
#include <string>

#include <fmt/core.h>

#include "knitforge/geometry/halfedges.h"
#include "knitforge/util/errors.h"

namespace knitforge {

CutMeshResult cut_mesh_along_path(const TriMesh& mesh, const std::vector<int>& path) {
  return cut_mesh_along_paths(mesh, {path});
}

CutMeshResult cut_mesh_along_paths(const TriMesh& mesh, const std::vector<std::vector<int>>& paths) {
  const int nv = mesh.num_vertices();
  if (paths.empty()) throw InvalidInput("cut_mesh_along_paths: no path to cut along");
  for (size_t p = 0; p < paths.size(); ++p) {
    const std::vector<int>& path = paths[p];
    const int np = static_cast<int>(path.size());
    const std::string which = paths.size() > 1 ? fmt::format(" {}", p) : "";
    if (np < 2) {
      throw InvalidInput(fmt::format("cut_mesh_along_path: the path{} has {} vertices; a cut needs at least two",
                                     which, np));
    }
    for (int i = 0; i < np; ++i) {
      if (path[i] < 0 || path[i] >= nv) {
        throw InvalidInput(fmt::format("cut_mesh_along_path: path{} vertex {} (position {}) is out of range; "
                                       "the mesh has {} vertices",
                                       which, path[i], i, nv));
      }
    }
  }
  const Halfedges he = build_halfedges(nv, mesh.faces);
  // An outgoing half-edge per vertex, the boundary one when there is one:
  // rotation around the vertex starts there and visits all its half-edges.
  std::vector<int> out_h(nv, -1);
  for (int h = 0; h < he.num_halfedges(); ++h) {
    const int v = he.from(h);
    if (out_h[v] < 0 || he.opposite(h) < 0) out_h[v] = h;
  }
  auto find_h = [&](int a, int b) {  // the half-edge a -> b, or -1
    const int h0 = out_h[a];
    if (h0 < 0) return -1;
    int h = h0;
    do {
      if (he.to(h) == b) return h;
      h = he.opposite(he.prev(h));
    } while (h >= 0 && h != h0);
    return -1;
  };

  CutMeshResult out;
  std::vector<char> cut(he.num_edges(), 0);
  for (size_t p = 0; p < paths.size(); ++p) {
    const std::vector<int>& path = paths[p];
    const std::string which = paths.size() > 1 ? fmt::format(" of path {}", p) : "";
    for (size_t i = 0; i + 1 < path.size(); ++i) {
      const int a = path[i], b = path[i + 1];
      if (a == b) {
        throw InvalidInput(fmt::format("cut_mesh_along_path: path positions {} and {}{} are the same vertex "
                                       "{}; remove the repetition",
                                       i, i + 1, which, a));
      }
      const int hab = find_h(a, b), hba = find_h(b, a);
      if (hab < 0 && hba < 0) {
        throw InvalidInput(fmt::format("cut_mesh_along_path: path vertices {} and {} (positions {} and {}{}) "
                                       "are not joined by a mesh edge; split the mesh along the path "
                                       "first (split_mesh_along_path)",
                                       a, b, i, i + 1, which));
      }
      if (hab >= 0 && hba >= 0 && !cut[he.edge(hab)]) {
        cut[he.edge(hab)] = 1;
        ++out.num_cut_edges;
      }
    }
  }

  std::vector<int> corner_vertex(3 * static_cast<size_t>(mesh.num_faces()));
  for (int f = 0; f < mesh.num_faces(); ++f)
    for (int k = 0; k < 3; ++k) corner_vertex[3 * f + k] = mesh.faces[f][k];
  out.mesh.vertices = mesh.vertices;
  out.vertex_origin.resize(nv);
  for (int v = 0; v < nv; ++v) out.vertex_origin[v] = v;

  std::vector<int> verts;
  for (const auto& path : paths) verts.insert(verts.end(), path.begin(), path.end());
  std::sort(verts.begin(), verts.end());
  verts.erase(std::unique(verts.begin(), verts.end()), verts.end());
  std::vector<int> hs;
  for (int v : verts) {
    if (out_h[v] < 0) continue;
    hs.clear();
    const int h0 = out_h[v];
    int h = h0;
    do {
      hs.push_back(h);
      h = he.opposite(he.prev(h));
    } while (h >= 0 && h != h0);
    const bool boundary = he.opposite(h0) < 0;
    const int k = static_cast<int>(hs.size());
    // cut_after[i]: the edge between the faces of hs[i] and hs[i+1] is cut.
    auto cut_after = [&](int i) { return cut[he.edge(he.prev(hs[i]))] != 0; };
    int first = 0;
    if (!boundary) {
      int i0 = -1;
      for (int i = 0; i < k && i0 < 0; ++i)
        if (cut_after(i)) i0 = i;
      if (i0 < 0) continue;
      first = (i0 + 1) % k;
    }
    int wedge_vertex = v;
    for (int j = 0; j < k; ++j) {
      const int idx = (first + j) % k;
      const int hh = hs[idx];
      corner_vertex[3 * he.face(hh) + he.corner(hh)] = wedge_vertex;
      const bool last = j + 1 == k;
      if (!last && cut_after(idx)) {
        wedge_vertex = out.mesh.num_vertices();
        out.mesh.vertices.push_back(mesh.vertices[v]);
        out.vertex_origin.push_back(v);
      }
    }
  }
  out.mesh.faces.resize(mesh.num_faces());
  for (int f = 0; f < mesh.num_faces(); ++f)
    for (int k = 0; k < 3; ++k) out.mesh.faces[f][k] = corner_vertex[3 * f + k];

  // The two sides of the paths, path after path.
  auto corner_at = [&](int h, int v) {  // the corner of face(h) at vertex v (v an end of h)
    const int hh = he.from(h) == v ? h : he.next(h);
    return corner_vertex[3 * he.face(hh) + he.corner(hh)];
  };
  for (const auto& path : paths) {
    const int np = static_cast<int>(path.size());
    for (int i = 0; i < np; ++i) {
      const int a = i + 1 < np ? path[i] : path[i - 1];
      const int b = i + 1 < np ? path[i + 1] : path[i];
      const int hab = find_h(a, b), hba = find_h(b, a);
      out.left.push_back(hab >= 0 ? corner_at(hab, path[i]) : -1);
      out.right.push_back(hba >= 0 ? corner_at(hba, path[i]) : -1);
    }
  }

  // Components: faces joined by edges that were not cut.
  out.face_component.assign(mesh.num_faces(), -1);
  std::vector<int> stack;
  for (int f0 = 0; f0 < mesh.num_faces(); ++f0) {
    if (out.face_component[f0] >= 0) continue;
    out.face_component[f0] = out.num_components;
    stack.push_back(f0);
    while (!stack.empty()) {
      const int f = stack.back();
      stack.pop_back();
      for (int k = 0; k < 3; ++k) {
        const int h = he.halfedge(f, k);
        const int o = he.opposite(h);
        if (o < 0 || cut[he.edge(h)]) continue;
        const int g = he.face(o);
        if (out.face_component[g] < 0) {
          out.face_component[g] = out.num_components;
          stack.push_back(g);
        }
      }
    }
    ++out.num_components;
  }
  return out;
}

}  // namespace knitforge
