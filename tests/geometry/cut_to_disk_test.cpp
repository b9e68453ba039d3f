#include "knitforge/geometry/cut_to_disk.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <numbers>
#include <string>

#include <gtest/gtest.h>

#include "geometry/test_meshes.h"
#include "knitforge/geometry/geodesic_distance.h"
#include "knitforge/geometry/halfedges.h"
#include "knitforge/geometry/mesh_measures.h"
#include "knitforge/geometry/shapes.h"
#include "knitforge/geometry/surface_checks.h"
#include "knitforge/util/errors.h"

namespace knitforge {
namespace {

constexpr double kPi = std::numbers::pi;

// What every result must be: a disk with the input's area, vertices that
// are where their origin is, seams that end on the input's boundary.
void check_disk(const TriMesh& in, const CutToDisk& c) {
  const SurfaceReport r = validate_surface(c.mesh);
  EXPECT_TRUE(r.is_disk) << r.summary();
  EXPECT_NEAR(total_area(c.mesh), total_area(in), 1e-9 * total_area(in));
  ASSERT_EQ(c.vertex_origin.size(), static_cast<size_t>(c.mesh.num_vertices()));
  for (int v = 0; v < c.mesh.num_vertices(); ++v) {
    const int o = c.vertex_origin[v];
    if (o >= 0) {
      EXPECT_EQ(c.mesh.vertices[v], in.vertices[o]);
    }
    if (v < in.num_vertices()) {
      EXPECT_EQ(o, v);
    }
  }
  for (const Seam& s : c.seams) {
    double len = 0.0;
    for (size_t i = 1; i < s.path.size(); ++i) len += (s.path[i] - s.path[i - 1]).norm();
    EXPECT_NEAR(s.length, len, 1e-9 * (1.0 + len));
  }
}

bool source_point_near(const TriMesh& m, const GeodesicSource& s,
                       const std::function<bool(const Vec3&)>& pred) {
  for (const auto& line : s.polylines)
    for (const SurfacePoint& p : line)
      if (!pred(surface_point_position(m, p))) return false;
  return true;
}

// The tube: one seam from rim to rim, as long as the tube is high.
TEST(CutToDisk, TubeGetsOneSeamBetweenItsRims) {
  const TriMesh tube = open_tube(20.0, 30.0, 2.5);
  const CutToDisk c = cut_to_disk(tube);
  check_disk(tube, c);
  EXPECT_EQ(c.input_boundary_loops, 2);
  EXPECT_EQ(c.input_genus, 0);
  ASSERT_EQ(c.seams.size(), 1u);
  EXPECT_EQ(c.seams[0].kind, SeamKind::Loops);
  EXPECT_FALSE(c.seams[0].on_source);
  // Straight up, up to the bends where the staggered bands of the faceted
  // cylinder meet.
  EXPECT_NEAR(c.seams[0].length, 30.0, 0.001 * 30.0);
  EXPECT_NEAR(std::min(c.seams[0].path.front().z(), c.seams[0].path.back().z()), 0.0, 1e-9);
  EXPECT_NEAR(std::max(c.seams[0].path.front().z(), c.seams[0].path.back().z()), 30.0, 1e-9);
  // The boundary of the disk is both rims and the two lips.
  double boundary = 0.0;
  const Halfedges he = build_halfedges(c.mesh.num_vertices(), c.mesh.faces);
  for (int h = 0; h < he.num_halfedges(); ++h)
    if (he.is_boundary_halfedge(h))
      boundary += (c.mesh.vertices[he.to(h)] - c.mesh.vertices[he.from(h)]).norm();
  double rims = 0.0;
  const Halfedges he0 = build_halfedges(tube.num_vertices(), tube.faces);
  for (int h = 0; h < he0.num_halfedges(); ++h)
    if (he0.is_boundary_halfedge(h)) rims += (tube.vertices[he0.to(h)] - tube.vertices[he0.from(h)]).norm();
  EXPECT_NEAR(boundary, rims + 2.0 * c.seams[0].length, 1e-9 * boundary);
  // A disk is returned as it is.
  const TriMesh disk = flat_disk(20.0, 4.0);
  const CutToDisk same = cut_to_disk(disk);
  EXPECT_TRUE(same.seams.empty());
  EXPECT_EQ(same.mesh.faces, disk.faces);
}

// The cap with the source on its symmetry plane: the plane meets both rims
// twice, so two pieces of it join them; the seam follows the shorter (the
// 15 degrees of the front meridian under the chin, 23.6 mm) or, asked for,
// the longer (face to neck over the crown and down the back, 195 degrees);
// the rest of the plane section is the carried source.
TEST(CutToDisk, CapSeamOnTheSymmetryPlane) {
  const TriMesh m = cap(CapShape{}, 5.0);
  const GeodesicSource plane = source_from_plane(m, Vec3(1, 0, 0), 0.0);
  for (const bool longest : {false, true}) {
    SCOPED_TRACE(longest ? "longest" : "shortest");
    CutToDiskOptions o;
    o.source = plane;
    o.longest_source_seam = longest;
    const CutToDisk c = cut_to_disk(m, o);
    check_disk(m, c);
    EXPECT_EQ(c.source_seam_candidates, 2);
    ASSERT_EQ(c.seams.size(), 1u);
    EXPECT_TRUE(c.seams[0].on_source);
    for (const Vec3& p : c.seams[0].path) EXPECT_NEAR(p.x(), 0.0, 1e-9);
    const double arc = (longest ? 195.0 : 15.0) * kPi / 180.0 * 90.0;
    EXPECT_NEAR(c.seams[0].length, arc, 0.01 * arc);
    EXPECT_FALSE(c.source_on_seam);
    ASSERT_EQ(c.source.polylines.size(), 1u);
    EXPECT_NEAR(c.source.length(c.mesh), (longest ? 15.0 : 195.0) * kPi / 180.0 * 90.0, 0.02 * arc);
    // The source is the other piece: under the chin or over the crown.
    EXPECT_TRUE(source_point_near(c.mesh, c.source, [&](const Vec3& p) {
      return std::abs(p.x()) < 1e-9 && (longest ? (p.y() < 0 && p.z() < -50) : !(p.y() < 0 && p.z() < -50));
    }));
    // It cuts the disk in two, with the sides of the plane.
    ASSERT_EQ(c.source.vertex_side.size(), static_cast<size_t>(c.mesh.num_vertices()));
    for (int v = 0; v < c.mesh.num_vertices(); ++v) {
      const double x = c.mesh.vertices[v].x();
      if (std::abs(x) > 1e-6) {
        EXPECT_EQ(c.source.vertex_side[v], x > 0 ? 1 : -1);
      }
    }
    EXPECT_NO_THROW(geodesic_distance(c.mesh, c.source));
  }
}

// A source that crosses the seam (a ring around the tube) is broken there:
// one open polyline from one lip to the other, signed (above / below).
TEST(CutToDisk, SourceCrossingTheSeamIsOpenedThere) {
  const TriMesh tube = open_tube(20.0, 30.0, 2.5);
  CutToDiskOptions o;
  o.source = source_from_plane(tube, Vec3(0, 0, 1), 15.0);
  const CutToDisk c = cut_to_disk(tube, o);
  check_disk(tube, c);
  ASSERT_EQ(c.source.polylines.size(), 1u);
  const auto& line = c.source.polylines[0];
  const Vec3 a = surface_point_position(c.mesh, line.front()),
             b = surface_point_position(c.mesh, line.back());
  EXPECT_EQ(a, b);  // the two lips of the seam
  EXPECT_GT(c.source.length(c.mesh), 0.99 * 2.0 * kPi * 20.0);
  EXPECT_FALSE(c.source.vertex_side.empty());
  const GeodesicField f = geodesic_distance(c.mesh, c.source);
  for (int v = 0; v < c.mesh.num_vertices(); v += 37) {
    const double dz = c.mesh.vertices[v].z() - 15.0;
    EXPECT_NEAR(f.distance[v], dz, 0.001 * std::abs(dz) + 1e-9);  // the faceted cylinder's bends
  }
}

// When the source is all on the seam it is kept on one lip of it.
TEST(CutToDisk, SourceOnlyOnTheSeamStaysOnOneLip) {
  const TriMesh tube = open_tube(20.0, 30.0, 2.5);
  CutToDiskOptions o;
  o.source = source_from_plane(tube, Vec3(1, 0, 0), 0.0);
  ASSERT_EQ(o.source.polylines.size(), 2u);
  o.source.polylines.pop_back();  // one vertical line only
  o.source.vertex_side.clear();
  const CutToDisk c = cut_to_disk(tube, o);
  check_disk(tube, c);
  EXPECT_TRUE(c.source_on_seam);
  ASSERT_FALSE(c.source.polylines.empty());
  const Halfedges he = build_halfedges(c.mesh.num_vertices(), c.mesh.faces);
  for (const auto& line : c.source.polylines)
    for (const SurfacePoint& p : line)
      for (int k = 0; k < 3; ++k)
        if (p.bary[k] != 0.0) {
          EXPECT_TRUE(he.is_boundary_vertex(c.mesh.faces[p.face][k]));
        }
  // One lip only: the field from it reaches half round the tube and more.
  const GeodesicField f = geodesic_distance(c.mesh, c.source);
  EXPECT_GT(f.max_abs_distance, 1.9 * kPi * 20.0);
}

// A disk with three holes: three seams, each joining two loops.
TEST(CutToDisk, DiskWithHolesGetsASeamPerHole) {
  TriMesh grid = test::square_grid(12, 5.0);
  TriMesh m;
  m.vertices = grid.vertices;
  for (int f = 0; f < grid.num_faces(); ++f) {
    const int cell = f / 2, i = cell % 12, j = cell / 12;
    const bool hole = j >= 5 && j <= 6 && (i == 2 || i == 3 || i == 6 || i == 7 || i == 10);
    if (!hole) m.faces.push_back(grid.faces[f]);
  }
  ASSERT_EQ(validate_surface(m).num_boundary_loops, 4);
  const CutToDisk c = cut_to_disk(m);
  check_disk(m, c);
  EXPECT_EQ(c.input_boundary_loops, 4);
  ASSERT_EQ(c.seams.size(), 3u);
  // The straight gaps (grid edges): hole C to the right border (one cell),
  // then hole B to C and hole A to the left border or to B (two cells).
  std::vector<double> lengths;
  for (const Seam& s : c.seams) {
    EXPECT_EQ(s.kind, SeamKind::Loops);
    lengths.push_back(s.length);
  }
  std::sort(lengths.begin(), lengths.end());
  EXPECT_NEAR(lengths[0], 5.0, 1e-9);
  EXPECT_NEAR(lengths[1], 10.0, 1e-9);
  EXPECT_NEAR(lengths[2], 10.0, 1e-9);
}

// Handles: a torus (closed, genus 1) and a torus with a hole (one loop)
// become disks through a cut graph.
TEST(CutToDisk, HandlesGetACutGraph) {
  const TriMesh torus = test::ring_grid(12, 24, true);
  const CutToDisk c = cut_to_disk(torus);
  check_disk(torus, c);
  EXPECT_EQ(c.input_genus, 1);
  EXPECT_EQ(c.input_boundary_loops, 0);
  ASSERT_FALSE(c.seams.empty());
  for (const Seam& s : c.seams) EXPECT_EQ(s.kind, SeamKind::Handle);
  TriMesh holed = torus;
  holed.faces.erase(holed.faces.begin() + 40, holed.faces.begin() + 42);
  const CutToDisk h = cut_to_disk(holed);
  check_disk(holed, h);
  EXPECT_EQ(h.input_genus, 1);
  EXPECT_EQ(h.input_boundary_loops, 1);
}

// The user's cut comes first: a radial cut of an annulus drawn a little past
// both rims (its ends move onto them) is the only seam.
TEST(CutToDisk, UserCutJoinsTheLoops) {
  const TriMesh ring = test::ring_grid(4, 48, false);
  CutToDiskOptions o;
  o.cuts = {{Vec3(0.95, 0.02, 0), Vec3(3.0, 0.02, 0), Vec3(5.04, 0.02, 0)}};
  const CutToDisk c = cut_to_disk(ring, o);
  check_disk(ring, c);
  ASSERT_EQ(c.seams.size(), 1u);
  EXPECT_EQ(c.seams[0].kind, SeamKind::User);
  EXPECT_NEAR(c.seams[0].length, 4.0, 0.01);
  // A cut across a disk separates it: said so.
  CutToDiskOptions across;
  across.cuts = {{Vec3(-1, 2.5, 0), Vec3(6, 2.5, 0)}};
  try {
    cut_to_disk(test::square_grid(5), across, "grid.obj");
    ADD_FAILURE() << "expected TopologyError";
  } catch (const TopologyError& e) {
    EXPECT_NE(std::string(e.what()).find("separate the surface into 2 pieces"), std::string::npos)
        << e.what();
  }
}

TEST(CutToDisk, SurfacesThatCannotBeADisk) {
  try {
    cut_to_disk(test::tetrahedron(), {}, "tet.obj");
    ADD_FAILURE() << "expected TopologyError";
  } catch (const TopologyError& e) {
    EXPECT_NE(std::string(e.what()).find("tet.obj is a closed surface"), std::string::npos) << e.what();
  }
  TriMesh two = test::square_grid(2);
  const int n = two.num_vertices();
  for (int v = 0; v < n; ++v) two.vertices.push_back(two.vertices[v] + Vec3(10, 0, 0));
  for (int f = 0, nf = two.num_faces(); f < nf; ++f)
    two.faces.push_back({two.faces[f][0] + n, two.faces[f][1] + n, two.faces[f][2] + n});
  EXPECT_THROW(cut_to_disk(two), TopologyError);
  TriMesh bad = test::square_grid(2);
  bad.faces.push_back(bad.faces[0]);
  EXPECT_THROW(cut_to_disk(bad), TopologyError);
}

TEST(CutToDisk, Deterministic) {
  const TriMesh m = cap(CapShape{}, 6.0);
  CutToDiskOptions o;
  o.source = source_from_plane(m, Vec3(1, 0, 0), 0.0);
  const CutToDisk a = cut_to_disk(m, o), b = cut_to_disk(m, o);
  EXPECT_EQ(a.mesh.faces, b.mesh.faces);
  EXPECT_EQ(a.mesh.vertices, b.mesh.vertices);
  const CutToDisk g1 = cut_to_disk(m), g2 = cut_to_disk(m);
  EXPECT_EQ(g1.mesh.faces, g2.mesh.faces);
  ASSERT_EQ(g1.seams.size(), 1u);
  EXPECT_NEAR(g1.seams[0].length, 15.0 * kPi / 180.0 * 90.0,
              0.02 * 23.6);  // the shortest path: under the chin
}

}  // namespace
}  // namespace knitforge
