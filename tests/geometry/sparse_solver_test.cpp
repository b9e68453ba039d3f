#include "knitforge/geometry/sparse_solver.h"

#include <dlfcn.h>
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <iterator>
#include <thread>
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

// serial_cholmod_calls(): CHOLMOD's calls run with OpenMP's parallel regions
// off, and the value the process had is back afterwards (a process-wide
// change would serialise LibTorch's OpenMP work in knitforge-ddr); a
// supernodal factor (>= 10k unknowns) still solves exactly.
TEST(SparseSolver, CholmodCallsRunSerialAndRestoreOpenMp) {
  if (std::getenv("OMP_MAX_ACTIVE_LEVELS") != nullptr) GTEST_SKIP() << "OMP_MAX_ACTIVE_LEVELS is set";
  // Debian's CHOLMOD is built with OpenMP, so the runtime is there.
  ASSERT_TRUE(serial_cholmod_calls());
  using SetLevels = void (*)(int);
  const auto set = reinterpret_cast<SetLevels>(dlsym(RTLD_DEFAULT, "omp_set_max_active_levels"));
  ASSERT_NE(set, nullptr);
  const int before = openmp_max_active_levels();
  set(3);
  const SparseMatrix A = shifted_laplacian(12000, 0.01);
  const Eigen::VectorXd x_true = Eigen::VectorXd::LinSpaced(12000, -1, 3);
  SparseSolver s;
  s.analyze(A);
  s.refactor(A);
  EXPECT_LE((s.solve(A * x_true) - x_true).norm(), 1e-9 * x_true.norm());
  EXPECT_EQ(openmp_max_active_levels(), 3);
  SparseSolver t(A);
  Eigen::MatrixXd B(12000, 2);
  B << A * x_true, A * x_true;
  EXPECT_LE((t.solve_columns(B).col(1) - x_true).norm(), 1e-9 * x_true.norm());
  EXPECT_EQ(openmp_max_active_levels(), 3);
  EXPECT_THROW(SparseSolver{shifted_laplacian(50, -1.0)}, SolverError);  // a failed factor restores too
  EXPECT_EQ(openmp_max_active_levels(), 3);
  // Inside the calls CHOLMOD's parallel regions run on the calling thread
  // alone: the OpenMP runtime starts no workers for it. (A new thread has
  // a pool of its own, whose workers would stay listed until it ends.)
  std::thread fresh([] {
    const auto threads = [] {
      return std::distance(std::filesystem::directory_iterator("/proc/self/task"),
                           std::filesystem::directory_iterator{});
    };
    const SparseMatrix big = shifted_laplacian(60000, 0.01);
    const auto threads_before = threads();
    SparseSolver u(big);
    EXPECT_LE((u.solve(big * Eigen::VectorXd::Ones(60000)) - Eigen::VectorXd::Ones(60000)).norm(), 1e-7);
    EXPECT_EQ(threads(), threads_before);
  });
  fresh.join();
  EXPECT_EQ(openmp_max_active_levels(), 3);
  set(before);
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
