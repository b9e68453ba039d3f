// Regression tests of the window pruning in geodesic_propagation.cpp (end-
// vertex trimming, the vertex filter, merging only near flat vertices):
// exact agreement with CGAL's Surface_mesh_shortest_path on irregular curved
// meshes with many saddles, and on a mesh mixing flat and curved parts.
#include <gtest/gtest.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Surface_mesh_shortest_path.h>

#include <cmath>
#include <cstdint>
#include <vector>

#include "knitforge/geometry/geodesic_distance.h"
#include "knitforge/geometry/geodesic_source.h"
#include "knitforge/geometry/shapes.h"

namespace knitforge {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using CgalMesh = CGAL::Surface_mesh<Kernel::Point_3>;
using Traits = CGAL::Surface_mesh_shortest_path_traits<Kernel, CgalMesh>;
using ShortestPaths = CGAL::Surface_mesh_shortest_path<Traits>;

// CGAL's exact distances at every vertex from vertex s.
std::vector<double> cgal_vertex_distances(const TriMesh& m, int s) {
  CgalMesh c;
  std::vector<CgalMesh::Vertex_index> vs;
  for (const Vec3& p : m.vertices) vs.push_back(c.add_vertex(Kernel::Point_3(p.x(), p.y(), p.z())));
  for (const auto& f : m.faces) c.add_face(vs[f[0]], vs[f[1]], vs[f[2]]);
  ShortestPaths sp(c);
  sp.add_source_point(vs[s]);
  std::vector<double> d;
  for (auto v : c.vertices()) d.push_back(sp.shortest_distance_to_source_points(v).first);
  return d;
}

// Deterministic noise in [-1, 1].
double noise(uint64_t& state) {
  state = state * 6364136223846793005ull + 1442695040888963407ull;
  return static_cast<double>(state >> 11) / static_cast<double>(uint64_t{1} << 52) - 1.0;
}

double max_error(const TriMesh& m, int s) {
  const GeodesicField f = geodesic_distance(m, source_from_vertex(m, s));
  const std::vector<double> ref = cgal_vertex_distances(m, s);
  double err = 0.0;
  for (int v = 0; v < m.num_vertices(); ++v) err = std::max(err, std::abs(f.distance[v] - ref[v]));
  return err;
}

// A scan-like surface: the triple-peak with every vertex moved up or down by
// up to 0.8 mm, so that about half the vertices are saddles that emit windows
// and the wavefront is split everywhere.
TEST(GeodesicPruning, NoisySurfaceMatchesCgal) {
  TriMesh m = triple_peak(8.0);
  uint64_t state = 12345;
  for (Vec3& p : m.vertices) p.z() += 0.8 * noise(state);
  for (int s : {0, m.num_vertices() / 3, (2 * m.num_vertices()) / 3})
    EXPECT_LT(max_error(m, s), 1e-9 * 150.0) << "source vertex " << s;
}

// A flat rectangle with a bump in the middle: windows are merged on the flat
// part (and must still be exact around the bump, where they are not).
TEST(GeodesicPruning, FlatWithBumpMatchesCgalAndMergesOnFlatPart) {
  TriMesh m = rectangle(120.0, 80.0, 6.0);
  for (Vec3& p : m.vertices) {
    const double r2 = (p.x() * p.x() + p.y() * p.y()) / (25.0 * 25.0);
    if (r2 < 1.0) p.z() = 12.0 * (1.0 - r2) * (1.0 - r2);
  }
  int corner = 0;
  for (int v = 0; v < m.num_vertices(); ++v)
    if (m.vertices[v].x() + m.vertices[v].y() < m.vertices[corner].x() + m.vertices[corner].y()) corner = v;
  EXPECT_LT(max_error(m, corner), 1e-9 * 150.0);
  EXPECT_LT(max_error(m, m.num_vertices() / 2), 1e-9 * 150.0);
  // On the plain flat rectangle every window piece meets its neighbours again
  // and is merged: the window count stays a small multiple of the faces.
  const TriMesh flat = rectangle(120.0, 80.0, 6.0);
  const GeodesicField f = geodesic_distance(flat, source_from_vertex(flat, 0));
  EXPECT_LT(f.num_windows, static_cast<size_t>(4 * flat.num_faces()));
}

}  // namespace
}  // namespace knitforge
