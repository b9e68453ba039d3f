#pragma once
/// \file energy_eval.h
/// EnergyEval: what every energy term adds into — a value, a gradient and
/// (optionally) a sparse Hessian of the 3n positions x = (x_0, y_0, z_0, x_1,
/// ...), n vertices, in the simulator's units (energy µJ = mN·mm, gradient mN,
/// Hessian mN/mm).
///
/// The Hessian has a fixed sparsity pattern (HessianPattern): every pair of
/// vertices that shares a membrane element or a bending hinge, plus every
/// vertex with itself (contact, friction, inertia and pins only touch those
/// diagonal blocks). The pattern is built once per model, so the symbolic
/// analysis of the Cholesky factorisation can be reused by every Newton
/// iteration and time step, and terms add their element blocks straight into
/// the matrix's value array (no triplet sort).

#include <algorithm>
#include <array>
#include <memory>
#include <span>
#include <vector>

#include <Eigen/Core>

#include "knitforge/geometry/sparse_solver.h"
#include "knitforge/geometry/vec.h"
#include "knitforge/util/parallel_ranges.h"

namespace knitforge {

struct SimModel;

/// Value, gradient and Hessian of one element of K vertices (3K unknowns).
template <int K>
struct ElementEnergy {
  double value = 0.0;
  Eigen::Matrix<double, 3 * K, 1> gradient = Eigen::Matrix<double, 3 * K, 1>::Zero();
  Eigen::Matrix<double, 3 * K, 3 * K> hessian = Eigen::Matrix<double, 3 * K, 3 * K>::Zero();
};

/// The lower triangle of a symmetric 3n x 3n matrix made of 3x3 vertex
/// blocks, in compressed column form (what CHOLMOD reads).
class HessianPattern {
 public:
  /// Pattern with the diagonal blocks of `num_vertices` vertices and the
  /// blocks of every pair of vertices within one stencil (a stencil is a
  /// list of 2-4 vertex indices; -1 entries are ignored).
  HessianPattern(int num_vertices, std::span<const std::array<int, 4>> stencils);

  int num_vertices() const { return n_; }
  int64_t nonzeros() const { return static_cast<int64_t>(inner_.size()); }
  /// Index into the value array of entry (3i + p, 3j + q) of the lower
  /// triangle, for vertices i >= j in the pattern (p >= q when i == j);
  /// -1 when the block is not in the pattern.
  int64_t index(int i, int p, int j, int q) const;
  /// Position of vertex i among the neighbours i' > j of vertex j (i > j),
  /// -1 when (i, j) is not in the pattern. Entry (3i + p, 3j + q) is at
  /// column_starts()[3j + q] + (3 - q) + 3 rank + p.
  int rank(int i, int j) const;
  /// Index of diagonal entry (r, r).
  int64_t diagonal_index(int r) const { return outer_[r]; }
  /// A matrix with this pattern and the given values (nonzeros() entries).
  SparseMatrix matrix(std::span<const double> values) const;
  /// Row index of every stored entry, and the first entry of every column
  /// (3n + 1), in compressed column order.
  const std::vector<int>& rows() const { return inner_; }
  const std::vector<int64_t>& column_starts() const { return outer_; }

 private:
  int n_ = 0;
  std::vector<int64_t> outer_;             ///< 3n + 1 column starts
  std::vector<int> inner_;                 ///< row of every entry
  std::vector<int> neighbour_start_;       ///< n + 1: per vertex j, its neighbours i > j in neighbours_
  std::vector<int> neighbours_;            ///< sorted
};

/// The pattern of a model's membrane elements and bending hinges.
std::shared_ptr<const HessianPattern> build_hessian_pattern(const SimModel& model);

/// How much of an energy to evaluate.
enum class Derivatives { Value, Gradient, Hessian };

/// Value, gradient and Hessian of a sum of energy terms (see the file
/// comment). Terms only add; the caller creates one EnergyEval per
/// evaluation.
struct EnergyEval {
  double value = 0.0;
  Eigen::VectorXd gradient;            ///< 3n (empty when only the value is wanted)
  std::vector<double> hessian_values;  ///< pattern->nonzeros() (empty unless Derivatives::Hessian)
  std::shared_ptr<const HessianPattern> pattern;

  /// An empty evaluation of n vertices with the requested derivatives
  /// (`pattern` required for Derivatives::Hessian).
  EnergyEval(int num_vertices, Derivatives what, std::shared_ptr<const HessianPattern> pattern = nullptr);

  bool wants_gradient() const { return gradient.size() > 0; }
  bool wants_hessian() const { return !hessian_values.empty(); }

  /// Adds the 3x3 block H_ij (rows of vertex i, columns of vertex j) of a
  /// symmetric element Hessian. Call it for every ordered pair (i, j) of the
  /// element, i == j included: only the blocks in the lower triangle are
  /// stored, the others are ignored. \pre the block is in the pattern.
  void add_hessian_block(int i, int j, const Mat3& block);
  /// Adds a dense element Hessian over `vertices` (3k x 3k, k = size).
  template <int K>
  void add_element_hessian(const std::array<int, K>& vertices, const Eigen::Matrix<double, 3 * K, 3 * K>& h) {
    for (int a = 0; a < K; ++a)
      for (int b = 0; b < K; ++b) add_hessian_block(vertices[a], vertices[b], h.template block<3, 3>(3 * a, 3 * b));
  }
  /// Adds g to the gradient entries of vertex v.
  void add_gradient(int v, const Vec3& g) { gradient.segment<3>(3 * v) += g; }
};

/// Adds the energies of n elements of K vertices to `out`:
/// element(i, what) returns element i's ElementEnergy<K> with the
/// derivatives `what`, and `vertices(i)` its K vertices. The values and
/// gradients of large sets are computed on all hardware threads
/// (util/parallel_ranges.h), a block at a time, and added to `out` in
/// element order, so `out` holds the same bits as a serial loop gives.
/// Hessians are computed and added serially: held per element they cost
/// more memory (1.2 kB for 4 vertices) than the threads saved (measured on
/// the free hemisphere, docs/benchmarks.md).
template <int K, class Element, class Vertices>
void add_element_energies(std::size_t n, const Element& element, const Vertices& vertices, EnergyEval& out) {
  const Derivatives what = out.wants_hessian()    ? Derivatives::Hessian
                           : out.wants_gradient() ? Derivatives::Gradient
                                                  : Derivatives::Value;
  // Below this many elements the threads cost more than they save.
  constexpr std::size_t kParallelFrom = 2048, kBlock = 8192;
  if (what == Derivatives::Hessian || n < kParallelFrom) {
    for (std::size_t i = 0; i < n; ++i) {
      const std::array<int, K> v = vertices(i);
      const ElementEnergy<K> e = element(i, what);
      out.value += e.value;
      if (what == Derivatives::Value) continue;
      for (int k = 0; k < K; ++k) out.add_gradient(v[k], e.gradient.template segment<3>(3 * k));
      if (what == Derivatives::Hessian) out.add_element_hessian<K>(v, e.hessian);
    }
    return;
  }
  // Kept between calls (one set per calling thread): a solve evaluates the
  // same model hundreds of times, and fresh pages cost more than the copy.
  // The lambda below reaches them through references: a thread_local named
  // in it would be the worker thread's own, empty one.
  thread_local std::vector<double> kept_values;
  thread_local std::vector<Eigen::Matrix<double, 3 * K, 1>> kept_gradients;
  std::vector<double>& values = kept_values;
  std::vector<Eigen::Matrix<double, 3 * K, 1>>& gradients = kept_gradients;
  for (std::size_t first = 0; first < n; first += kBlock) {
    const std::size_t count = std::min(kBlock, n - first);
    values.resize(count);
    if (what == Derivatives::Gradient) gradients.resize(count);
    parallel_ranges(count, kParallelFrom, [&](std::size_t begin, std::size_t end) {
      for (std::size_t i = begin; i < end; ++i) {
        const ElementEnergy<K> e = element(first + i, what);
        values[i] = e.value;
        if (what == Derivatives::Gradient) gradients[i] = e.gradient;
      }
    });
    for (std::size_t i = 0; i < count; ++i) {
      out.value += values[i];
      if (what == Derivatives::Value) continue;
      const std::array<int, K> v = vertices(first + i);
      for (int k = 0; k < K; ++k) out.add_gradient(v[k], gradients[i].template segment<3>(3 * k));
    }
  }
}

}  // namespace knitforge
