#include "knitforge/geometry/laplacian_eigenvectors.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>
#include <Eigen/Dense>

#include "knitforge/geometry/cotan_laplacian.h"
#include "knitforge/geometry/isocurves.h"
#include "knitforge/geometry/mesh_measures.h"
#include "knitforge/geometry/sparse_solver.h"
#include "knitforge/geometry/surface_checks.h"
#include "knitforge/util/errors.h"

namespace knitforge {

namespace {

// Columns of X made M-orthonormal and M-orthogonal to the constants (mass
// vector m = diag M); columns that vanish are replaced by nothing (dropped).
Eigen::MatrixXd m_orthonormalise(const Eigen::MatrixXd& X, const Eigen::VectorXd& m) {
  const double total = m.sum();
  Eigen::MatrixXd Q(X.rows(), X.cols());
  int q = 0;
  for (int j = 0; j < X.cols(); ++j) {
    Eigen::VectorXd x = X.col(j);
    for (int pass = 0; pass < 2; ++pass) {
      x.array() -= m.dot(x) / total;
      for (int i = 0; i < q; ++i) x -= Q.col(i).dot(m.cwiseProduct(x)) * Q.col(i);
    }
    const double norm = std::sqrt(x.dot(m.cwiseProduct(x)));
    if (!(norm > 1e-12 * std::sqrt(total) * (X.col(j).cwiseAbs().maxCoeff() + 1e-300))) continue;
    Q.col(q++) = x / norm;
  }
  return Q.leftCols(q);
}

}  // namespace

LaplacianEigenvectors laplacian_eigenvectors(const TriMesh& mesh, const EigenvectorOptions& o) {
  return stiffness_eigenvectors(mesh, cotan_laplacian(mesh), o);
}

SparseMatrix directional_stiffness(const TriMesh& mesh, const std::vector<Vec3>& d, double epsilon) {
  const int n = mesh.num_vertices();
  if (d.size() != mesh.faces.size())
    throw InvalidInput(
        fmt::format("directional stiffness: {} directions for {} faces", d.size(), mesh.faces.size()));
  if (!(epsilon >= 0.0))
    throw InvalidInput(fmt::format("directional stiffness: epsilon must be >= 0, got {}", epsilon));
  std::vector<Eigen::Triplet<double>> trip;
  for (size_t f = 0; f < mesh.faces.size(); ++f) {
    const auto& t = mesh.faces[f];
    for (int k = 0; k < 3; ++k)
      if (t[k] < 0 || t[k] >= n)
        throw InvalidInput(fmt::format("directional stiffness: face {} has vertex {} out of range", f, t[k]));
    if (d[f].squaredNorm() == 0.0) continue;
    const Vec3 p[3] = {mesh.vertices[static_cast<size_t>(t[0])], mesh.vertices[static_cast<size_t>(t[1])],
                       mesh.vertices[static_cast<size_t>(t[2])]};
    const Vec3 cr = (p[1] - p[0]).cross(p[2] - p[0]);
    const double twice = cr.norm();
    if (!(twice > 0.0)) continue;
    const Vec3 nrm = cr / twice;
    double g[3];  // <grad phi_k, d>: grad phi_k = n x (p_k+2 - p_k+1) / (2 A)
    for (int k = 0; k < 3; ++k) g[k] = nrm.cross(p[(k + 2) % 3] - p[(k + 1) % 3]).dot(d[f]) / twice;
    const double area = 0.5 * twice;
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) trip.emplace_back(t[a], t[b], area * g[a] * g[b]);
  }
  SparseMatrix B(n, n);
  B.setFromTriplets(trip.begin(), trip.end());
  if (epsilon > 0.0) B += epsilon * cotan_laplacian(mesh);
  return B;
}

std::vector<Vec3> flat_weighted_directions(const TriMesh& mesh, const std::vector<double>& field,
                                           bool isocurve_tangent) {
  const std::vector<Vec3> g = field_face_gradients(mesh, field);
  std::vector<Vec3> d = isocurve_tangent ? wale_directions(mesh, field) : g;
  const std::vector<double> areas = face_areas(mesh);
  double sum = 0.0, area = 0.0;
  for (size_t f = 0; f < g.size(); ++f) {
    sum += areas[f] * g[f].squaredNorm();
    area += areas[f];
  }
  const double rms = area > 0.0 ? std::sqrt(sum / area) : 0.0;
  // A field whose gradients are round-off of its values is constant.
  double peak = 0.0;
  for (double x : field) peak = std::max(peak, std::abs(x));
  const BoundingBox box = bounding_box(mesh);
  const bool constant = !(rms * (box.max - box.min).norm() > 1e-12 * peak);
  for (size_t f = 0; f < d.size(); ++f) {
    const double len = g[f].norm();
    if (constant || !(len > 0.0)) {
      d[f] = Vec3::Zero();
      continue;
    }
    if (!isocurve_tangent) d[f] /= len;
    d[f] *= std::min(1.0, len / rms);
  }
  return d;
}

LaplacianEigenvectors stiffness_eigenvectors(const TriMesh& mesh, const SparseMatrix& L,
                                             const EigenvectorOptions& o) {
  if (o.count < 1)
    throw InvalidInput(fmt::format("Laplacian eigenvectors: count must be >= 1, got {}", o.count));
  const int n = mesh.num_vertices();
  const int p = o.count + 4;
  if (mesh.faces.empty() || n < p + 1)
    throw InvalidInput(
        fmt::format("Laplacian eigenvectors: the mesh has {} vertices and {} faces; {} eigenvectors "
                    "need at least {} vertices",
                    n, mesh.faces.size(), o.count, p + 1));
  const SurfaceReport rep = validate_surface(mesh);
  if (rep.num_components != 1)
    throw InvalidInput(
        fmt::format("Laplacian eigenvectors: the mesh has {} connected pieces; the Fiedler vector is "
                    "defined on one piece (split it and take each piece on its own)",
                    rep.num_components));
  if (L.rows() != n || L.cols() != n)
    throw InvalidInput(
        fmt::format("Laplacian eigenvectors: a {} x {} stiffness for {} vertices", L.rows(), L.cols(), n));
  const std::vector<double> area = mixed_voronoi_areas(mesh);
  Eigen::VectorXd m(n);
  for (int v = 0; v < n; ++v) m[v] = area[static_cast<size_t>(v)];
  // Vertices no face uses have no mass: give them a tiny one so that M stays
  // definite (their values are then free and end up 0).
  const double mean_mass = m.sum() / n;
  for (int v = 0; v < n; ++v)
    if (!(m[v] > 0.0)) m[v] = 1e-12 * mean_mass;
  const double sigma = 1e-6 * L.diagonal().sum() / m.sum();
  SparseMatrix A = L;
  for (int v = 0; v < n; ++v) A.coeffRef(v, v) += sigma * m[v];
  const SparseSolver solver(A);

  // Start: coordinate monomials of degree 1 and 2, about the centroid, in the
  // bounding box's scale.
  Vec3 c = Vec3::Zero();
  for (const Vec3& x : mesh.vertices) c += x;
  c /= n;
  Eigen::MatrixXd X(n, std::max(p, 9));
  for (int v = 0; v < n; ++v) {
    const Vec3 x = mesh.vertices[static_cast<size_t>(v)] - c;
    const double r[9] = {x.x(),         x.y(),         x.z(),         x.x() * x.x(), x.y() * x.y(),
                         x.z() * x.z(), x.x() * x.y(), x.y() * x.z(), x.z() * x.x()};
    for (int j = 0; j < X.cols(); ++j)
      X(v, j) = j < 9 ? r[j] : std::pow(x.x(), 3) * (j - 8) + std::pow(x.y(), 3);
  }
  X = m_orthonormalise(X, m).leftCols(std::min<Eigen::Index>(p, X.cols()));

  LaplacianEigenvectors out;
  Eigen::VectorXd lambda;
  for (int it = 1; it <= o.max_iterations; ++it) {
    Eigen::MatrixXd Y = solver.solve_columns(m.asDiagonal() * X);
    Y = m_orthonormalise(Y, m);
    const Eigen::MatrixXd LY = L * Y;
    Eigen::MatrixXd K = Y.transpose() * LY;
    K = 0.5 * (K + K.transpose()).eval();
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(K);  // Y is M-orthonormal: B = I
    X = Y * es.eigenvectors();
    lambda = es.eigenvalues();
    out.iterations = it;
    bool done = X.cols() >= o.count;
    const Eigen::MatrixXd R = L * X;
    for (int j = 0; j < o.count && done && j < X.cols(); ++j) {
      const Eigen::VectorXd Mx = m.cwiseProduct(X.col(j));
      const double res = (R.col(j) - lambda[j] * Mx).norm();
      if (!(res <= o.tolerance * std::abs(lambda[j]) * Mx.norm())) done = false;
    }
    if (done) {
      out.converged = true;
      break;
    }
  }
  const int k = std::min<int>(o.count, static_cast<int>(X.cols()));
  for (int j = 0; j < k; ++j) {
    Eigen::VectorXd x = X.col(j);
    Eigen::Index at = 0;
    x.cwiseAbs().maxCoeff(&at);
    if (x[at] < 0.0) x = -x;
    out.values.push_back(lambda[j]);
    out.vectors.emplace_back(x.data(), x.data() + n);
  }
  return out;
}

std::vector<double> fiedler_vector(const TriMesh& mesh) {
  return laplacian_eigenvectors(mesh, {}).vectors.front();
}

double gradient_alignment(const TriMesh& mesh, const std::vector<double>& a, const std::vector<double>& b) {
  const size_t n = static_cast<size_t>(mesh.num_vertices());
  if (a.size() != n || b.size() != n)
    throw InvalidInput(fmt::format("gradient alignment: fields of {} and {} values on a mesh of {} vertices",
                                   a.size(), b.size(), n));
  const std::vector<Vec3> ga = field_face_gradients(mesh, a), gb = field_face_gradients(mesh, b);
  const std::vector<double> fa = face_areas(mesh);
  double sum = 0.0, w = 0.0;
  for (size_t f = 0; f < fa.size(); ++f) {
    const double na = ga[f].norm(), nb = gb[f].norm();
    if (!(na > 0.0) || !(nb > 0.0)) continue;
    sum += fa[f] * std::abs(ga[f].dot(gb[f])) / (na * nb);
    w += fa[f];
  }
  return w > 0.0 ? sum / w : 1.0;
}

}  // namespace knitforge
