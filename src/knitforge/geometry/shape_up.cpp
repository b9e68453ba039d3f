#include "knitforge/geometry/shape_up.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <Eigen/SVD>
#include <fmt/core.h>

#include "knitforge/util/errors.h"

namespace knitforge {

void ShapeUpPolygons::add(const std::vector<int>& corner_vertices, const std::vector<Vec3>& corner_targets,
                          double weight) {
  if (corner_vertices.size() != corner_targets.size() || corner_vertices.size() < 2) {
    throw InvalidInput(fmt::format("Shape-Up polygon {}: {} vertices but {} targets (need the same number, >= 2)",
                                   num_polygons(), corner_vertices.size(), corner_targets.size()));
  }
  vertices.insert(vertices.end(), corner_vertices.begin(), corner_vertices.end());
  targets.insert(targets.end(), corner_targets.begin(), corner_targets.end());
  weights.push_back(weight);
  start.push_back(static_cast<int>(vertices.size()));
}

namespace {

int find_root(std::vector<int>& parent, int a) {
  while (parent[a] != a) {
    parent[a] = parent[parent[a]];
    a = parent[a];
  }
  return a;
}

// Columns r1, r2 (orthonormal) maximising tr([r1 r2]^T M) for a 3x2 M: the
// polar factor M (M^T M)^{-1/2}, with a fallback for rank-deficient M.
void polar_3x2(const Eigen::Matrix<double, 3, 2>& M, Vec3* r1, Vec3* r2) {
  const double b00 = M.col(0).squaredNorm(), b11 = M.col(1).squaredNorm(), b01 = M.col(0).dot(M.col(1));
  const double tr = b00 + b11;
  const double det = b00 * b11 - b01 * b01;
  if (!(tr > 1e-300)) {
    *r1 = Vec3::UnitX();
    *r2 = Vec3::UnitY();
    return;
  }
  if (det > 1e-14 * tr * tr) {
    const double s = std::sqrt(det);
    const double t = std::sqrt(tr + 2 * s);
    // sqrt(B) = (B + s I) / t; its inverse:
    const double a = (b00 + s) / t, d = (b11 + s) / t, c = b01 / t;
    const double id = 1.0 / (a * d - c * c);
    const double i00 = d * id, i11 = a * id, i01 = -c * id;
    *r1 = M.col(0) * i00 + M.col(1) * i01;
    *r2 = M.col(0) * i01 + M.col(1) * i11;
    return;
  }
  // Rank one (collinear current corners): map the dominant target direction
  // onto the dominant current direction, the other one onto any perpendicular.
  Eigen::Matrix2d B;
  B << b00, b01, b01, b11;
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> es(B);
  const Eigen::Vector2d v = es.eigenvectors().col(1);
  Vec3 u = M * v;
  u.normalize();
  Vec3 axis = std::abs(u.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY();
  Vec3 w = u.cross(axis).normalized();
  const Eigen::Vector2d vp(-v.y(), v.x());
  *r1 = u * v.x() + w * vp.x();
  *r2 = u * v.y() + w * vp.y();
}

}  // namespace

ShapeUpSolver::ShapeUpSolver(int num_vertices, ShapeUpPolygons polygons, std::vector<int> fixed)
    : num_vertices_(num_vertices), poly_(std::move(polygons)) {
  const int P = poly_.num_polygons();
  if (num_vertices < 0) throw InvalidInput("Shape-Up: negative number of vertices");
  if (P < 0 || poly_.start.empty() || poly_.start.front() != 0 ||
      poly_.start.back() != static_cast<int>(poly_.vertices.size()) ||
      poly_.vertices.size() != poly_.targets.size() || static_cast<int>(poly_.weights.size()) != P) {
    throw InvalidInput(fmt::format(
        "Shape-Up: inconsistent polygon arrays ({} starts, {} corner vertices, {} targets, {} weights)",
        poly_.start.size(), poly_.vertices.size(), poly_.targets.size(), poly_.weights.size()));
  }
  planar_.assign(P, 0);
  centred_.resize(poly_.targets.size());
  for (int f = 0; f < P; ++f) {
    const int b = poly_.start[f], e = poly_.start[f + 1];
    if (e - b < 2) throw InvalidInput(fmt::format("Shape-Up: polygon {} has {} corners (need >= 2)", f, e - b));
    if (!(std::isfinite(poly_.weights[f]) && poly_.weights[f] > 0)) {
      throw InvalidInput(fmt::format("Shape-Up: polygon {} has weight {} (need a finite value > 0)", f,
                                     poly_.weights[f]));
    }
    Vec3 mean = Vec3::Zero();
    double extent = 0, maxz = 0;
    for (int k = b; k < e; ++k) {
      const int v = poly_.vertices[k];
      if (v < 0 || v >= num_vertices) {
        throw InvalidInput(fmt::format("Shape-Up: polygon {} uses vertex {} (valid: 0..{})", f, v, num_vertices - 1));
      }
      for (int l = b; l < k; ++l) {
        if (poly_.vertices[l] == v) throw InvalidInput(fmt::format("Shape-Up: polygon {} uses vertex {} twice", f, v));
      }
      if (!poly_.targets[k].allFinite()) throw InvalidInput(fmt::format("Shape-Up: polygon {} has a non-finite target", f));
      mean += poly_.targets[k];
      extent = std::max(extent, poly_.targets[k].head<2>().cwiseAbs().maxCoeff());
      maxz = std::max(maxz, std::abs(poly_.targets[k].z()));
    }
    mean /= (e - b);
    for (int k = b; k < e; ++k) centred_[k] = poly_.targets[k] - mean;
    planar_[f] = maxz <= 1e-12 * extent ? 1 : 0;
    if (planar_[f]) {
      for (int k = b; k < e; ++k) centred_[k].z() = 0;
    }
  }

  std::vector<int> parent(num_vertices);
  std::iota(parent.begin(), parent.end(), 0);
  for (int f = 0; f < P; ++f) {
    const int r0 = find_root(parent, poly_.vertices[poly_.start[f]]);
    for (int k = poly_.start[f] + 1; k < poly_.start[f + 1]; ++k) {
      const int r = find_root(parent, poly_.vertices[k]);
      if (r != r0) parent[std::max(r, r0)] = std::min(r, r0);
    }
  }
  if (fixed.empty()) {
    // With union by smaller index, each root is its component's smallest vertex.
    for (int v = 0; v < num_vertices; ++v) {
      if (find_root(parent, v) == v) fixed.push_back(v);
    }
  }
  free_index_.assign(num_vertices, 0);
  std::vector<char> pinned(num_vertices, 0);
  for (int v : fixed) {
    if (v < 0 || v >= num_vertices) throw InvalidInput(fmt::format("Shape-Up: fixed vertex {} out of range", v));
    free_index_[v] = -1;
    pinned[find_root(parent, v)] = 1;
  }
  for (int v = 0; v < num_vertices; ++v) {
    if (!pinned[find_root(parent, v)]) {
      throw InvalidInput(fmt::format("Shape-Up: the connected part containing vertex {} has no fixed vertex, so its "
                                     "position is not determined; fix one of its vertices",
                                     v));
    }
  }
  for (int v = 0; v < num_vertices; ++v) {
    if (free_index_[v] < 0) {
      fixed_.push_back(v);
    } else {
      free_index_[v] = num_free_++;
    }
  }
  if (num_free_ == 0) return;

  std::vector<Eigen::Triplet<double>> trip;
  trip.reserve(poly_.vertices.size() * 3);
  for (int f = 0; f < P; ++f) {
    const int b = poly_.start[f], e = poly_.start[f + 1];
    const double w = poly_.weights[f], wn = w / (e - b);
    for (int j = b; j < e; ++j) {
      const int fj = free_index_[poly_.vertices[j]];
      if (fj < 0) continue;
      for (int k = b; k < e; ++k) {
        const int fk = free_index_[poly_.vertices[k]];
        if (fk < 0 || fk > fj) continue;  // lower triangle only
        trip.emplace_back(fj, fk, (j == k ? w : 0.0) - wn);
      }
    }
  }
  SparseMatrix A(num_free_, num_free_);
  A.setFromTriplets(trip.begin(), trip.end());
  solver_.factor(A);
}

double ShapeUpSolver::local_step(const std::vector<Vec3>& x, Eigen::MatrixXd* rhs) const {
  const int P = poly_.num_polygons();
  if (rhs) rhs->setZero(num_free_, 3);
  double energy = 0;
  Vec3 fit[16];
  std::vector<Vec3> big;
  for (int f = 0; f < P; ++f) {
    const int b = poly_.start[f], e = poly_.start[f + 1], n = e - b;
    Vec3* p = fit;
    if (n > 16) {
      big.resize(n);
      p = big.data();
    }
    Vec3 c = Vec3::Zero();
    for (int k = b; k < e; ++k) c += x[poly_.vertices[k]];
    c /= n;
    if (planar_[f]) {
      Eigen::Matrix<double, 3, 2> M = Eigen::Matrix<double, 3, 2>::Zero();
      for (int k = b; k < e; ++k) M += (x[poly_.vertices[k]] - c) * centred_[k].head<2>().transpose();
      Vec3 r1, r2;
      polar_3x2(M, &r1, &r2);
      for (int k = b; k < e; ++k) p[k - b] = r1 * centred_[k].x() + r2 * centred_[k].y();
    } else {
      Mat3 S = Mat3::Zero();
      for (int k = b; k < e; ++k) S += (x[poly_.vertices[k]] - c) * centred_[k].transpose();
      Eigen::JacobiSVD<Mat3> svd(S, Eigen::ComputeFullU | Eigen::ComputeFullV);
      Mat3 D = Mat3::Identity();
      D(2, 2) = (svd.matrixU() * svd.matrixV().transpose()).determinant() < 0 ? -1.0 : 1.0;
      const Mat3 R = svd.matrixU() * D * svd.matrixV().transpose();
      for (int k = b; k < e; ++k) p[k - b] = R * centred_[k];
    }
    const double w = poly_.weights[f];
    double ef = 0;
    Vec3 fixed_sum = Vec3::Zero();
    for (int k = b; k < e; ++k) {
      const int v = poly_.vertices[k];
      ef += (x[v] - c - p[k - b]).squaredNorm();
      if (free_index_[v] < 0) fixed_sum += x[v];
    }
    energy += w * ef;
    if (rhs) {
      fixed_sum *= w / n;
      for (int k = b; k < e; ++k) {
        const int fv = free_index_[poly_.vertices[k]];
        if (fv < 0) continue;
        const Vec3 add = w * p[k - b] + fixed_sum;
        (*rhs)(fv, 0) += add.x();
        (*rhs)(fv, 1) += add.y();
        (*rhs)(fv, 2) += add.z();
      }
    }
  }
  return energy;
}

double ShapeUpSolver::energy(const std::vector<Vec3>& positions) const {
  if (static_cast<int>(positions.size()) != num_vertices_) {
    throw InvalidInput(fmt::format("Shape-Up: {} positions given for {} vertices", positions.size(), num_vertices_));
  }
  return local_step(positions, nullptr);
}

ShapeUpResult ShapeUpSolver::solve(std::vector<Vec3> start, const ShapeUpOptions& options) const {
  if (static_cast<int>(start.size()) != num_vertices_) {
    throw InvalidInput(fmt::format("Shape-Up: {} start positions given for {} vertices", start.size(), num_vertices_));
  }
  for (size_t v = 0; v < start.size(); ++v) {
    if (!start[v].allFinite()) throw InvalidInput(fmt::format("Shape-Up: start position of vertex {} is not finite", v));
  }
  if (options.max_iterations < 0 || !(options.tolerance >= 0) || options.anderson_depth < 0) {
    throw InvalidInput("Shape-Up: max_iterations, tolerance and anderson_depth must be >= 0");
  }
  double scale = 0;
  for (int f = 0; f < poly_.num_polygons(); ++f) {
    for (int k = poly_.start[f]; k < poly_.start[f + 1]; ++k) scale += poly_.weights[f] * centred_[k].squaredNorm();
  }
  const double floor = 1e-24 * scale;

  ShapeUpResult res;
  res.positions = std::move(start);
  const int nf = num_free_;
  Eigen::MatrixXd rhs(nf, 3);
  double E = local_step(res.positions, &rhs);
  res.energy.push_back(E);
  if (nf == 0 || E <= floor) {
    res.converged = true;
    return res;
  }
  auto scatter = [&](const Eigen::MatrixXd& X) {
    for (int v = 0; v < num_vertices_; ++v) {
      const int fv = free_index_[v];
      if (fv >= 0) res.positions[v] = X.row(fv).transpose();
    }
  };
  Eigen::MatrixXd X(nf, 3);
  for (int v = 0; v < num_vertices_; ++v) {
    if (free_index_[v] >= 0) X.row(free_index_[v]) = res.positions[v].transpose();
  }
  // Anderson acceleration of the fixed-point map X -> G(X) = global(local(X))
  // (Peng et al., "Anderson acceleration for geometry optimization and
  // physics simulation", SIGGRAPH 2018), with their energy safeguard: an
  // accelerated step is kept only if it lowers the energy, otherwise the
  // plain Shape-Up step is taken and the history is cleared.
  const int m = options.anderson_depth;
  const Eigen::Index N = 3 * static_cast<Eigen::Index>(nf);
  Eigen::MatrixXd dF(m > 0 ? N : 0, m), dG(m > 0 ? N : 0, m);
  Eigen::MatrixXd Fk(nf, 3), Fprev(nf, 3), Gprev(nf, 3), Xc(nf, 3);
  int hist = 0, head = 0;
  bool have_prev = false;
  for (int it = 0; it < options.max_iterations; ++it) {
    const Eigen::MatrixXd Gk = solver_.solve_columns(rhs);
    ++res.iterations;
    Fk = Gk - X;
    if (m > 0) {
      if (have_prev) {
        dF.col(head) = Eigen::Map<const Eigen::VectorXd>(Fk.data(), N) - Eigen::Map<const Eigen::VectorXd>(Fprev.data(), N);
        dG.col(head) = Eigen::Map<const Eigen::VectorXd>(Gk.data(), N) - Eigen::Map<const Eigen::VectorXd>(Gprev.data(), N);
        head = (head + 1) % m;
        hist = std::min(hist + 1, m);
      }
      Fprev = Fk;
      Gprev = Gk;
      have_prev = true;
    }
    bool accelerated = false;
    if (hist > 0) {
      const auto DF = dF.leftCols(hist);
      Eigen::MatrixXd M = DF.transpose() * DF;
      const Eigen::VectorXd r = DF.transpose() * Eigen::Map<const Eigen::VectorXd>(Fk.data(), N);
      M.diagonal().array() += 1e-10 * std::max(M.trace(), 1e-300);
      const Eigen::VectorXd theta = M.ldlt().solve(r);
      if (theta.allFinite()) {
        Xc = Gk;
        Eigen::Map<Eigen::VectorXd>(Xc.data(), N) -= dG.leftCols(hist) * theta;
        accelerated = true;
      }
    }
    double En = 0;
    if (accelerated) {
      scatter(Xc);
      En = local_step(res.positions, &rhs);
      if (!(En < E)) {
        accelerated = false;
        hist = head = 0;
      }
    }
    if (!accelerated) {
      Xc = Gk;
      scatter(Xc);
      En = local_step(res.positions, &rhs);
    }
    X.swap(Xc);
    res.energy.push_back(En);
    const bool done = En <= floor || (E - En) <= options.tolerance * E;
    E = En;
    if (done) {
      res.converged = true;
      break;
    }
  }
  return res;
}

ShapeUpResult shape_up(const std::vector<Vec3>& start, const ShapeUpPolygons& polygons, const ShapeUpOptions& options) {
  ShapeUpSolver solver(static_cast<int>(start.size()), polygons);
  return solver.solve(start, options);
}

}  // namespace knitforge
