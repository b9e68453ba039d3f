#pragma once
/// \file sparse_solver.h
/// The one sparse linear-algebra wrapper of knitforge (ARCHITECTURE.md):
/// a symmetric positive definite matrix factored once with CHOLMOD's
/// Cholesky (LL^T via Eigen's CholmodSupport: simplicial below 10k unknowns,
/// supernodal from there on, where OpenBLAS makes it 3.5-5x faster), then any number of
/// right-hand sides solved against the factor. Failures are checked and
/// reported as SolverError instead of silently returning garbage.

#include <memory>

#include <Eigen/Core>
#include <Eigen/SparseCore>

namespace knitforge {

using SparseMatrix = Eigen::SparseMatrix<double>;

/// How the factor is computed.
/// - Auto: simplicial below 10k unknowns, supernodal from there on (fast).
/// - Simplicial: always CHOLMOD's simplicial factor, which calls no BLAS.
///   The supernodal factor's last bits depend on the BLAS kernels OpenBLAS
///   picks for the CPU (Haswell, SkylakeX, ... give different round-off), so
///   use this where a result must be bit-identical on every machine, e.g. the
///   built-in body model (body/generated_body.h), whose fits amplify
///   round-off.
enum class FactorMode { Auto, Simplicial };

/// Cholesky factor of a sparse symmetric positive definite matrix.
/// Move-only. Only the lower triangle of the matrix is read.
class SparseSolver {
 public:
  explicit SparseSolver(FactorMode mode = FactorMode::Auto);
  /// Factors A (see factor()).
  explicit SparseSolver(const SparseMatrix& A, FactorMode mode = FactorMode::Auto);
  ~SparseSolver();
  SparseSolver(SparseSolver&&) noexcept;
  SparseSolver& operator=(SparseSolver&&) noexcept;
  SparseSolver(const SparseSolver&) = delete;
  SparseSolver& operator=(const SparseSolver&) = delete;

  /// Factors A = L L^T (replacing any previous factor).
  /// \throw InvalidInput when A is not square, empty, or has non-finite entries;
  ///        SolverError when A is not positive definite (singular or
  ///        indefinite), naming the column where the factorisation stopped.
  void factor(const SparseMatrix& A);
  /// Factors A, whose sparsity pattern is that of the matrix of the last
  /// successful factor()/refactor() (same size and non-zeros): the symbolic
  /// analysis (ordering) is reused, only the numeric factor is recomputed.
  /// Falls back to factor() when there is none or the size or non-zero count
  /// differs. After analyze(), A must have exactly the analysed pattern
  /// (same nonzero positions, explicit zeros included); no fallback then.
  /// \throw as factor(); after analyze(), InvalidInput when A has another
  ///        size or pattern.
  void refactor(const SparseMatrix& A);

  /// Symbolic analysis only (fill-reducing ordering, elimination tree) of
  /// the pattern of A (its values are not read), for refactor(): a caller
  /// that factors many matrices with one sparsity pattern (a Laplacian with
  /// changing Dirichlet rows kept as explicit zeros) pays the ordering once.
  /// Drops any previous factor.
  /// \throw InvalidInput when A is not square or empty.
  void analyze(const SparseMatrix& pattern);

  bool factored() const;
  /// Size of the factored matrix (0 before factor()).
  int rows() const;

  /// Solves A x = b. \throw InvalidInput when not factored or b has the wrong
  /// size; SolverError when the solution is not finite.
  Eigen::VectorXd solve(const Eigen::VectorXd& b) const;
  /// Solves A X = B for all columns of B at once (same checks as above);
  /// cheaper than one solve() per column.
  Eigen::MatrixXd solve_columns(const Eigen::MatrixXd& B) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// Whether CHOLMOD's calls run with OpenMP's parallel regions off. Debian's
/// CHOLMOD runs parts of the supernodal factor and solves in parallel
/// regions of a fixed 4 threads, whose start and join cost more than they
/// give on a small machine (on the free short-row hemisphere, 11k unknowns,
/// 2 cores, about a quarter of the process's time went to waking and
/// parking those threads: docs/benchmarks.md, 2026-12-07). So every
/// SparseSolver call into CHOLMOD sets the calling thread's OpenMP
/// max-active-levels to 0 for its duration and restores the previous value
/// afterwards; OpenMP work outside these calls (LibTorch in knitforge-ddr)
/// keeps its threads.
/// The results do not change (the parallel loops are independent). False
/// when the process has no OpenMP runtime, or the environment sets
/// OMP_MAX_ACTIVE_LEVELS (then that stands for CHOLMOD too).
bool serial_cholmod_calls();
/// The calling thread's OpenMP max-active-levels now (-1 without an OpenMP
/// runtime); for tests.
int openmp_max_active_levels();

/// One-shot: factors A and solves A x = b. Throws as SparseSolver.
Eigen::VectorXd solve_spd(const SparseMatrix& A, const Eigen::VectorXd& b);

}  // namespace knitforge
