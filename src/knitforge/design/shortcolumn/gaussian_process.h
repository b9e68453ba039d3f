#pragma once
/// \file gaussian_process.h
/// Gaussian-process regression with a Matern-5/2 ARD kernel and Gaussian
/// noise, the surrogate model of TuRBO [47] (seed §3.3.5, L1465-1467).
///
/// Inputs live in the unit cube (the caller scales them); outputs are
/// standardised (mean 0, standard deviation 1) before fitting, and
/// predictions are returned in the original units. The model holds the
/// Cholesky factor L of K + noise I and alpha = (K + noise I)^-1 y, never
/// the inverse itself; predictions solve triangular systems with L.
///
/// Hyperparameters theta = (log l_1..l_d, log s, log noise) maximise the
/// log marginal likelihood
///
///     log p(y | theta) = -1/2 y^T alpha - sum_i log L_ii - n/2 log(2 pi)
///
/// with gradient 1/2 tr((alpha alpha^T - (K + noise I)^-1) dK/dtheta_j), by
/// Adam in log space projected onto the box bounds (as the reference TuRBO
/// fits GPyTorch models: Adam, learning rate 0.1), from the previous
/// hyperparameters and from the defaults; the better optimum is kept.
/// Bounds are TuRBO's: lengthscales [0.005, 2], output scale [0.05, 20],
/// noise variance [5e-4, 0.2] (in standardised units). Deterministic.

#include <Eigen/Core>

#include "knitforge/design/shortcolumn/matern52_kernel.h"

namespace knitforge {

/// Box bounds of the hyperparameters (not logs).
struct GpBounds {
  double lengthscale_min = 0.005, lengthscale_max = 2.0;
  double outputscale_min = 0.05, outputscale_max = 20.0;
  double noise_min = 5e-4, noise_max = 0.2;
};

/// Options of fit_gaussian_process().
struct GpFitOptions {
  GpBounds bounds;
  int iterations = 100;        ///< Adam steps per start
  double learning_rate = 0.1;  ///< Adam step size in log space
};

/// Hyperparameters in their natural units (standardised outputs).
struct GpHyperparameters {
  Matern52Params kernel;
  double noise = 0.005;  ///< noise variance
};

/// A fitted Gaussian process.
struct GaussianProcess {
  Eigen::MatrixXd X;      ///< n x d training inputs
  Eigen::VectorXd y;      ///< standardised outputs
  double y_mean = 0.0;    ///< of the original outputs
  double y_scale = 1.0;   ///< standard deviation of the original outputs (1 when constant)
  GpHyperparameters hyper;
  Eigen::MatrixXd chol;   ///< lower Cholesky factor of K + noise I
  Eigen::VectorXd alpha;  ///< (K + noise I)^-1 y
  double log_likelihood = 0.0;  ///< log marginal likelihood at `hyper` (standardised outputs)
  int dim() const { return static_cast<int>(X.cols()); }
};

/// Log marginal likelihood of standardised outputs y at `h`, and its
/// gradient with respect to (log l, log s, log noise) when `gradient` is set.
/// \throw SolverError when K + noise I is not positive definite.
double gp_log_likelihood(const Eigen::MatrixXd& X, const Eigen::VectorXd& y, const GpHyperparameters& h,
                         Eigen::VectorXd* gradient = nullptr);

/// Fits the hyperparameters and the model to (X, y) (y in original units).
/// `start` (optional) is where the first Adam run starts (e.g. the previous
/// fit); the second always starts from lengthscale 0.5, output scale 1,
/// noise 0.005, clamped to the bounds.
/// \throw InvalidInput when X is empty, X.rows() != y.size(), or an entry is
///        not finite; SolverError from gp_log_likelihood().
GaussianProcess fit_gaussian_process(const Eigen::MatrixXd& X, const Eigen::VectorXd& y,
                                     const GpFitOptions& options = {}, const GpHyperparameters* start = nullptr);

/// Posterior mean and variance (original units) at the rows of Xs, without
/// observation noise.
struct GpPrediction {
  Eigen::VectorXd mean;
  Eigen::VectorXd variance;
};
/// \throw InvalidInput when Xs has the wrong number of columns.
GpPrediction gp_predict(const GaussianProcess& gp, const Eigen::MatrixXd& Xs);

/// One joint sample of the posterior (original units) at the rows of Xs,
/// from standard normal draws z (size Xs.rows()): mean + chol(Sigma) z, with
/// a jitter of 1e-8 (relative) added until Sigma factors.
/// \throw InvalidInput when z has the wrong size.
Eigen::VectorXd gp_posterior_sample(const GaussianProcess& gp, const Eigen::MatrixXd& Xs, const Eigen::VectorXd& z);

}  // namespace knitforge
