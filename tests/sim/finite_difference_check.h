#pragma once
// The one finite-difference check of the simulator's energies (every energy
// term's test uses it): central differences of the value against the
// gradient, and of the gradient against the Hessian.

#include <algorithm>
#include <cmath>
#include <functional>

#include <Eigen/Core>
#include <gtest/gtest.h>

namespace knitforge::test {

struct Derivs {
  double value = 0.0;
  Eigen::VectorXd gradient;
  Eigen::MatrixXd hessian;  // empty: not checked
};

// f(x) -> value, gradient and (optionally) Hessian at x. Checks the gradient
// against central differences of the value, and the Hessian against central
// differences of the gradient, entrywise within
// tol * (|reference| + scale), scale = the largest magnitude of the
// derivative being checked (so tiny entries are not held to a relative
// bound they cannot meet in floating point).
inline void expect_derivatives_match(const std::function<Derivs(const Eigen::VectorXd&)>& f,
                                     const Eigen::VectorXd& x, double h, double tol,
                                     bool check_hessian = true) {
  const Derivs d = f(x);
  const Eigen::Index n = x.size();
  Eigen::VectorXd fd_g(n);
  Eigen::MatrixXd fd_h(n, n);
  for (Eigen::Index i = 0; i < n; ++i) {
    Eigen::VectorXd xp = x, xm = x;
    xp[i] += h;
    xm[i] -= h;
    const Derivs dp = f(xp), dm = f(xm);
    fd_g[i] = (dp.value - dm.value) / (2 * h);
    if (check_hessian) fd_h.col(i) = (dp.gradient - dm.gradient) / (2 * h);
  }
  const double gscale = std::max(d.gradient.cwiseAbs().maxCoeff(), fd_g.cwiseAbs().maxCoeff());
  for (Eigen::Index i = 0; i < n; ++i) {
    EXPECT_NEAR(d.gradient[i], fd_g[i], tol * (std::abs(fd_g[i]) + gscale)) << "gradient entry " << i;
  }
  if (!check_hessian || d.hessian.size() == 0) return;
  const double hscale = std::max(d.hessian.cwiseAbs().maxCoeff(), fd_h.cwiseAbs().maxCoeff());
  for (Eigen::Index i = 0; i < n; ++i) {
    for (Eigen::Index j = 0; j < n; ++j) {
      EXPECT_NEAR(d.hessian(i, j), fd_h(i, j), tol * (std::abs(fd_h(i, j)) + hscale))
          << "Hessian entry (" << i << ", " << j << ")";
    }
  }
}

}  // namespace knitforge::test
