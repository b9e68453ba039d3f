#include "knitforge/geometry/surface_checks.h"

#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "geometry/test_meshes.h"
#include "knitforge/geometry/shapes.h"
#include "knitforge/util/errors.h"

namespace knitforge {
namespace {

using K = SurfaceIssueKind;

const SurfaceIssue* find_issue(const SurfaceReport& r, K kind) {
  for (const auto& i : r.issues)
    if (i.kind == kind) return &i;
  return nullptr;
}

std::string disk_error(const TriMesh& m) {
  try {
    require_disk(m, "mesh.obj");
  } catch (const TopologyError& e) {
    return e.what();
  }
  ADD_FAILURE() << "require_disk did not throw";
  return "";
}

TEST(SurfaceChecks, CleanDiskReportsNothing) {
  for (const TriMesh& m : {test::square_grid(4), flat_disk(20.0, 4.0)}) {
    const SurfaceReport r = validate_surface(m);
    EXPECT_TRUE(r.issues.empty()) << r.summary();
    EXPECT_TRUE(r.ok());
    EXPECT_TRUE(r.manifold);
    EXPECT_TRUE(r.is_disk);
    EXPECT_EQ(r.num_components, 1);
    EXPECT_EQ(r.num_boundary_loops, 1);
    EXPECT_EQ(r.euler_characteristic, 1);
    EXPECT_EQ(r.genus, 0);
    EXPECT_EQ(r.num_vertices, m.num_vertices());
    EXPECT_EQ(r.num_faces, m.num_faces());
    EXPECT_NO_THROW(require_disk(m, "disk"));
  }
}

TEST(SurfaceChecks, GridCounts) {
  const SurfaceReport r = validate_surface(test::square_grid(3));
  EXPECT_EQ(r.num_vertices, 16);
  EXPECT_EQ(r.num_faces, 18);
  EXPECT_EQ(r.num_edges, 33);
}

TEST(SurfaceChecks, NonFiniteVertex) {
  TriMesh m = test::square_grid(2);
  m.vertices[4].y() = std::numeric_limits<double>::quiet_NaN();
  m.vertices[7].z() = std::numeric_limits<double>::infinity();
  const SurfaceReport r = validate_surface(m);
  ASSERT_EQ(r.count(K::NonFiniteVertex), 2);
  EXPECT_EQ(r.issues[0].element, 4);
  EXPECT_EQ(r.issues[1].element, 7);
  EXPECT_TRUE(r.issues[0].is_error);
  EXPECT_FALSE(r.ok());
  EXPECT_FALSE(r.is_disk);
  EXPECT_THROW(require_disk(m, "m"), InvalidInput);
}

TEST(SurfaceChecks, IndexOutOfRangeAndRepeatedVertex) {
  TriMesh m = test::square_grid(2);
  m.faces[5] = {0, 1, 9};
  m.faces[6] = {4, 5, 4};
  m.faces[7][0] = -1;
  const SurfaceReport r = validate_surface(m);
  EXPECT_EQ(r.count(K::IndexOutOfRange), 2);
  EXPECT_EQ(r.count(K::RepeatedVertex), 1);
  const SurfaceIssue* range = find_issue(r, K::IndexOutOfRange);
  ASSERT_NE(range, nullptr);
  EXPECT_EQ(range->element, 5);
  EXPECT_NE(range->message.find("vertex 9"), std::string::npos);
  const SurfaceIssue* rep = find_issue(r, K::RepeatedVertex);
  ASSERT_NE(rep, nullptr);
  EXPECT_EQ(rep->element, 6);
  EXPECT_EQ(r.num_faces, 5);  // the three bad faces are left out of the summary
  EXPECT_EQ(r.num_errors, 3);
}

TEST(SurfaceChecks, DegenerateFaceAndShortEdgeAreWarnings) {
  TriMesh m = test::square_grid(2);
  // Collapse edge (0, 1): vertex 1 moves onto vertex 0.
  m.vertices[1] = m.vertices[0];
  const SurfaceReport r = validate_surface(m);
  EXPECT_EQ(r.num_errors, 0);
  EXPECT_TRUE(r.ok());
  ASSERT_EQ(r.count(K::ShortEdge), 1);
  const SurfaceIssue* e = find_issue(r, K::ShortEdge);
  EXPECT_EQ(e->vertex_a, 0);
  EXPECT_EQ(e->vertex_b, 1);
  EXPECT_FALSE(e->is_error);
  // Face 0 = (0, 1, 4) has zero area now.
  ASSERT_EQ(r.count(K::DegenerateFace), 1);
  EXPECT_EQ(find_issue(r, K::DegenerateFace)->element, 0);
  EXPECT_EQ(r.num_warnings, 2);
  EXPECT_TRUE(r.is_disk);  // warnings do not change the topology
}

TEST(SurfaceChecks, CollinearFaceIsDegenerate) {
  TriMesh m;
  m.vertices = {{0, 0, 0}, {2, 0, 0}, {1, 1e-12, 0}, {1, 1, 0}};
  m.faces = {{0, 1, 2}, {0, 2, 3}, {2, 1, 3}};
  const SurfaceReport r = validate_surface(m);
  ASSERT_EQ(r.count(K::DegenerateFace), 1);
  EXPECT_EQ(find_issue(r, K::DegenerateFace)->element, 0);
  EXPECT_EQ(r.count(K::ShortEdge), 0);
}

TEST(SurfaceChecks, DuplicateFace) {
  TriMesh m = test::square_grid(1);
  m.faces.push_back({m.faces[0][1], m.faces[0][2], m.faces[0][0]});  // same face, rotated
  const SurfaceReport r = validate_surface(m);
  ASSERT_EQ(r.count(K::DuplicateFace), 1);
  const SurfaceIssue* d = find_issue(r, K::DuplicateFace);
  EXPECT_EQ(d->element, 2);
  EXPECT_EQ(d->other, 0);
  EXPECT_EQ(r.num_errors, 1);  // the duplicate is not reported again as a non-manifold edge
  EXPECT_EQ(r.num_faces, 2);
}

TEST(SurfaceChecks, NonManifoldEdge) {
  TriMesh m;
  m.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}};
  m.faces = {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}};
  const SurfaceReport r = validate_surface(m);
  ASSERT_EQ(r.count(K::NonManifoldEdge), 1);
  const SurfaceIssue* e = find_issue(r, K::NonManifoldEdge);
  EXPECT_EQ(e->vertex_a, 0);
  EXPECT_EQ(e->vertex_b, 1);
  EXPECT_NE(e->message.find("3 faces (0, 1, 2)"), std::string::npos) << e->message;
  EXPECT_EQ(r.count(K::NonManifoldVertex), 0);
  EXPECT_FALSE(r.manifold);
  EXPECT_EQ(r.num_boundary_loops, -1);
  EXPECT_EQ(r.genus, -1);
  EXPECT_FALSE(r.is_disk);
}

TEST(SurfaceChecks, BowTieVertex) {
  TriMesh m;
  m.vertices = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {-1, 0, 0}, {-1, -1, 0}};
  m.faces = {{0, 1, 2}, {0, 3, 4}};
  const SurfaceReport r = validate_surface(m);
  ASSERT_EQ(r.count(K::NonManifoldVertex), 1);
  EXPECT_EQ(find_issue(r, K::NonManifoldVertex)->element, 0);
  EXPECT_EQ(r.num_errors, 1);
  EXPECT_EQ(r.num_components, 2);
}

TEST(SurfaceChecks, InconsistentOrientationListsEveryFlippedPair) {
  TriMesh m = test::square_grid(3);
  std::swap(m.faces[8][1], m.faces[8][2]);  // an interior face: three neighbours disagree
  const SurfaceReport r = validate_surface(m);
  EXPECT_EQ(r.count(K::InconsistentOrientation), 3);
  for (const auto& i : r.issues) {
    ASSERT_EQ(i.kind, K::InconsistentOrientation);
    EXPECT_TRUE(i.element == 8 || i.other == 8);
  }
  EXPECT_EQ(r.count(K::NonManifoldVertex), 0);
  EXPECT_FALSE(r.manifold);
}

TEST(SurfaceChecks, IsolatedVertexIsAWarning) {
  TriMesh m = test::square_grid(1);
  m.vertices.emplace_back(5.0, 5.0, 5.0);
  const SurfaceReport r = validate_surface(m);
  ASSERT_EQ(r.count(K::IsolatedVertex), 1);
  EXPECT_EQ(find_issue(r, K::IsolatedVertex)->element, 4);
  EXPECT_TRUE(r.ok());
  EXPECT_TRUE(r.is_disk);
  EXPECT_EQ(r.num_vertices, 4);
}

TEST(SurfaceChecks, TopologySummaries) {
  const SurfaceReport tet = validate_surface(test::tetrahedron());
  EXPECT_EQ(tet.num_boundary_loops, 0);
  EXPECT_EQ(tet.euler_characteristic, 2);
  EXPECT_EQ(tet.genus, 0);
  EXPECT_FALSE(tet.is_disk);

  const SurfaceReport annulus = validate_surface(test::ring_grid(2, 8, false));
  EXPECT_EQ(annulus.num_boundary_loops, 2);
  EXPECT_EQ(annulus.euler_characteristic, 0);
  EXPECT_EQ(annulus.genus, 0);

  const SurfaceReport torus = validate_surface(test::ring_grid(4, 8, true));
  EXPECT_EQ(torus.num_boundary_loops, 0);
  EXPECT_EQ(torus.euler_characteristic, 0);
  EXPECT_EQ(torus.genus, 1);

  TriMesh two = test::square_grid(1);
  for (int k = 0; k < 4; ++k) two.vertices.push_back(two.vertices[k] + Vec3(10, 0, 0));
  two.faces.push_back({4, 5, 7});
  two.faces.push_back({4, 7, 6});
  const SurfaceReport r2 = validate_surface(two);
  EXPECT_EQ(r2.num_components, 2);
  EXPECT_EQ(r2.num_boundary_loops, 2);
  EXPECT_EQ(r2.genus, 0);
  EXPECT_FALSE(r2.is_disk);
}

TEST(SurfaceChecks, RequireDiskMessagesSayWhatToDo) {
  const std::string annulus = disk_error(test::ring_grid(2, 8, false));
  EXPECT_NE(annulus.find("mesh.obj has 2 boundary loops and genus 0 (a cylinder/annulus)"), std::string::npos)
      << annulus;
  EXPECT_NE(annulus.find("cut it into a disk"), std::string::npos);
  const std::string closed = disk_error(test::tetrahedron());
  EXPECT_NE(closed.find("closed surface"), std::string::npos) << closed;
  const std::string torus = disk_error(test::ring_grid(4, 8, true));
  EXPECT_NE(torus.find("genus 1"), std::string::npos) << torus;
  TriMesh two = test::square_grid(1);
  for (int k = 0; k < 4; ++k) two.vertices.push_back(two.vertices[k] + Vec3(10, 0, 0));
  two.faces.push_back({4, 5, 7});
  two.faces.push_back({4, 7, 6});
  EXPECT_NE(disk_error(two).find("2 connected components"), std::string::npos);
  TriMesh bad = test::square_grid(2);
  std::swap(bad.faces[0][1], bad.faces[0][2]);
  const std::string flipped = disk_error(bad);
  EXPECT_NE(flipped.find("mesh.obj is not a valid surface"), std::string::npos) << flipped;
  EXPECT_NE(flipped.find("same direction"), std::string::npos) << flipped;
  EXPECT_THROW(require_disk(TriMesh{}, "empty"), TopologyError);
}

TEST(SurfaceChecks, SummaryNamesCounts) {
  TriMesh m = test::square_grid(1);
  m.vertices.emplace_back(5.0, 5.0, 5.0);
  const std::string s = validate_surface(m).summary();
  EXPECT_NE(s.find("1 isolated vertex"), std::string::npos) << s;
  EXPECT_NE(s.find("(a disk)"), std::string::npos) << s;
}

}  // namespace
}  // namespace knitforge
