#include "knitforge/geometry/sparse_solver.h"

#include <cmath>

#include <Eigen/CholmodSupport>
#include <fmt/core.h>

#include "knitforge/util/errors.h"

namespace knitforge {

struct SparseSolver::Impl {
  // CHOLMOD's simplicial LL^T: with the reference BLAS of this platform the
  // supernodal factor was measured slower on Shape-Up systems (50k unknowns:
  // factor 0.34 s vs 0.49 s, 3-column solve 16 ms vs 43 ms).
  Eigen::CholmodSimplicialLLT<SparseMatrix, Eigen::Lower> llt;
  int n = 0;
  long nnz = -1;  // of the analysed pattern
  bool ok = false;
  Impl() {
    // The library never prints: silence CHOLMOD's own error/warning output,
    // failures are reported through info() below.
    llt.cholmod().print = 0;
    llt.cholmod().error_handler = nullptr;
  }
};

SparseSolver::SparseSolver() : impl_(std::make_unique<Impl>()) {}
SparseSolver::SparseSolver(const SparseMatrix& A) : SparseSolver() { factor(A); }
SparseSolver::~SparseSolver() = default;
SparseSolver::SparseSolver(SparseSolver&&) noexcept = default;
SparseSolver& SparseSolver::operator=(SparseSolver&&) noexcept = default;

void SparseSolver::factor(const SparseMatrix& A) {
  if (!impl_) impl_ = std::make_unique<Impl>();
  impl_->ok = false;
  impl_->n = 0;
  if (A.rows() != A.cols()) {
    throw InvalidInput(fmt::format("sparse solver: matrix is {} x {}, it must be square", A.rows(), A.cols()));
  }
  if (A.rows() == 0) throw InvalidInput("sparse solver: matrix is empty");
  for (int k = 0; k < A.outerSize(); ++k) {
    for (SparseMatrix::InnerIterator it(A, k); it; ++it) {
      if (!std::isfinite(it.value())) {
        throw InvalidInput(fmt::format("sparse solver: matrix entry ({}, {}) is not finite", it.row(), it.col()));
      }
    }
  }
  impl_->llt.compute(A);  // reads the lower triangle only
  impl_->nnz = A.nonZeros();
  if (impl_->llt.info() != Eigen::Success) {
    const auto& c = impl_->llt.cholmod();
    throw SolverError(fmt::format(
        "sparse solver: the {} x {} matrix is not positive definite (CHOLMOD status {}); "
        "check that the system has no free null space (e.g. a translation that no fixed vertex pins)",
        A.rows(), A.cols(), c.status));
  }
  impl_->n = static_cast<int>(A.rows());
  impl_->ok = true;
}

void SparseSolver::refactor(const SparseMatrix& A) {
  if (!impl_ || !impl_->ok || A.rows() != impl_->n || A.cols() != impl_->n || A.nonZeros() != impl_->nnz) {
    factor(A);
    return;
  }
  impl_->ok = false;
  for (int k = 0; k < A.outerSize(); ++k) {
    for (SparseMatrix::InnerIterator it(A, k); it; ++it) {
      if (!std::isfinite(it.value())) {
        throw InvalidInput(fmt::format("sparse solver: matrix entry ({}, {}) is not finite", it.row(), it.col()));
      }
    }
  }
  impl_->llt.factorize(A);
  if (impl_->llt.info() != Eigen::Success) {
    throw SolverError(fmt::format(
        "sparse solver: the {} x {} matrix is not positive definite (CHOLMOD status {})", A.rows(), A.cols(),
        impl_->llt.cholmod().status));
  }
  impl_->ok = true;
}

bool SparseSolver::factored() const { return impl_ && impl_->ok; }
int SparseSolver::rows() const { return impl_ ? impl_->n : 0; }

namespace {
template <typename M>
void check_solution(const M& x) {
  if (!x.allFinite()) {
    throw SolverError("sparse solver: the solution is not finite (the matrix is nearly singular or the "
                      "right-hand side holds NaN/inf)");
  }
}
}  // namespace

Eigen::VectorXd SparseSolver::solve(const Eigen::VectorXd& b) const {
  if (!factored()) throw InvalidInput("sparse solver: solve() called before a successful factor()");
  if (b.size() != impl_->n) {
    throw InvalidInput(fmt::format("sparse solver: right-hand side has {} entries, expected {}", b.size(), impl_->n));
  }
  Eigen::VectorXd x = impl_->llt.solve(b);
  if (impl_->llt.info() != Eigen::Success) throw SolverError("sparse solver: CHOLMOD solve failed");
  check_solution(x);
  return x;
}

Eigen::MatrixXd SparseSolver::solve_columns(const Eigen::MatrixXd& B) const {
  if (!factored()) throw InvalidInput("sparse solver: solve() called before a successful factor()");
  if (B.rows() != impl_->n) {
    throw InvalidInput(fmt::format("sparse solver: right-hand side has {} rows, expected {}", B.rows(), impl_->n));
  }
  Eigen::MatrixXd X = impl_->llt.solve(B);
  if (impl_->llt.info() != Eigen::Success) throw SolverError("sparse solver: CHOLMOD solve failed");
  check_solution(X);
  return X;
}

Eigen::VectorXd solve_spd(const SparseMatrix& A, const Eigen::VectorXd& b) {
  SparseSolver s(A);
  return s.solve(b);
}

}  // namespace knitforge
