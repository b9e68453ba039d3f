// Cotangent Laplacian and mixed Voronoi areas (geometry/cotan_laplacian.h),
// and the symbolic-reuse path of the sparse solver.
#include "knitforge/geometry/cotan_laplacian.h"

#include <gtest/gtest.h>

#include <cmath>

#include "geometry/test_meshes.h"
#include "knitforge/geometry/mesh_measures.h"
#include "knitforge/geometry/shapes.h"
#include "knitforge/util/errors.h"

namespace knitforge {
namespace {

Eigen::VectorXd linear_field(const TriMesh& m, const Vec3& a, double c) {
  Eigen::VectorXd x(m.num_vertices());
  for (int v = 0; v < m.num_vertices(); ++v) x[v] = a.dot(m.vertices[v]) + c;
  return x;
}

TEST(CotanLaplacian, AnnihilatesLinearFunctionsAtInteriorVerticesAndHasConstantNullSpace) {
  const TriMesh m = flat_disk(20.0, 2.0);  // irregular planar triangulation
  const SparseMatrix L = cotan_laplacian(m);
  const Halfedges he = build_halfedges(m.num_vertices(), m.faces);
  const Eigen::VectorXd ones = Eigen::VectorXd::Ones(m.num_vertices());
  EXPECT_LE((L * ones).cwiseAbs().maxCoeff(), 1e-9);
  const Eigen::VectorXd y = L * linear_field(m, Vec3(0.3, -1.2, 0.0), 4.0);
  for (int v = 0; v < m.num_vertices(); ++v)
    if (!he.is_boundary_vertex(v)) {
      EXPECT_NEAR(y[v], 0.0, 1e-9) << "vertex " << v;
    }
  // Symmetric.
  EXPECT_LE((SparseMatrix(L.transpose()) - L).norm(), 1e-12 * L.norm());
}

TEST(CotanLaplacian, QuadraticFormIsTheDirichletEnergy) {
  const TriMesh m = hemisphere(30.0, 3.0);
  const SparseMatrix L = cotan_laplacian(m);
  // For a piecewise-linear x, x^T L x = sum over faces of area |grad x|^2.
  Eigen::VectorXd x(m.num_vertices());
  for (int v = 0; v < m.num_vertices(); ++v) x[v] = std::sin(0.1 * m.vertices[v].x()) + 0.02 * m.vertices[v].y();
  double energy = 0.0;
  for (const auto& f : m.faces) {
    const Vec3 &a = m.vertices[f[0]], &b = m.vertices[f[1]], &c = m.vertices[f[2]];
    const Vec3 av = (b - a).cross(c - a);
    const double two_a = av.norm();
    const Vec3 n = av / two_a;
    const Vec3 g = (x[f[0]] * n.cross(c - b) + x[f[1]] * n.cross(a - c) + x[f[2]] * n.cross(b - a)) / two_a;
    energy += 0.5 * two_a * g.squaredNorm();
  }
  EXPECT_NEAR(x.dot(L * x), energy, 1e-9 * energy);
}

TEST(CotanLaplacian, VoronoiAreasSumToTheSurfaceArea) {
  for (const TriMesh& m : {hemisphere(30.0, 3.0), triple_peak(5.0), flat_disk(20.0, 2.0)}) {
    const std::vector<double> a = mixed_voronoi_areas(m);
    double sum = 0.0;
    for (double x : a) {
      EXPECT_GT(x, 0.0);
      sum += x;
    }
    EXPECT_NEAR(sum, total_area(m), 1e-9 * total_area(m));
  }
  // A right isosceles triangle: its circumcentre is on the hypotenuse, so the
  // Voronoi split gives the right-angle corner half the area.
  TriMesh t;
  t.vertices = {Vec3(0, 0, 0), Vec3(2, 0, 0), Vec3(0, 2, 0)};
  t.faces = {{0, 1, 2}};
  const std::vector<double> a = mixed_voronoi_areas(t);
  EXPECT_NEAR(a[0], 1.0, 1e-12);
  EXPECT_NEAR(a[1], 0.5, 1e-12);
  EXPECT_NEAR(a[2], 0.5, 1e-12);
}

TEST(CotanLaplacian, RejectsFacesOutOfRange) {
  TriMesh t;
  t.vertices = {Vec3(0, 0, 0), Vec3(1, 0, 0)};
  t.faces = {{0, 1, 2}};
  EXPECT_THROW(cotan_laplacian(t), InvalidInput);
  EXPECT_THROW(mixed_voronoi_areas(t), InvalidInput);
}

TEST(SparseSolverRefactor, ReusesTheSymbolicAnalysisForMatricesOfOnePattern) {
  const TriMesh m = flat_disk(15.0, 2.0);
  SparseMatrix L = cotan_laplacian(m);
  SparseSolver s;
  s.analyze(L);
  EXPECT_FALSE(s.factored());
  for (double shift : {0.5, 0.01, 3.0}) {
    SparseMatrix A = L;
    for (int k = 0; k < A.outerSize(); ++k)
      for (SparseMatrix::InnerIterator it(A, k); it; ++it)
        if (it.row() == it.col()) it.valueRef() += shift;
    s.refactor(A);
    ASSERT_TRUE(s.factored());
    const Eigen::VectorXd x_true = linear_field(m, Vec3(1, 2, 0), -1);
    const Eigen::VectorXd x = s.solve(A * x_true);
    EXPECT_LE((x - x_true).norm(), 1e-9 * x_true.norm()) << "shift " << shift;
    // Same result as a fresh factorisation.
    EXPECT_LE((x - solve_spd(A, A * x_true)).norm(), 1e-9 * x_true.norm());
  }
  // Explicit zeros keep their place in the pattern.
  SparseMatrix Z = L;
  for (int k = 0; k < Z.outerSize(); ++k)
    for (SparseMatrix::InnerIterator it(Z, k); it; ++it) it.valueRef() = it.row() == it.col() ? 1.0 : 0.0;
  s.refactor(Z);
  EXPECT_NEAR(s.solve(Eigen::VectorXd::Ones(m.num_vertices())).sum(), m.num_vertices(), 1e-9);
  // An indefinite matrix of the same pattern is refused, with the factor marked invalid.
  SparseMatrix N = L;
  for (int k = 0; k < N.outerSize(); ++k)
    for (SparseMatrix::InnerIterator it(N, k); it; ++it)
      if (it.row() == it.col()) it.valueRef() -= 0.5;
  EXPECT_THROW(s.refactor(N), SolverError);
  EXPECT_FALSE(s.factored());
  // Another pattern is refused.
  SparseMatrix other = L;
  other.coeffRef(0, m.num_vertices() - 1) = 0.1;
  other.coeffRef(m.num_vertices() - 1, 0) = 0.1;
  EXPECT_THROW(s.refactor(other), InvalidInput);
  // Without analyze(), refactor() of a first matrix factors it.
  SparseMatrix A = L;
  for (int k = 0; k < A.outerSize(); ++k)
    for (SparseMatrix::InnerIterator it(A, k); it; ++it)
      if (it.row() == it.col()) it.valueRef() += 1.0;
  SparseSolver fresh;
  fresh.refactor(A);
  EXPECT_TRUE(fresh.factored());
}

}  // namespace
}  // namespace knitforge
