// The governing field of the short-column route (seed §3.3.2-3.3.3):
// boundary parameterisation and Dirichlet intervals, the harmonic field, the
// Fiedler field, and the divergence metric eq. 3.5/3.6.
#include <algorithm>
#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "design/shortcolumn/test_meshes.h"
#include "knitforge/design/shortcolumn/boundary_intervals.h"
#include "knitforge/design/shortcolumn/divergence_metric.h"
#include "knitforge/design/shortcolumn/harmonic_field.h"
#include "knitforge/geometry/cotan_laplacian.h"
#include "knitforge/geometry/geodesic_distance.h"
#include "knitforge/geometry/geodesic_source.h"
#include "knitforge/geometry/halfedges.h"
#include "knitforge/geometry/mesh_measures.h"
#include "knitforge/geometry/shapes.h"
#include "knitforge/util/errors.h"

namespace knitforge {
namespace {

constexpr double kPi = std::numbers::pi;

using test::polar_grid;

TEST(BoundaryParameterisation, RunsAnticlockwiseByArcLengthFromTheLargestX) {
  const TriMesh m = rectangle(40.0, 30.0, 2.5);
  const BoundaryParameterisation b = parameterise_boundary(m);
  // Start: the corner (20, -15) (largest x, then smallest y).
  EXPECT_NEAR(m.vertices[b.loop[0]].x(), 20.0, 1e-12);
  EXPECT_NEAR(m.vertices[b.loop[0]].y(), -15.0, 1e-12);
  EXPECT_NEAR(b.length, 140.0, 1e-9);
  // Anticlockwise seen from +z: positive signed area of the loop polygon.
  double area2 = 0.0;
  for (int k = 0; k < b.size(); ++k) {
    const Vec3& p = m.vertices[b.loop[k]];
    const Vec3& q = m.vertices[b.loop[(k + 1) % b.size()]];
    area2 += p.x() * q.y() - q.x() * p.y();
    if (k > 0) {
      EXPECT_GT(b.t[k], b.t[k - 1]);
    }
  }
  EXPECT_NEAR(0.5 * area2, 1200.0, 1e-6);
  // t = 30/140 is the corner (20, 15); nearest() snaps to it.
  const int k = b.nearest(30.0 / 140.0);
  EXPECT_NEAR(m.vertices[b.loop[k]].y(), 15.0, 1e-9);
  EXPECT_EQ(b.nearest(1.0 + 30.0 / 140.0), k);  // wraps
  EXPECT_THROW(parameterise_boundary(TriMesh{}), Error);
}

TEST(BoundaryIntervals, FeasibleSetAndParsing) {
  EXPECT_TRUE(is_feasible({0.1, 0.2, 0.5, 0.9}));
  EXPECT_TRUE(is_feasible({0.1, 0.1, 0.5, 0.5}));  // point conditions
  EXPECT_TRUE(is_feasible({0.8, 0.9, 1.2, 1.7}));  // wraps
  EXPECT_FALSE(is_feasible({0.1, 0.2, 0.2, 0.5}));  // b1 < b2 is strict
  EXPECT_FALSE(is_feasible({0.1, 0.2, 0.5, 1.1}));  // b3 < 1 + b0
  EXPECT_FALSE(is_feasible({1.0, 1.1, 1.2, 1.3}));  // 1 + b0 < 2
  EXPECT_FALSE(is_feasible({-0.1, 0.2, 0.5, 0.6}));
  const BoundaryVector b = parse_boundary_vector("0.1,0.2,0.5,0.9");
  EXPECT_DOUBLE_EQ(b[2], 0.5);
  EXPECT_THROW(parse_boundary_vector("0.1,0.2,0.5"), InvalidInput);
  EXPECT_THROW(parse_boundary_vector("0.1,0.2,x,0.9"), InvalidInput);
  EXPECT_THROW(parse_boundary_vector("0.5,0.2,0.6,0.9"), InvalidInput);
}

TEST(BoundaryIntervals, SnapsToVerticesAndMovesDegenerateSets) {
  const TriMesh m = rectangle(40.0, 30.0, 2.5);
  const BoundaryParameterisation bp = parameterise_boundary(m);
  // Left side [70/140, 100/140] and right side [1, 1 + 30/140].
  const DirichletSets d = dirichlet_sets(m, bp, {0.5, 100.0 / 140.0, 1.0, 1.0 + 30.0 / 140.0});
  EXPECT_FALSE(d.adjusted);
  for (int v : d.zero) EXPECT_NEAR(m.vertices[v].x(), -20.0, 1e-9);
  for (int v : d.one) EXPECT_NEAR(m.vertices[v].x(), 20.0, 1e-9);
  EXPECT_EQ(d.zero.size(), 13u);  // 30 mm at 2.5 mm: 12 edges
  EXPECT_EQ(d.one.size(), 13u);
  // Point conditions.
  const DirichletSets p = dirichlet_sets(m, bp, {0.25, 0.25, 0.75, 0.75});
  EXPECT_EQ(p.zero.size(), 1u);
  EXPECT_EQ(p.one.size(), 1u);
  // Two points closer than one edge: the same vertex after snapping; R_e moves.
  const double e = 1.0 / bp.size();
  const DirichletSets q = dirichlet_sets(m, bp, {0.25, 0.25, 0.25 + 0.1 * e, 0.25 + 0.1 * e});
  EXPECT_TRUE(q.adjusted);
  ASSERT_EQ(q.one.size(), 1u);
  EXPECT_NE(q.one[0], q.zero[0]);
  // Not in one triangle with R_s: neither the same vertex nor a neighbour
  // sharing a face with it.
  bool share = false;
  for (const auto& f : m.faces)
    share = share || (std::count(f.begin(), f.end(), q.zero[0]) && std::count(f.begin(), f.end(), q.one[0]));
  EXPECT_FALSE(share);
  EXPECT_THROW(dirichlet_sets(m, bp, {0.5, 0.4, 0.6, 0.7}), InvalidInput);
}

TEST(HarmonicField, IsTheLinearFunctionBetweenOppositeSidesOfARectangle) {
  const TriMesh m = rectangle(40.0, 30.0, 2.5);
  const HarmonicField h = harmonic_field(m, {0.5, 100.0 / 140.0, 1.0, 1.0 + 30.0 / 140.0});
  // Neumann on top and bottom: f = (x + 20) / 40 exactly (linear precision).
  for (int v = 0; v < m.num_vertices(); ++v) EXPECT_NEAR(h.value[v], (m.vertices[v].x() + 20.0) / 40.0, 1e-9);
  EXPECT_EQ(h.interior_extrema, 0);
}

TEST(HarmonicField, RepeatedSolvesMatchFreshSolvesAndObeyTheMaximumPrinciple) {
  const TriMesh m = hemisphere(40.0, 3.0);
  HarmonicFieldSolver solver(m);
  const Halfedges he = build_halfedges(m.num_vertices(), m.faces);
  for (const BoundaryVector& b : {BoundaryVector{0.0, 0.2, 0.5, 0.7}, BoundaryVector{0.1, 0.1, 0.6, 0.6},
                                  BoundaryVector{0.7, 0.9, 1.3, 1.6}, BoundaryVector{0.2, 0.45, 0.5, 1.1}}) {
    const HarmonicField h = solver.solve(b);
    const HarmonicField fresh = harmonic_field(m, b);
    double diff = 0.0, lo = 1.0, hi = 0.0;
    for (int v = 0; v < m.num_vertices(); ++v) {
      diff = std::max(diff, std::abs(h.value[v] - fresh.value[v]));
      lo = std::min(lo, h.value[v]);
      hi = std::max(hi, h.value[v]);
    }
    EXPECT_LE(diff, 1e-10);
    EXPECT_DOUBLE_EQ(lo, 0.0);
    EXPECT_DOUBLE_EQ(hi, 1.0);
    for (int v : h.sets.zero) EXPECT_EQ(h.value[v], 0.0);
    for (int v : h.sets.one) EXPECT_EQ(h.value[v], 1.0);
    EXPECT_EQ(h.interior_extrema, 0) << format_boundary_vector(b);
    // Harmonic: (L f)_i = 0 away from the Dirichlet vertices is what the
    // solver imposes; check it through the mean-value property on the free
    // boundary too: every free vertex lies strictly between its neighbours.
    for (int v = 0; v < m.num_vertices(); ++v) {
      if (h.value[v] == 0.0 || h.value[v] == 1.0) continue;
      double nlo = 1.0, nhi = 0.0;
      for (int w : he.vertex_neighbors(v)) nlo = std::min(nlo, h.value[w]), nhi = std::max(nhi, h.value[w]);
      EXPECT_LT(nlo, h.value[v]);
      EXPECT_GT(nhi, h.value[v]);
    }
  }
  EXPECT_THROW(solver.solve({0.3, 0.2, 0.5, 0.7}), InvalidInput);
}

TEST(FiedlerField, IsTheFirstNeumannModeOfALongRectangle) {
  const TriMesh m = rectangle(60.0, 15.0, 2.0);
  const FiedlerField f = fiedler_field(m);
  EXPECT_TRUE(f.converged);
  // First non-constant Neumann eigenfunction: cos(pi (x + 30) / 60), eigenvalue (pi / 60)^2.
  EXPECT_NEAR(f.eigenvalue, (kPi / 60) * (kPi / 60), 0.01 * (kPi / 60) * (kPi / 60));
  double worst = 0.0;
  for (int v = 0; v < m.num_vertices(); ++v) {
    const double c = std::cos(kPi * (m.vertices[v].x() + 30.0) / 60.0);
    // Rescaled to [0, 1]; either sign.
    const double e = std::min(std::abs(f.value[v] - 0.5 * (1 - c)), std::abs(f.value[v] - 0.5 * (1 + c)));
    worst = std::max(worst, e);
  }
  EXPECT_LE(worst, 0.01);
  EXPECT_EQ(f.interior_extrema, 0);
}

TEST(DivergenceMetric, AngularFieldHasDivergenceMinusOneOverR) {
  // f = angle about c = (-80, 0): g = theta^ / r, J g^ = z x theta^ = -r^,
  // div(-r^) = -1 / r, on an irregular planar disk of radius 50 (r in [30, 130]).
  const TriMesh m = flat_disk(50.0, 1.5);
  const Vec3 c(-80, 0, 0);
  std::vector<double> f(m.num_vertices());
  for (int v = 0; v < m.num_vertices(); ++v) f[v] = std::atan2(m.vertices[v].y() - c.y(), m.vertices[v].x() - c.x());
  const DivergenceMetric d = divergence_metric(m, f);
  EXPECT_EQ(d.flat_faces, 0);
  double err = 0.0, sum = 0.0, exact = 0.0;
  int checked = 0;
  const std::vector<double> area = mixed_voronoi_areas(m);
  for (int v = 0; v < m.num_vertices(); ++v) {
    if (!d.interior[v]) continue;
    const double r = (m.vertices[v] - c).norm();
    err += area[v] * std::abs(1.5 * d.divergence[v] + 1.0 / r);
    sum += area[v] / r;
    exact += area[v] / r;
    ++checked;
  }
  EXPECT_GT(checked, 1000);
  // eq. 3.5 converges to 2/3 of the divergence (see divergence_metric.h).
  EXPECT_LT(err, 0.05 * sum) << "area-weighted relative error of 3/2 [div v]_i against -1/r";
  EXPECT_NEAR(d.total, 2.0 / 3.0 * exact, 0.03 * exact);
  EXPECT_LT(d.positive, 0.05 * d.total);
  // The reversed field (f = -angle) flips v and the sign of the divergence, not the metric.
  for (double& x : f) x = -x;
  const DivergenceMetric r = divergence_metric(m, f);
  EXPECT_NEAR(r.total, d.total, 1e-9 * d.total);
  EXPECT_NEAR(r.negative, d.positive, 1e-9 * d.total);
}

TEST(DivergenceMetric, DistanceFieldsHaveNoDivergence) {
  // f = r on the sector: a geodesic distance (eq. 3.4), isocurves are circles
  // with J g^ = theta^, divergence-free.
  const TriMesh m = polar_grid(20, 60, 0.2, 2.6, 40, 80);
  std::vector<double> f(m.num_vertices());
  for (int v = 0; v < m.num_vertices(); ++v) f[v] = m.vertices[v].norm();
  const DivergenceMetric d = divergence_metric(m, f);
  EXPECT_LE(d.total, 1e-3 * (60 - 20) * 2.4);
}

TEST(DivergenceMetric, ExactGeodesicFieldOfTheShortRowRouteIsNearlyDivergenceFree) {
  // The short-row route's governing field on the hemisphere (signed geodesic
  // distance from the plane x = 0) against a harmonic field on the same mesh.
  const TriMesh m = hemisphere(75.0, 2.5);
  const GeodesicField g = geodesic_distance(m, source_from_plane(m, Vec3(1, 0, 0), 0.0));
  const DivergenceMetric dg = divergence_metric(m, g.distance);
  const HarmonicField h = harmonic_field(m, {0.2, 0.3, 0.7, 0.8});
  const DivergenceMetric dh = divergence_metric(m, h.value);
  EXPECT_LT(dg.transfer_estimate(3.0), 0.1 * dh.transfer_estimate(3.0));
  EXPECT_LT(dg.normalised(), 2e-4);  // 1/mm: ~1.6 transfers over the 354 cm^2 at sw = 3 mm
  EXPECT_GT(dh.normalised(), 1e-3);
}

TEST(DivergenceMetric, RejectsBadFields) {
  const TriMesh m = flat_disk(10.0, 2.0);
  EXPECT_THROW(divergence_metric(m, std::vector<double>(3, 0.0)), InvalidInput);
  std::vector<double> f(m.num_vertices(), 1.0);
  f[0] = std::nan("");
  EXPECT_THROW(divergence_metric(m, f), InvalidInput);
  // A constant field has no direction anywhere: every face is flat, metric 0.
  const DivergenceMetric c = divergence_metric(m, std::vector<double>(m.num_vertices(), 2.0));
  EXPECT_EQ(c.flat_faces, m.num_faces());
  EXPECT_EQ(c.total, 0.0);
}

}  // namespace
}  // namespace knitforge
