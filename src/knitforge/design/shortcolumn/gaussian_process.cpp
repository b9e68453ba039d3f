#include "knitforge/design/shortcolumn/gaussian_process.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include <Eigen/Cholesky>
#include <fmt/core.h>

#include "knitforge/util/errors.h"

namespace knitforge {

namespace {

Eigen::MatrixXd covariance(const Eigen::MatrixXd& X, const GpHyperparameters& h) {
  Eigen::MatrixXd K = matern52_matrix(X, X, h.kernel);
  K.diagonal().array() += h.noise;
  return K;
}

Eigen::VectorXd to_theta(const GpHyperparameters& h) {
  const int d = static_cast<int>(h.kernel.lengthscale.size());
  Eigen::VectorXd t(d + 2);
  t.head(d) = h.kernel.lengthscale.array().log();
  t[d] = std::log(h.kernel.outputscale);
  t[d + 1] = std::log(h.noise);
  return t;
}

GpHyperparameters from_theta(const Eigen::VectorXd& t) {
  const int d = static_cast<int>(t.size()) - 2;
  GpHyperparameters h;
  h.kernel.lengthscale = t.head(d).array().exp();
  h.kernel.outputscale = std::exp(t[d]);
  h.noise = std::exp(t[d + 1]);
  return h;
}

void clamp_theta(Eigen::VectorXd& t, const GpBounds& b) {
  const int d = static_cast<int>(t.size()) - 2;
  for (int i = 0; i < d; ++i) t[i] = std::clamp(t[i], std::log(b.lengthscale_min), std::log(b.lengthscale_max));
  t[d] = std::clamp(t[d], std::log(b.outputscale_min), std::log(b.outputscale_max));
  t[d + 1] = std::clamp(t[d + 1], std::log(b.noise_min), std::log(b.noise_max));
}

/// Adam ascent on the log likelihood from theta0; returns the best theta seen.
Eigen::VectorXd adam(const Eigen::MatrixXd& X, const Eigen::VectorXd& y, Eigen::VectorXd theta,
                     const GpFitOptions& o, double& best_ll) {
  clamp_theta(theta, o.bounds);
  Eigen::VectorXd m = Eigen::VectorXd::Zero(theta.size()), v = m, g(theta.size());
  Eigen::VectorXd best = theta;
  best_ll = -std::numeric_limits<double>::infinity();
  constexpr double b1 = 0.9, b2 = 0.999, eps = 1e-8;
  for (int it = 1; it <= o.iterations + 1; ++it) {
    double ll;
    try {
      ll = gp_log_likelihood(X, y, from_theta(theta), &g);
    } catch (const SolverError&) {
      break;  // keep the best so far
    }
    if (ll > best_ll) {
      best_ll = ll;
      best = theta;
    }
    if (it > o.iterations) break;
    m = b1 * m + (1 - b1) * g;
    v = b2 * v + (1 - b2) * g.cwiseProduct(g);
    const double c1 = 1 - std::pow(b1, it), c2 = 1 - std::pow(b2, it);
    theta += o.learning_rate * ((m / c1).array() / ((v / c2).array().sqrt() + eps)).matrix();
    clamp_theta(theta, o.bounds);
  }
  return best;
}

}  // namespace

double gp_log_likelihood(const Eigen::MatrixXd& X, const Eigen::VectorXd& y, const GpHyperparameters& h,
                         Eigen::VectorXd* gradient) {
  const int n = static_cast<int>(X.rows()), d = static_cast<int>(X.cols());
  const Eigen::LLT<Eigen::MatrixXd> llt(covariance(X, h));
  if (llt.info() != Eigen::Success)
    throw SolverError("Gaussian process: the covariance matrix is not positive definite");
  const Eigen::VectorXd alpha = llt.solve(y);
  const Eigen::MatrixXd& L = llt.matrixLLT();
  double logdet = 0.0;
  for (int i = 0; i < n; ++i) logdet += std::log(L(i, i));
  const double ll = -0.5 * y.dot(alpha) - logdet - 0.5 * n * std::log(2.0 * std::numbers::pi);
  if (gradient) {
    const Eigen::MatrixXd W = alpha * alpha.transpose() - llt.solve(Eigen::MatrixXd::Identity(n, n));
    const std::vector<Eigen::MatrixXd> dK = matern52_log_gradients(X, h.kernel);
    gradient->resize(d + 2);
    for (int j = 0; j <= d; ++j) (*gradient)[j] = 0.5 * W.cwiseProduct(dK[static_cast<size_t>(j)]).sum();
    (*gradient)[d + 1] = 0.5 * W.trace() * h.noise;  // dK/dlog noise = noise I
  }
  return ll;
}

GaussianProcess fit_gaussian_process(const Eigen::MatrixXd& X, const Eigen::VectorXd& y, const GpFitOptions& o,
                                     const GpHyperparameters* start) {
  if (X.rows() == 0 || X.cols() == 0) throw InvalidInput("Gaussian process: no training data");
  if (X.rows() != y.size())
    throw InvalidInput(fmt::format("Gaussian process: {} inputs but {} outputs", X.rows(), y.size()));
  if (!X.allFinite() || !y.allFinite()) throw InvalidInput("Gaussian process: training data must be finite");
  GaussianProcess gp;
  gp.X = X;
  gp.y_mean = y.mean();
  const double var = (y.array() - gp.y_mean).square().sum() / std::max<Eigen::Index>(1, y.size());
  gp.y_scale = var > 0.0 ? std::sqrt(var) : 1.0;
  gp.y = (y.array() - gp.y_mean) / gp.y_scale;

  const int d = static_cast<int>(X.cols());
  GpHyperparameters def;
  def.kernel.lengthscale = Eigen::VectorXd::Constant(d, 0.5);
  def.kernel.outputscale = 1.0;
  def.noise = 0.005;
  double ll_a = -std::numeric_limits<double>::infinity(), ll_b = ll_a;
  Eigen::VectorXd best = adam(gp.X, gp.y, to_theta(def), o, ll_a);
  if (start && start->kernel.lengthscale.size() == d) {
    const Eigen::VectorXd other = adam(gp.X, gp.y, to_theta(*start), o, ll_b);
    if (ll_b > ll_a) best = other;
  }
  if (!std::isfinite(std::max(ll_a, ll_b)))
    throw SolverError("Gaussian process: no hyperparameters within the bounds give a positive definite covariance");
  gp.hyper = from_theta(best);
  const Eigen::LLT<Eigen::MatrixXd> llt(covariance(gp.X, gp.hyper));
  if (llt.info() != Eigen::Success) throw SolverError("Gaussian process: the covariance matrix is not positive definite");
  gp.chol = llt.matrixL();
  gp.alpha = llt.solve(gp.y);
  gp.log_likelihood = gp_log_likelihood(gp.X, gp.y, gp.hyper);
  return gp;
}

GpPrediction gp_predict(const GaussianProcess& gp, const Eigen::MatrixXd& Xs) {
  if (Xs.cols() != gp.dim())
    throw InvalidInput(fmt::format("Gaussian process: prediction points of dimension {}, model {}", Xs.cols(), gp.dim()));
  const Eigen::MatrixXd Ks = matern52_matrix(gp.X, Xs, gp.hyper.kernel);  // n x m
  GpPrediction p;
  p.mean = (Ks.transpose() * gp.alpha).array() * gp.y_scale + gp.y_mean;
  const Eigen::MatrixXd V = gp.chol.triangularView<Eigen::Lower>().solve(Ks);
  p.variance = ((gp.hyper.kernel.outputscale - V.colwise().squaredNorm().array()).max(0.0) * gp.y_scale * gp.y_scale)
                   .matrix()
                   .transpose();
  return p;
}

Eigen::VectorXd gp_posterior_sample(const GaussianProcess& gp, const Eigen::MatrixXd& Xs, const Eigen::VectorXd& z) {
  if (Xs.cols() != gp.dim()) throw InvalidInput("Gaussian process: sample points of the wrong dimension");
  if (z.size() != Xs.rows()) throw InvalidInput("Gaussian process: one normal draw per sample point is needed");
  const Eigen::MatrixXd Ks = matern52_matrix(gp.X, Xs, gp.hyper.kernel);
  const Eigen::MatrixXd V = gp.chol.triangularView<Eigen::Lower>().solve(Ks);
  Eigen::MatrixXd S = matern52_matrix(Xs, Xs, gp.hyper.kernel) - V.transpose() * V;
  const Eigen::VectorXd mean = Ks.transpose() * gp.alpha;
  double jitter = 1e-8 * gp.hyper.kernel.outputscale;
  for (int attempt = 0; attempt < 12; ++attempt, jitter *= 10.0) {
    Eigen::MatrixXd Sj = S;
    Sj.diagonal().array() += jitter;
    const Eigen::LLT<Eigen::MatrixXd> llt(Sj);
    if (llt.info() == Eigen::Success) {
      return ((mean + llt.matrixL() * z).array() * gp.y_scale + gp.y_mean).matrix();
    }
  }
  throw SolverError("Gaussian process: the posterior covariance does not factor even with jitter");
}

}  // namespace knitforge
