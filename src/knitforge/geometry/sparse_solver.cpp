#include "knitforge/geometry/sparse_solver.h"

#include <dlfcn.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <vector>

#include <Eigen/CholmodSupport>
#include <fmt/core.h>

#include "knitforge/util/errors.h"

namespace knitforge {

namespace {

// CHOLMOD's OpenMP regions made serial while a CHOLMOD call runs (see
// serial_cholmod_calls() in the header). The OpenMP runtime is looked up at
// run time: CHOLMOD brings it in when it was built with OpenMP; without it,
// or when the user sets OMP_MAX_ACTIVE_LEVELS, nothing is changed.
struct OpenMpLevels {
  using Get = int (*)();
  using Set = void (*)(int);
  Get get = nullptr;
  Set set = nullptr;
  OpenMpLevels() {
    if (std::getenv("OMP_MAX_ACTIVE_LEVELS") != nullptr) return;  // the user's choice stands
    get = reinterpret_cast<Get>(dlsym(RTLD_DEFAULT, "omp_get_max_active_levels"));
    set = reinterpret_cast<Set>(dlsym(RTLD_DEFAULT, "omp_set_max_active_levels"));
    if (get == nullptr || set == nullptr) get = nullptr, set = nullptr;
  }
};

const OpenMpLevels& openmp_levels() {
  static const OpenMpLevels levels;
  return levels;
}

/// Scope of one CHOLMOD call: max-active-levels is 0 inside and back to its
/// value afterwards. The value belongs to the calling thread (OpenMP 5's
/// per-data-environment ICV, as libgomp keeps it), so other threads' OpenMP
/// work is not touched.
class SerialCholmod {
 public:
  SerialCholmod() {
    const OpenMpLevels& l = openmp_levels();
    if (l.set == nullptr) return;
    saved_ = l.get();
    l.set(0);
  }
  ~SerialCholmod() {
    const OpenMpLevels& l = openmp_levels();
    if (l.set != nullptr) l.set(saved_);
  }
  SerialCholmod(const SerialCholmod&) = delete;
  SerialCholmod& operator=(const SerialCholmod&) = delete;

 private:
  int saved_ = 0;
};

}  // namespace

bool serial_cholmod_calls() { return openmp_levels().set != nullptr; }

int openmp_max_active_levels() {
  const OpenMpLevels& l = openmp_levels();
  return l.get != nullptr ? l.get() : -1;
}

struct SparseSolver::Impl {
  // CHOLMOD's LL^T, simplicial below kSupernodalFrom unknowns and supernodal
  // from there on (set per analysis by use_mode_for()). With OpenBLAS (serial,
  // installed by scripts/setup) the supernodal factor is 3.5-5x faster from
  // 50k unknowns on (CPU time, triangulated-grid systems with 3 unknowns per
  // vertex: 0.23 s vs 0.81 s at 50.7k, 0.75 s vs 3.7 s at 120k); below about
  // 10k unknowns the two are within milliseconds and simplicial solves faster.
  Eigen::CholmodDecomposition<SparseMatrix, Eigen::Lower> llt;
  int n = 0;
  long nnz = -1;  // of the analysed pattern
  bool ok = false;
  bool analyzed = false;
  // Pattern of analyze() (column starts and row indices, lower triangle).
  std::vector<SparseMatrix::StorageIndex> outer, inner;
  Impl() {
    // The library never prints: silence CHOLMOD's own error/warning output,
    // failures are reported through info() below.
    llt.cholmod().print = 0;
    llt.cholmod().error_handler = nullptr;
  }
  FactorMode mode = FactorMode::Auto;
  static constexpr long kSupernodalFrom = 10000;
  void use_mode_for(long unknowns) {
    const bool supernodal = mode == FactorMode::Auto && unknowns >= kSupernodalFrom;
    llt.setMode(supernodal ? Eigen::CholmodSupernodalLLt : Eigen::CholmodSimplicialLLt);
  }
};

SparseSolver::SparseSolver(FactorMode mode) : impl_(std::make_unique<Impl>()) { impl_->mode = mode; }
SparseSolver::SparseSolver(const SparseMatrix& A, FactorMode mode) : SparseSolver(mode) { factor(A); }
SparseSolver::~SparseSolver() = default;
SparseSolver::SparseSolver(SparseSolver&&) noexcept = default;
SparseSolver& SparseSolver::operator=(SparseSolver&&) noexcept = default;

namespace {

void check_square(const SparseMatrix& A) {
  if (A.rows() != A.cols()) {
    throw InvalidInput(fmt::format("sparse solver: matrix is {} x {}, it must be square", A.rows(), A.cols()));
  }
  if (A.rows() == 0) throw InvalidInput("sparse solver: matrix is empty");
}

void check_finite(const SparseMatrix& A) {
  for (int k = 0; k < A.outerSize(); ++k) {
    for (SparseMatrix::InnerIterator it(A, k); it; ++it) {
      if (!std::isfinite(it.value())) {
        throw InvalidInput(fmt::format("sparse solver: matrix entry ({}, {}) is not finite", it.row(), it.col()));
      }
    }
  }
}

/// The lower triangle of A, compressed (the pattern CHOLMOD sees).
SparseMatrix lower_part(const SparseMatrix& A) {
  SparseMatrix L = A.triangularView<Eigen::Lower>();
  L.makeCompressed();
  return L;
}

}  // namespace

void SparseSolver::analyze(const SparseMatrix& pattern) {
  if (!impl_) impl_ = std::make_unique<Impl>();
  impl_->ok = false;
  impl_->analyzed = false;
  impl_->n = 0;
  check_square(pattern);
  const SparseMatrix L = lower_part(pattern);
  impl_->use_mode_for(L.rows());
  {
    SerialCholmod serial;
    impl_->llt.analyzePattern(L);
  }
  impl_->outer.assign(L.outerIndexPtr(), L.outerIndexPtr() + L.outerSize() + 1);
  impl_->inner.assign(L.innerIndexPtr(), L.innerIndexPtr() + L.nonZeros());
  impl_->n = static_cast<int>(pattern.rows());
  impl_->analyzed = true;
}

namespace {

/// refactor() after analyze(): the exact analysed pattern.
void refactor_analyzed(Eigen::CholmodDecomposition<SparseMatrix, Eigen::Lower>& llt, int n,
                       const std::vector<SparseMatrix::StorageIndex>& outer,
                       const std::vector<SparseMatrix::StorageIndex>& inner, const SparseMatrix& A, bool& ok) {
  if (A.rows() != n || A.cols() != n) {
    throw InvalidInput(fmt::format("sparse solver: refactor() of a {} x {} matrix, analyzed {} x {}", A.rows(),
                                   A.cols(), n, n));
  }
  check_finite(A);
  const SparseMatrix L = lower_part(A);
  if (!std::equal(outer.begin(), outer.end(), L.outerIndexPtr()) ||
      static_cast<size_t>(L.nonZeros()) != inner.size() || !std::equal(inner.begin(), inner.end(), L.innerIndexPtr())) {
    throw InvalidInput("sparse solver: refactor() of a matrix whose pattern differs from the analyzed one");
  }
  {
    SerialCholmod serial;
    llt.factorize(L);
  }
  if (llt.info() != Eigen::Success) {
    throw SolverError(fmt::format("sparse solver: the {} x {} matrix is not positive definite (CHOLMOD status {})",
                                  A.rows(), A.cols(), llt.cholmod().status));
  }
  ok = true;
}

}  // namespace

void SparseSolver::factor(const SparseMatrix& A) {
  if (!impl_) impl_ = std::make_unique<Impl>();
  impl_->ok = false;
  impl_->analyzed = false;
  impl_->n = 0;
  check_square(A);
  check_finite(A);
  impl_->use_mode_for(A.rows());
  {
    SerialCholmod serial;
    impl_->llt.compute(A);  // reads the lower triangle only
  }
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
  if (impl_ && impl_->analyzed) {
    impl_->ok = false;
    refactor_analyzed(impl_->llt, impl_->n, impl_->outer, impl_->inner, A, impl_->ok);
    return;
  }
  if (!impl_ || !impl_->ok || A.rows() != impl_->n || A.cols() != impl_->n || A.nonZeros() != impl_->nnz) {
    factor(A);
    return;
  }
  impl_->ok = false;
  check_finite(A);
  {
    SerialCholmod serial;
    impl_->llt.factorize(A);
  }
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
  Eigen::VectorXd x;
  {
    SerialCholmod serial;
    x = impl_->llt.solve(b);
  }
  if (impl_->llt.info() != Eigen::Success) throw SolverError("sparse solver: CHOLMOD solve failed");
  check_solution(x);
  return x;
}

Eigen::MatrixXd SparseSolver::solve_columns(const Eigen::MatrixXd& B) const {
  if (!factored()) throw InvalidInput("sparse solver: solve() called before a successful factor()");
  if (B.rows() != impl_->n) {
    throw InvalidInput(fmt::format("sparse solver: right-hand side has {} rows, expected {}", B.rows(), impl_->n));
  }
  Eigen::MatrixXd X;
  {
    SerialCholmod serial;
    X = impl_->llt.solve(B);
  }
  if (impl_->llt.info() != Eigen::Success) throw SolverError("sparse solver: CHOLMOD solve failed");
  check_solution(X);
  return X;
}

Eigen::VectorXd solve_spd(const SparseMatrix& A, const Eigen::VectorXd& b) {
  SparseSolver s(A);
  return s.solve(b);
}

}  // namespace knitforge
