#include "knitforge/geometry/isocurves.h"

#include <cmath>
#include <map>
#include <numbers>
#include <set>
#include <tuple>

#include <gtest/gtest.h>

#include "geometry/test_meshes.h"
#include "knitforge/geometry/halfedges.h"
#include "knitforge/geometry/mesh_measures.h"
#include "knitforge/geometry/shapes.h"
#include "knitforge/util/errors.h"

namespace knitforge {
namespace {

std::vector<double> field_of(const TriMesh& m, double (*f)(const Vec3&)) {
  std::vector<double> v;
  for (const Vec3& p : m.vertices) v.push_back(f(p));
  return v;
}

// A key identifying an isocurve point: (v0, v1) with v0 == v1 for a vertex.
std::pair<int, int> key(const MeshPoint& p) { return {std::min(p.v0, p.v1), std::max(p.v0, p.v1)}; }

// Field value at the point (linear interpolation).
double value_at(const TriMesh& m, const std::vector<double>& f, const MeshPoint& p) {
  return mesh_point_value(m, f, p);
}

// Signed area (xy) of a closed polygon.
double signed_area_xy(const std::vector<Vec3>& p) {
  double a = 0.0;
  for (size_t i = 0; i < p.size(); ++i) {
    const Vec3& u = p[i];
    const Vec3& w = p[(i + 1) % p.size()];
    a += u.x() * w.y() - w.x() * u.y();
  }
  return 0.5 * a;
}

// Every segment runs along n x grad F of its face: the field increases to
// the right. Returns the number of segments checked.
int check_orientation(const TriMesh& m, const std::vector<double>& f, const Isocurve& c) {
  const auto grads = field_face_gradients(m, f);
  const int n = c.num_points();
  const int segs = c.closed ? n : n - 1;
  EXPECT_EQ(static_cast<int>(c.faces.size()), segs);
  for (int i = 0; i < segs; ++i) {
    const Vec3 d = c.positions[(i + 1) % n] - c.positions[i];
    const int face = c.faces[i];
    EXPECT_GE(face, 0);
    const Vec3 nrm = face_normal(m, face);
    // right of d seen from the normal side: d x n; the gradient points there.
    const Vec3 right = d.cross(nrm);
    EXPECT_GT(right.dot(grads[face]), 0.0) << "segment " << i << " of the curve at " << c.value;
  }
  return segs;
}

double lin_x(const Vec3& p) { return p.x(); }
double radius(const Vec3& p) { return std::hypot(p.x(), p.y()); }
double height(const Vec3& p) { return p.z(); }

TEST(Isocurves, LinearFieldOnRectangleGivesExactStraightLines) {
  const TriMesh m = rectangle(150.0, 100.0, 5.0);
  const auto f = field_of(m, lin_x);
  for (double level : {-50.3, 0.0, 33.3, 71.0}) {
    const auto curves = extract_isocurve(m, f, level);
    ASSERT_EQ(curves.size(), 1u) << level;
    const Isocurve& c = curves[0];
    EXPECT_FALSE(c.closed);
    EXPECT_FALSE(c.starts_at_junction);
    EXPECT_FALSE(c.ends_at_junction);
    for (const Vec3& p : c.positions) EXPECT_NEAR(p.x(), level, 1e-12);
    // Boundary to boundary, walking along +y (= n x grad x with n = +z).
    EXPECT_NEAR(c.positions.front().y(), -50.0, 1e-9);
    EXPECT_NEAR(c.positions.back().y(), 50.0, 1e-9);
    EXPECT_NEAR(c.length(), 100.0, 1e-9);
    for (size_t i = 1; i < c.positions.size(); ++i) EXPECT_GT(c.positions[i].y(), c.positions[i - 1].y());
    check_orientation(m, f, c);
  }
  // Outside the range: nothing.
  EXPECT_TRUE(extract_isocurve(m, f, 80.0).empty());
}

TEST(Isocurves, LevelThroughGridVerticesFollowsTheEdges) {
  const int n = 4;
  const TriMesh m = test::square_grid(n);
  const auto f = field_of(m, lin_x);
  const auto curves = extract_isocurve(m, f, 2.0);
  ASSERT_EQ(curves.size(), 1u);
  const Isocurve& c = curves[0];
  ASSERT_EQ(c.num_points(), n + 1);
  for (int j = 0; j <= n; ++j) {
    EXPECT_TRUE(c.points[j].is_vertex());
    EXPECT_EQ(c.points[j].v0, j * (n + 1) + 2);  // vertex (2, j), upwards
  }
  // The reported face of an on-level edge lies on the larger side (x > 2).
  for (int face : c.faces) {
    Vec3 centroid = Vec3::Zero();
    for (int v : m.faces[face]) centroid += m.vertices[v] / 3.0;
    EXPECT_GT(centroid.x(), 2.0);
  }
  // Half-way between columns: crossing points of edges and diagonals.
  const auto mid = extract_isocurve(m, f, 1.5);
  ASSERT_EQ(mid.size(), 1u);
  EXPECT_EQ(mid[0].num_points(), 2 * n + 1);
  for (const auto& p : mid[0].points) EXPECT_TRUE(p.is_edge());
  for (const Vec3& p : mid[0].positions) EXPECT_DOUBLE_EQ(p.x(), 1.5);
}

TEST(Isocurves, RadialFieldOnDiskGivesClosedCircles) {
  const TriMesh m = flat_disk(50.0, 2.5);
  const auto f = field_of(m, radius);
  for (double r : {10.0, 25.0, 40.0}) {
    const auto curves = extract_isocurve(m, f, r);
    ASSERT_EQ(curves.size(), 1u) << r;
    const Isocurve& c = curves[0];
    EXPECT_TRUE(c.closed);
    // Points are exactly on the level of the piecewise-linear field and
    // within the interpolation error h^2 / (8 r) of the true circle.
    for (size_t i = 0; i < c.points.size(); ++i) {
      EXPECT_NEAR(value_at(m, f, c.points[i]), r, 1e-9);
      EXPECT_LE(std::abs(radius(c.positions[i]) - r), 2.5 * 2.5 / (4.0 * r) + 1e-9);
      EXPECT_NEAR(c.positions[i].z(), 0.0, 1e-12);
    }
    EXPECT_NEAR(c.length(), 2.0 * std::numbers::pi * r, 0.01 * 2.0 * std::numbers::pi * r);
    // The field increases outwards = to the right: counter-clockwise seen from +z.
    EXPECT_NEAR(signed_area_xy(c.positions), std::numbers::pi * r * r, 0.02 * std::numbers::pi * r * r);
    check_orientation(m, f, c);
  }
}

TEST(Isocurves, HeightLevelsOnHemisphereRunAlongWaleDirection) {
  const TriMesh m = hemisphere(75.0, 5.0);
  const auto f = field_of(m, height);
  const auto levels = isocurve_levels(5.0, 70.0, 5.0);
  ASSERT_EQ(levels.size(), 14u);
  const auto all = extract_isocurves(m, f, levels);
  ASSERT_EQ(all.size(), levels.size());
  const auto dirs = wale_directions(m, f);
  for (size_t l = 0; l < levels.size(); ++l) {
    ASSERT_EQ(all[l].size(), 1u) << levels[l];
    const Isocurve& c = all[l][0];
    EXPECT_TRUE(c.closed);
    EXPECT_EQ(c.value, levels[l]);
    check_orientation(m, f, c);
    for (int i = 0; i < c.num_points(); ++i) {
      const Vec3 d = (c.positions[(i + 1) % c.num_points()] - c.positions[i]).normalized();
      EXPECT_GT(d.dot(dirs[c.faces[i]]), 0.99);
    }
    // Many levels at once give exactly the single-level result.
    const auto single = extract_isocurve(m, f, levels[l]);
    ASSERT_EQ(single.size(), 1u);
    ASSERT_EQ(single[0].num_points(), c.num_points());
    for (int i = 0; i < c.num_points(); ++i) {
      EXPECT_EQ(key(single[0].points[i]), key(c.points[i]));
      EXPECT_EQ(single[0].points[i].ratio, c.points[i].ratio);
      EXPECT_EQ(single[0].faces[i], c.faces[i]);
    }
  }
}

TEST(Isocurves, ManyLevelsInAnyOrderWithRepeats) {
  const TriMesh m = flat_disk(50.0, 5.0);
  std::vector<double> f;
  for (const Vec3& p : m.vertices) f.push_back(p.x() + 0.5 * p.y());
  const std::vector<double> levels = {20.0, -30.0, 20.0, 0.0, 100.0};
  const auto all = extract_isocurves(m, f, levels);
  ASSERT_EQ(all.size(), 5u);
  for (size_t l = 0; l < levels.size(); ++l) {
    const auto single = extract_isocurve(m, f, levels[l]);
    ASSERT_EQ(all[l].size(), single.size());
    for (size_t c = 0; c < single.size(); ++c) {
      EXPECT_EQ(all[l][c].positions, single[c].positions);
      EXPECT_EQ(all[l][c].value, levels[l]);
    }
  }
  EXPECT_EQ(all[0].size(), 1u);
  EXPECT_TRUE(all[4].empty());
}

TEST(Isocurves, ChainsAreManifoldOnTriplePeak) {
  const TriMesh m = triple_peak(6.0);
  const auto f = field_of(m, height);
  const auto levels = isocurve_levels(1.0, 55.0, 3.0);
  const auto all = extract_isocurves(m, f, levels);
  int total = 0;
  bool some_closed = false, some_open = false;
  for (const auto& curves : all) {
    std::map<std::pair<int, int>, int> uses;
    for (const auto& c : curves) {
      ++total;
      some_closed |= c.closed;
      some_open |= !c.closed;
      for (const auto& p : c.points) ++uses[key(p)];
      check_orientation(m, f, c);
      // Open chains on a generic field end on the mesh boundary.
      if (!c.closed) {
        EXPECT_FALSE(c.starts_at_junction);
        EXPECT_FALSE(c.ends_at_junction);
      }
    }
    // Generic levels: no point is shared between chains or repeated.
    for (const auto& [k, count] : uses) EXPECT_EQ(count, 1);
  }
  EXPECT_GT(total, 10);
  EXPECT_TRUE(some_closed);  // around the peaks
  EXPECT_TRUE(some_open);
}

// A single counter-clockwise triangle (0,0), (1,0), (0,1).
TriMesh one_triangle() {
  TriMesh m;
  m.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  m.faces = {{0, 1, 2}};
  return m;
}

TEST(Isocurves, TriangleCasesOfFig323) {
  const TriMesh m = one_triangle();
  {  // (0, -, +): vertex to the crossing on the opposite edge, + on the right.
    const auto c = extract_isocurve(m, {0.0, -1.0, 1.0}, 0.0);
    ASSERT_EQ(c.size(), 1u);
    ASSERT_EQ(c[0].num_points(), 2);
    EXPECT_TRUE(c[0].points[0].is_edge());
    EXPECT_EQ(key(c[0].points[0]), std::make_pair(1, 2));
    EXPECT_DOUBLE_EQ(c[0].points[0].ratio, 0.5);
    EXPECT_TRUE(c[0].points[1].is_vertex());
    EXPECT_EQ(c[0].points[1].v0, 0);
    EXPECT_EQ(c[0].faces, std::vector<int>{0});
  }
  // (0, +, +) and (0, -, -): the level only touches a vertex.
  EXPECT_TRUE(extract_isocurve(m, {0.0, 1.0, 2.0}, 0.0).empty());
  EXPECT_TRUE(extract_isocurve(m, {0.0, -1.0, -2.0}, 0.0).empty());
  // (-, -, -): nothing.
  EXPECT_TRUE(extract_isocurve(m, {-1.0, -1.0, -2.0}, 0.0).empty());
  {  // (-, +, +): two crossings, + to the right.
    const auto c = extract_isocurve(m, {-1.0, 1.0, 3.0}, 0.0);
    ASSERT_EQ(c.size(), 1u);
    ASSERT_EQ(c[0].num_points(), 2);
    EXPECT_EQ(key(c[0].points[0]), std::make_pair(0, 1));
    EXPECT_EQ(key(c[0].points[1]), std::make_pair(0, 2));
    EXPECT_NEAR(c[0].positions[0].x(), 0.5, 1e-15);
    EXPECT_NEAR(c[0].positions[1].y(), 0.25, 1e-15);
  }
  {  // (0, 0, +): the boundary edge between the on-level vertices, once,
     // walked with the face (larger side) on the right: 1 -> 0.
    const auto c = extract_isocurve(m, {0.0, 0.0, 1.0}, 0.0);
    ASSERT_EQ(c.size(), 1u);
    ASSERT_EQ(c[0].num_points(), 2);
    EXPECT_EQ(c[0].points[0].v0, 1);
    EXPECT_EQ(c[0].points[1].v0, 0);
    const auto d = extract_isocurve(m, {0.0, 0.0, -1.0}, 0.0);
    ASSERT_EQ(d.size(), 1u);
    EXPECT_EQ(d[0].points[0].v0, 0);
    EXPECT_EQ(d[0].points[1].v0, 1);
  }
  // (0, 0, 0) alone: a flat face on the boundary outlines nothing.
  EXPECT_TRUE(extract_isocurve(m, {0.0, 0.0, 0.0}, 0.0).empty());
}

TEST(Isocurves, ToleranceSnapsNearlyOnLevelVertices) {
  const TriMesh m = one_triangle();
  // Vertex 0 is 1e-13 off the level: with the default relative tolerance
  // (1e-10 of the range 2) it is on the level.
  const auto c = extract_isocurve(m, {1e-13, -1.0, 1.0}, 0.0);
  ASSERT_EQ(c.size(), 1u);
  EXPECT_TRUE(c[0].points[1].is_vertex());
  // Without tolerance it is a crossing on edge (0, 1) very close to vertex 0.
  IsocurveOptions exact;
  exact.relative_tolerance = 0.0;
  const auto d = extract_isocurve(m, {1e-13, -1.0, 1.0}, 0.0, exact);
  ASSERT_EQ(d.size(), 1u);
  EXPECT_TRUE(d[0].points[1].is_edge());
  // A larger absolute tolerance snaps more.
  IsocurveOptions loose;
  loose.tolerance = 0.2;
  const auto e = extract_isocurve(m, {0.1, -1.0, 1.0}, 0.0, loose);
  ASSERT_EQ(e.size(), 1u);
  EXPECT_TRUE(e[0].points[1].is_vertex());
}

TEST(Isocurves, FlatFaceIsOutlinedByItsBorderWithoutDuplicates) {
  {  // Flat face (0, 1, 4) in the corner of a 2x2 grid, everything else +.
    const TriMesh m = test::square_grid(2);
    std::vector<double> f(9, 1.0);
    f[0] = f[1] = f[4] = 0.0;
    const auto c = extract_isocurve(m, f, 0.0);
    ASSERT_EQ(c.size(), 1u);
    ASSERT_EQ(c[0].num_points(), 3);
    EXPECT_FALSE(c[0].closed);
    EXPECT_EQ(c[0].points[0].v0, 1);
    EXPECT_EQ(c[0].points[1].v0, 4);
    EXPECT_EQ(c[0].points[2].v0, 0);
    EXPECT_EQ(c[0].faces, (std::vector<int>{3, 1}));  // the + faces on the right
    // Everything else negative: the same outline, reversed.
    for (int v : {2, 3, 5, 6, 7, 8}) f[v] = -1.0;
    const auto d = extract_isocurve(m, f, 0.0);
    ASSERT_EQ(d.size(), 1u);
    ASSERT_EQ(d[0].num_points(), 3);
    EXPECT_EQ(d[0].points[0].v0, 0);
    EXPECT_EQ(d[0].points[2].v0, 1);
  }
  {  // Interior flat face (5, 6, 10) of a 3x3 grid: a closed triangle,
     // counter-clockwise (the larger values outside, on the right).
    const TriMesh m = test::square_grid(3);
    std::vector<double> f(16, 1.0);
    f[5] = f[6] = f[10] = 0.0;
    const auto c = extract_isocurve(m, f, 0.0);
    ASSERT_EQ(c.size(), 1u);
    EXPECT_TRUE(c[0].closed);
    ASSERT_EQ(c[0].num_points(), 3);
    std::set<int> vs;
    for (const auto& p : c[0].points) vs.insert(p.v0);
    EXPECT_EQ(vs, (std::set<int>{5, 6, 10}));
    EXPECT_GT(signed_area_xy(c[0].positions), 0.0);
  }
  {  // Two adjacent flat faces (a flat square): its outline, no inner diagonal.
    const TriMesh m = test::square_grid(3);
    std::vector<double> f(16, -1.0);
    f[5] = f[6] = f[9] = f[10] = 0.0;
    const auto c = extract_isocurve(m, f, 0.0);
    ASSERT_EQ(c.size(), 1u);
    EXPECT_TRUE(c[0].closed);
    EXPECT_EQ(c[0].num_points(), 4);
    EXPECT_NEAR(c[0].length(), 4.0, 1e-12);
    EXPECT_LT(signed_area_xy(c[0].positions), 0.0);  // field larger inside: clockwise
  }
}

TEST(Isocurves, OnLevelEdgeBetweenTwoFacesIsEmittedOnce) {
  // Ridge: the middle column of a 2x2 grid is on the level, both sides below.
  const TriMesh m = test::square_grid(2);
  std::vector<double> f = {-1, 0, -1, -1, 0, -1, -1, 0, -1};
  const auto c = extract_isocurve(m, f, 0.0);
  ASSERT_EQ(c.size(), 1u);
  EXPECT_EQ(c[0].num_points(), 3);  // 1, 4, 7 in some direction, each once
  std::set<int> vs;
  for (const auto& p : c[0].points) vs.insert(p.v0);
  EXPECT_EQ(vs, (std::set<int>{1, 4, 7}));
}

TEST(Isocurves, SaddleJunctionIsSplitAndReported) {
  // A fan of six triangles around vertex 0 with the monkey-saddle field
  // r^3 cos(3 phi): the outer values alternate +, -, ...; the level 0 passes
  // through the centre with six branches.
  TriMesh m;
  m.vertices.push_back(Vec3::Zero());
  std::vector<double> f = {0.0};
  for (int k = 0; k < 6; ++k) {
    const double a = k * std::numbers::pi / 3.0;
    m.vertices.emplace_back(std::cos(a), std::sin(a), 0.0);
    f.push_back(std::cos(3.0 * a));
  }
  for (int k = 0; k < 6; ++k) m.faces.push_back({0, 1 + k, 1 + (k + 1) % 6});
  const auto curves = extract_isocurve(m, f, 0.0);
  ASSERT_EQ(curves.size(), 6u);
  for (const auto& c : curves) {
    EXPECT_FALSE(c.closed);
    EXPECT_EQ(c.num_points(), 2);
    EXPECT_TRUE(c.starts_at_junction != c.ends_at_junction);
    const MeshPoint& centre = c.starts_at_junction ? c.points.front() : c.points.back();
    EXPECT_TRUE(centre.is_vertex());
    EXPECT_EQ(centre.v0, 0);
    check_orientation(m, f, c);
  }
}

TEST(Isocurves, GradientOfLinearFieldIsExact) {
  const TriMesh m = test::square_grid(3, 2.0);
  std::vector<double> f;
  for (const Vec3& p : m.vertices) f.push_back(3.0 * p.x() - 2.0 * p.y() + 1.0);
  const auto g = field_face_gradients(m, f);
  const auto d = wale_directions(m, f);
  const Vec3 expected_dir = Vec3(0, 0, 1).cross(Vec3(3, -2, 0)).normalized();
  for (int face = 0; face < m.num_faces(); ++face) {
    EXPECT_NEAR((g[face] - Vec3(3, -2, 0)).norm(), 0.0, 1e-12);
    EXPECT_NEAR((d[face] - expected_dir).norm(), 0.0, 1e-12);
  }
  // A tilted face (plane z = x): the gradient of x within the face is
  // (1, 0, 1) / 2, along the slope.
  TriMesh t;
  t.vertices = {{0, 0, 0}, {1, 0, 1}, {0, 1, 0}};
  t.faces = {{0, 1, 2}};
  const auto gt = field_face_gradients(t, {0.0, 1.0, 0.0});  // field = z = x
  EXPECT_NEAR((gt[0] - Vec3(0.5, 0, 0.5)).norm(), 0.0, 1e-15);
}

TEST(Isocurves, RejectsBadInput) {
  const TriMesh m = one_triangle();
  EXPECT_THROW(extract_isocurve(m, {0.0, 1.0}, 0.5), InvalidInput);
  EXPECT_THROW(extract_isocurve(m, {0.0, 1.0, NAN}, 0.5), InvalidInput);
  EXPECT_THROW(extract_isocurve(m, {0.0, 1.0, 2.0}, INFINITY), InvalidInput);
  IsocurveOptions bad;
  bad.tolerance = -1.0;
  EXPECT_THROW(extract_isocurve(m, {0.0, 1.0, 2.0}, 0.5, bad), InvalidInput);
  EXPECT_THROW(field_face_gradients(m, {1.0}), InvalidInput);
  EXPECT_THROW(isocurve_levels(0.0, 1.0, 0.0), InvalidInput);
  EXPECT_EQ(isocurve_levels(0.0, 1.0, 0.25).size(), 5u);
  EXPECT_TRUE(isocurve_levels(1.0, 0.0, 0.25).empty());
  TriMesh nonmanifold = m;
  nonmanifold.vertices.emplace_back(0, 0, 1);
  nonmanifold.vertices.emplace_back(0, 0, -1);
  nonmanifold.faces.push_back({0, 1, 3});
  nonmanifold.faces.push_back({1, 0, 4});
  EXPECT_THROW(extract_isocurve(nonmanifold, {0, 1, 2, 3, 4}, 0.5), TopologyError);
}

}  // namespace
}  // namespace knitforge
