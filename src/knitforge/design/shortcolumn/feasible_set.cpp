#include "knitforge/design/shortcolumn/feasible_set.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Dense>
#include <fmt/core.h>

#include "knitforge/util/errors.h"

namespace knitforge {

bool LinearConstraints::contains(const Eigen::VectorXd& x, double tolerance) const {
  return ((A * x - c).array() >= -tolerance).all();
}

LinearConstraints boundary_constraints(double m) {
  LinearConstraints k;
  k.A = Eigen::MatrixXd::Zero(6, 4);
  k.c = Eigen::VectorXd::Zero(6);
  k.A(0, 0) = 1;                                    // b0 >= 0
  k.A(1, 1) = 1, k.A(1, 0) = -1;                    // b1 - b0 >= 0
  k.A(2, 2) = 1, k.A(2, 1) = -1, k.c[2] = m;        // b2 - b1 >= m
  k.A(3, 3) = 1, k.A(3, 2) = -1;                    // b3 - b2 >= 0
  k.A(4, 0) = 1, k.A(4, 3) = -1, k.c[4] = m - 1.0;  // 1 + b0 - b3 >= m
  k.A(5, 0) = -1, k.c[5] = m - 1.0;                 // 1 - b0 >= m
  return k;
}

LinearConstraints symmetric_constraints(double gap, double m) {
  if (!(gap > 2 * m && gap < 1 - 2 * m))
    throw InvalidInput(fmt::format("symmetric boundary conditions: the mirror points are {} apart along the "
                                   "boundary; they must be strictly between 0 and 1",
                                   gap));
  LinearConstraints k;
  k.A = Eigen::MatrixXd::Zero(4, 2);
  k.c = Eigen::VectorXd::Zero(4);
  k.A(0, 0) = 1;
  k.A(1, 1) = 1;
  k.A(2, 0) = -1, k.A(2, 1) = -1, k.c[2] = m - gap;
  k.A(3, 0) = -1, k.A(3, 1) = -1, k.c[3] = m - (1 - gap);
  return k;
}

Eigen::VectorXd project_onto_constraints(const LinearConstraints& k, const Eigen::VectorXd& y) {
  const int m = static_cast<int>(k.A.rows()), d = k.dim();
  if (m > 8 || d > 8 || d < 1 || y.size() != d || k.c.size() != m)
    throw InvalidInput(fmt::format("projection: {} constraints in {} dimensions for a point of {}", m, d, y.size()));
  if (k.contains(y)) return y;
  Eigen::VectorXd best;
  double best_d = std::numeric_limits<double>::infinity();
  for (unsigned mask = 1; mask < (1u << m); ++mask) {
    std::vector<int> rows;
    for (int r = 0; r < m; ++r)
      if (mask & (1u << r)) rows.push_back(r);
    if (static_cast<int>(rows.size()) > d) continue;
    Eigen::MatrixXd As(rows.size(), d);
    Eigen::VectorXd cs(rows.size());
    for (size_t i = 0; i < rows.size(); ++i) {
      As.row(static_cast<Eigen::Index>(i)) = k.A.row(rows[i]);
      cs[static_cast<Eigen::Index>(i)] = k.c[rows[i]];
    }
    const Eigen::MatrixXd G = As * As.transpose();
    const Eigen::FullPivLU<Eigen::MatrixXd> lu(G);
    if (lu.rank() < static_cast<int>(rows.size())) continue;  // dependent rows: a smaller subset covers it
    const Eigen::VectorXd x = y + As.transpose() * lu.solve(cs - As * y);
    if (!k.contains(x, 1e-12)) continue;
    const double dist = (x - y).squaredNorm();
    if (dist < best_d) best_d = dist, best = x;
  }
  if (best.size() == 0) throw InvalidInput("projection: the feasible set is empty");
  return best;
}

BoundaryVector boundary_from_unit(const Eigen::Vector4d& u, double m) {
  std::array<double, 3> s{u[1], u[2], u[3]};
  for (double& x : s) x = std::clamp(x, 0.0, 1.0);
  std::sort(s.begin(), s.end());
  const double w = 1.0 - 2.0 * m;
  BoundaryVector b;
  b[0] = std::clamp(u[0], 0.0, 1.0) * (1.0 - m);
  b[1] = b[0] + w * s[0];
  b[2] = b[1] + m + w * (s[1] - s[0]);
  b[3] = b[2] + w * (s[2] - s[1]);
  return b;
}

BoundaryVector snap_feasible(const BoundaryVector& b, double m) {
  const LinearConstraints k = boundary_constraints(m);
  if (!k.contains(Eigen::Vector4d(b[0], b[1], b[2], b[3]), 1e-9))
    throw InvalidInput(fmt::format("snap_feasible: b = ({}) is not within 1e-9 of the feasible set (eq. 3.8)",
                                   format_boundary_vector(b)));
  BoundaryVector r = b;
  r[0] = std::clamp(r[0], 0.0, 1.0 - m);
  r[1] = std::max(r[1], r[0]);
  r[2] = std::max(r[2], r[1] + m);
  r[3] = std::max(r[3], r[2]);
  if (r[3] > 1.0 + r[0] - m && 1.0 + r[0] - m >= r[2]) r[3] = 1.0 + r[0] - m;
  return r;
}

BoundaryVector canonical_boundary(const BoundaryVector& b) {
  const double shift = std::floor(b[0]);
  BoundaryVector r;
  for (int i = 0; i < 4; ++i) r[static_cast<size_t>(i)] = b[static_cast<size_t>(i)] - shift;
  return r;
}

BoundaryVector symmetric_boundary(double p, double gap, double a, double e) {
  const double q = p + gap;
  return canonical_boundary({p - a, p + a, q - e, q + e});
}

double boundary_distance(const BoundaryVector& a, const BoundaryVector& b) {
  double s = 0.0;
  for (int i = 0; i < 4; ++i) {
    double d = a[static_cast<size_t>(i)] - b[static_cast<size_t>(i)];
    d -= std::round(d);
    s += d * d;
  }
  return std::sqrt(s);
}

}  // namespace knitforge
