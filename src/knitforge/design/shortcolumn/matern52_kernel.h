#pragma once
/// \file matern52_kernel.h
/// The Matern-5/2 kernel with automatic relevance determination (one
/// lengthscale per input dimension), the covariance of the Gaussian-process
/// surrogate of the short-column optimisation (TuRBO [47], seed §3.3.5):
///
///     k(x, y) = s (1 + sqrt(5) r + 5/3 r^2) exp(-sqrt(5) r),
///     r^2 = sum_i ((x_i - y_i) / l_i)^2,
///
/// s the output scale, l_i the lengthscales. Derivatives are taken with
/// respect to the LOG hyperparameters (the optimiser works in log space):
///
///     dk / d log l_i = s 5/3 (1 + sqrt(5) r) exp(-sqrt(5) r) ((x_i - y_i) / l_i)^2,
///     dk / d log s   = k.
///
/// Inputs are rows of a matrix (n points x d dimensions).

#include <vector>

#include <Eigen/Core>

namespace knitforge {

/// Hyperparameters of the Matern-5/2 ARD kernel.
struct Matern52Params {
  Eigen::VectorXd lengthscale;  ///< l_i > 0, one per dimension
  double outputscale = 1.0;     ///< s > 0
};

/// k(x, y). \pre x, y and p.lengthscale have the same size.
double matern52(const Eigen::VectorXd& x, const Eigen::VectorXd& y, const Matern52Params& p);

/// The matrix K_ab = k(X.row(a), Y.row(b)) (X: n x d, Y: m x d).
/// \throw InvalidInput when the dimensions disagree or a hyperparameter is
///        not positive and finite.
Eigen::MatrixXd matern52_matrix(const Eigen::MatrixXd& X, const Eigen::MatrixXd& Y, const Matern52Params& p);

/// dK(X, X) / d theta_j for theta = (log l_1, ..., log l_d, log s): d + 1
/// matrices of n x n.
/// \throw InvalidInput as matern52_matrix().
std::vector<Eigen::MatrixXd> matern52_log_gradients(const Eigen::MatrixXd& X, const Matern52Params& p);

}  // namespace knitforge
