#include "knitforge/geometry/sparse_solver.h"

#include <gtest/gtest.h>

#include <vector>

#include "knitforge/util/errors.h"

using namespace knitforge;

namespace {

// 1D Laplacian plus a diagonal shift: SPD for shift > 0, indefinite for a
// shift below -lambda_min.
SparseMatrix shifted_laplacian(int n, double shift) {
  std::vector<Eigen::Triplet<double>> t;
  for (int i = 0; i < n; ++i) {
    t.emplace_back(i, i, 2.0 + shift);
    if (i + 1 < n) {
      t.emplace_back(i, i + 1, -1.0);
      t.emplace_back(i + 1, i, -1.0);
    }
  }
  SparseMatrix A(n, n);
  A.setFromTriplets(t.begin(), t.end());
  return A;
}

}  // namespace

TEST(SparseSolver, SolvesSpdSystems) {
  const SparseMatrix A = shifted_laplacian(200, 0.01);
  Eigen::VectorXd x_true = Eigen::VectorXd::LinSpaced(200, -1, 3);
  const Eigen::VectorXd b = A * x_true;
  const Eigen::VectorXd x = solve_spd(A, b);
  EXPECT_LE((x - x_true).norm(), 1e-9 * x_true.norm());

  SparseSolver s(A);
  EXPECT_TRUE(s.factored());
  EXPECT_EQ(s.rows(), 200);
  Eigen::MatrixXd X_true(200, 3);
  X_true.setRandom();
  const Eigen::MatrixXd X = s.solve_columns(A * X_true);
  EXPECT_LE((X - X_true).norm(), 1e-9 * X_true.norm());
  // Reuse: a second right-hand side against the same factor.
  EXPECT_LE((s.solve(b) - x_true).norm(), 1e-9 * x_true.norm());
}

TEST(SparseSolver, IndefiniteMatrixThrowsSolverError) {
  const SparseMatrix A = shifted_laplacian(50, -1.0);  // eigenvalues 1 - 2cos(...) < 0 for some
  EXPECT_THROW(SparseSolver{A}, SolverError);
  EXPECT_THROW(solve_spd(A, Eigen::VectorXd::Ones(50)), SolverError);
  // Singular (pure Laplacian with a free constant mode, Neumann ends).
  SparseMatrix L = shifted_laplacian(10, 0.0);
  L.coeffRef(0, 0) = 1.0;
  L.coeffRef(9, 9) = 1.0;
  EXPECT_THROW(SparseSolver{L}, SolverError);
}

TEST(SparseSolver, BadInputs) {
  EXPECT_THROW(SparseSolver{SparseMatrix(3, 4)}, InvalidInput);
  EXPECT_THROW(SparseSolver{SparseMatrix(0, 0)}, InvalidInput);
  SparseMatrix A = shifted_laplacian(4, 1.0);
  A.coeffRef(1, 1) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(SparseSolver{A}, InvalidInput);
  SparseSolver empty;
  EXPECT_FALSE(empty.factored());
  EXPECT_THROW(empty.solve(Eigen::VectorXd::Ones(4)), InvalidInput);
  SparseSolver s(shifted_laplacian(4, 1.0));
  EXPECT_THROW(s.solve(Eigen::VectorXd::Ones(5)), InvalidInput);
  Eigen::VectorXd nan = Eigen::VectorXd::Ones(4);
  nan(2) = std::numeric_limits<double>::infinity();
  EXPECT_THROW(s.solve(nan), SolverError);
}
