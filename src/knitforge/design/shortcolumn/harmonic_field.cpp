#include "knitforge/design/shortcolumn/harmonic_field.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include <Eigen/Dense>
#include <fmt/format.h>

#include "knitforge/geometry/cotan_laplacian.h"
#include "knitforge/geometry/halfedges.h"
#include "knitforge/geometry/mesh_measures.h"
#include "knitforge/geometry/surface_checks.h"
#include "knitforge/util/errors.h"

namespace knitforge {

struct HarmonicFieldSolver::Impl {
  const TriMesh* mesh = nullptr;
  SparseMatrix L;
  SparseMatrix A;  ///< the system, same pattern as L
  SparseSolver solver;
  BoundaryParameterisation boundary;
  Halfedges he;
};

HarmonicFieldSolver::HarmonicFieldSolver(const TriMesh& mesh) : impl_(std::make_unique<Impl>()) {
  require_disk(mesh, "harmonic field");
  impl_->mesh = &mesh;
  impl_->he = build_halfedges(mesh.num_vertices(), mesh.faces);
  impl_->boundary = parameterise_boundary(mesh);
  impl_->L = cotan_laplacian(mesh);
  impl_->A = impl_->L;
  impl_->solver.analyze(impl_->L);
}

HarmonicFieldSolver::~HarmonicFieldSolver() = default;
HarmonicFieldSolver::HarmonicFieldSolver(HarmonicFieldSolver&&) noexcept = default;
HarmonicFieldSolver& HarmonicFieldSolver::operator=(HarmonicFieldSolver&&) noexcept = default;

const BoundaryParameterisation& HarmonicFieldSolver::boundary() const { return impl_->boundary; }
const TriMesh& HarmonicFieldSolver::mesh() const { return *impl_->mesh; }

std::vector<double> HarmonicFieldSolver::solve_sets(const std::vector<int>& zero, const std::vector<int>& one) {
  const int n = impl_->mesh->num_vertices();
  if (zero.empty() || one.empty()) {
    throw InvalidInput("harmonic field: both Dirichlet sets (f = 0 and f = 1) need at least one vertex");
  }
  std::vector<signed char> fixed(static_cast<size_t>(n), -1);  // -1 free, 0 / 1 the value
  for (int v : zero) {
    if (v < 0 || v >= n) throw InvalidInput(fmt::format("harmonic field: Dirichlet vertex {} out of range", v));
    fixed[static_cast<size_t>(v)] = 0;
  }
  for (int v : one) {
    if (v < 0 || v >= n) throw InvalidInput(fmt::format("harmonic field: Dirichlet vertex {} out of range", v));
    if (fixed[static_cast<size_t>(v)] == 0) {
      throw InvalidInput(fmt::format("harmonic field: vertex {} is in both Dirichlet sets (f = 0 and f = 1)", v));
    }
    fixed[static_cast<size_t>(v)] = 1;
  }
  const SparseMatrix& L = impl_->L;
  SparseMatrix& A = impl_->A;
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(n);
  for (int j = 0; j < L.outerSize(); ++j) {
    SparseMatrix::InnerIterator a(A, j);
    for (SparseMatrix::InnerIterator it(L, j); it; ++it, ++a) {
      const int i = static_cast<int>(it.row());
      const signed char fi = fixed[static_cast<size_t>(i)], fj = fixed[static_cast<size_t>(j)];
      if (fi < 0 && fj < 0) {
        a.valueRef() = it.value();
      } else {
        a.valueRef() = i == j ? 1.0 : 0.0;
        if (fi < 0 && fj == 1) rhs[i] -= it.value();
      }
    }
  }
  for (int v = 0; v < n; ++v)
    if (fixed[static_cast<size_t>(v)] >= 0) rhs[v] = fixed[static_cast<size_t>(v)];
  impl_->solver.refactor(A);
  const Eigen::VectorXd x = impl_->solver.solve(rhs);
  std::vector<double> f(x.data(), x.data() + n);
  for (double& y : f) y = std::clamp(y, 0.0, 1.0);  // rounding only: the solution lies in [0, 1]
  return f;
}

HarmonicField HarmonicFieldSolver::solve(const BoundaryVector& b) {
  HarmonicField h;
  h.b = b;
  h.sets = dirichlet_sets(*impl_->mesh, impl_->boundary, b);
  h.value = solve_sets(h.sets.zero, h.sets.one);
  h.interior_extrema = count_interior_extrema(*impl_->mesh, h.value);
  return h;
}

HarmonicField harmonic_field(const TriMesh& mesh, const BoundaryVector& b) {
  HarmonicFieldSolver s(mesh);
  return s.solve(b);
}

int count_interior_extrema(const TriMesh& mesh, const std::vector<double>& field) {
  if (static_cast<int>(field.size()) != mesh.num_vertices()) {
    throw InvalidInput(fmt::format("interior extrema: field has {} values for {} vertices", field.size(),
                                   mesh.num_vertices()));
  }
  const int n = mesh.num_vertices();
  // Per vertex: is it above / below every edge neighbour so far.
  std::vector<char> is_max(static_cast<size_t>(n), 1), is_min(static_cast<size_t>(n), 1), used(static_cast<size_t>(n), 0);
  for (const auto& f : mesh.faces) {
    for (int k = 0; k < 3; ++k) {
      const int a = f[k], b = f[(k + 1) % 3];
      used[static_cast<size_t>(a)] = 1;
      if (!(field[a] > field[b])) is_max[static_cast<size_t>(a)] = 0;
      if (!(field[a] < field[b])) is_min[static_cast<size_t>(a)] = 0;
      if (!(field[b] > field[a])) is_max[static_cast<size_t>(b)] = 0;
      if (!(field[b] < field[a])) is_min[static_cast<size_t>(b)] = 0;
    }
  }
  const Halfedges he = build_halfedges(n, mesh.faces);
  int count = 0;
  for (int v = 0; v < n; ++v)
    if (used[static_cast<size_t>(v)] && !he.is_boundary_vertex(v) && (is_max[static_cast<size_t>(v)] || is_min[static_cast<size_t>(v)])) ++count;
  return count;
}

FiedlerField fiedler_field(const TriMesh& mesh) {
  require_disk(mesh, "Fiedler field");
  const int n = mesh.num_vertices();
  const SparseMatrix L = cotan_laplacian(mesh);
  const std::vector<double> area = mixed_voronoi_areas(mesh);
  const Eigen::Map<const Eigen::VectorXd> m(area.data(), n);
  const double total = m.sum();
  const double diag = bounding_box(mesh).diagonal();
  // Shift well below the smallest non-zero eigenvalue (about (pi / diameter)^2).
  const double sigma = 1e-3 * (std::numbers::pi / diag) * (std::numbers::pi / diag);
  SparseMatrix S = L;
  for (int v = 0; v < n; ++v) S.coeffRef(v, v) += sigma * m[v];
  SparseSolver solver(S);

  constexpr int kBlock = 4;
  auto deflate = [&](Eigen::MatrixXd& X) {  // M-orthogonal to the constants
    for (int c = 0; c < X.cols(); ++c) X.col(c).array() -= m.dot(X.col(c)) / total;
  };
  Eigen::MatrixXd X(n, kBlock);
  for (int v = 0; v < n; ++v) {
    const Vec3& p = mesh.vertices[v];
    X(v, 0) = p.x();
    X(v, 1) = p.y();
    X(v, 2) = p.z();
    X(v, 3) = p.x() * p.y() + 0.5 * p.z() * p.z();
  }
  deflate(X);
  FiedlerField out;
  Eigen::VectorXd best;
  for (int it = 1; it <= 300; ++it) {
    Eigen::MatrixXd Y = solver.solve_columns(m.asDiagonal() * X);
    deflate(Y);
    // Rayleigh-Ritz in span(Y): M-orthonormalise, then the small eigenproblem.
    const Eigen::MatrixXd G = Y.transpose() * m.asDiagonal() * Y;
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> ge(G);
    Eigen::MatrixXd B = Eigen::MatrixXd::Zero(kBlock, kBlock);
    const double gmax = ge.eigenvalues().maxCoeff();
    for (int c = 0; c < kBlock; ++c) {
      const double g = ge.eigenvalues()[c];
      if (g > 1e-14 * gmax) B.col(c) = ge.eigenvectors().col(c) / std::sqrt(g);
    }
    const Eigen::MatrixXd Q = Y * B;
    const Eigen::MatrixXd H = Q.transpose() * (L * Q);
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> he(H);
    X = Q * he.eigenvectors();
    // Smallest Ritz value with a non-trivial vector.
    int c = 0;
    while (c < kBlock && X.col(c).norm() == 0.0) ++c;
    if (c == kBlock) throw SolverError("Fiedler field: inverse iteration collapsed");
    const Eigen::VectorXd v = X.col(c);
    const double lambda = he.eigenvalues()[c];
    const Eigen::VectorXd r = L * v - lambda * m.asDiagonal() * v;
    const double res = r.norm() / std::max(1e-300, std::abs(lambda) * (m.asDiagonal() * v).norm());
    out.eigenvalue = lambda;
    out.residual = res;
    out.iterations = it;
    best = v;
    if (res < 1e-6) {
      out.converged = true;
      break;
    }
  }
  int big = 0;
  for (int v = 1; v < n; ++v)
    if (std::abs(best[v]) > std::abs(best[big])) big = v;
  if (best[big] < 0) best = -best;
  const double lo = best.minCoeff(), hi = best.maxCoeff();
  if (!(hi > lo)) throw SolverError("Fiedler field: the eigenvector is constant");
  out.value.resize(static_cast<size_t>(n));
  for (int v = 0; v < n; ++v) out.value[static_cast<size_t>(v)] = (best[v] - lo) / (hi - lo);
  out.interior_extrema = count_interior_extrema(mesh, out.value);
  return out;
}

}  // namespace knitforge
