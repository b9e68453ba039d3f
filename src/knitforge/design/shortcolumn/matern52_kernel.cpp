#include "knitforge/design/shortcolumn/matern52_kernel.h"

#include <cmath>

#include <fmt/core.h>

#include "knitforge/util/errors.h"

namespace knitforge {

namespace {

constexpr double kSqrt5 = 2.2360679774997896964;

void check(const Eigen::MatrixXd& X, const Eigen::MatrixXd& Y, const Matern52Params& p) {
  if (X.cols() != p.lengthscale.size() || Y.cols() != p.lengthscale.size())
    throw InvalidInput(fmt::format("Matern-5/2 kernel: inputs of dimension {} and {} for {} lengthscales",
                                   X.cols(), Y.cols(), p.lengthscale.size()));
  for (int i = 0; i < p.lengthscale.size(); ++i)
    if (!(p.lengthscale[i] > 0.0) || !std::isfinite(p.lengthscale[i]))
      throw InvalidInput(fmt::format("Matern-5/2 kernel: lengthscale {} = {} must be positive", i, p.lengthscale[i]));
  if (!(p.outputscale > 0.0) || !std::isfinite(p.outputscale))
    throw InvalidInput(fmt::format("Matern-5/2 kernel: output scale {} must be positive", p.outputscale));
}

double value_of_r(double r, double s) { return s * (1.0 + kSqrt5 * r + 5.0 / 3.0 * r * r) * std::exp(-kSqrt5 * r); }

}  // namespace

double matern52(const Eigen::VectorXd& x, const Eigen::VectorXd& y, const Matern52Params& p) {
  const double r = ((x - y).array() / p.lengthscale.array()).matrix().norm();
  return value_of_r(r, p.outputscale);
}

Eigen::MatrixXd matern52_matrix(const Eigen::MatrixXd& X, const Eigen::MatrixXd& Y, const Matern52Params& p) {
  check(X, Y, p);
  const Eigen::ArrayXd inv = p.lengthscale.array().inverse();
  Eigen::MatrixXd K(X.rows(), Y.rows());
  for (int a = 0; a < X.rows(); ++a)
    for (int b = 0; b < Y.rows(); ++b)
      K(a, b) = value_of_r(((X.row(a) - Y.row(b)).array().transpose() * inv).matrix().norm(), p.outputscale);
  return K;
}

std::vector<Eigen::MatrixXd> matern52_log_gradients(const Eigen::MatrixXd& X, const Matern52Params& p) {
  check(X, X, p);
  const int n = static_cast<int>(X.rows()), d = static_cast<int>(X.cols());
  std::vector<Eigen::MatrixXd> G(static_cast<size_t>(d + 1), Eigen::MatrixXd::Zero(n, n));
  const Eigen::ArrayXd inv = p.lengthscale.array().inverse();
  for (int a = 0; a < n; ++a) {
    for (int b = a; b < n; ++b) {
      const Eigen::ArrayXd z = (X.row(a) - X.row(b)).array().transpose() * inv;
      const double r = std::sqrt(z.square().sum());
      const double e = std::exp(-kSqrt5 * r);
      const double common = p.outputscale * 5.0 / 3.0 * (1.0 + kSqrt5 * r) * e;
      for (int i = 0; i < d; ++i) G[static_cast<size_t>(i)](a, b) = G[static_cast<size_t>(i)](b, a) = common * z[i] * z[i];
      G[static_cast<size_t>(d)](a, b) = G[static_cast<size_t>(d)](b, a) = value_of_r(r, p.outputscale);
    }
  }
  return G;
}

}  // namespace knitforge
