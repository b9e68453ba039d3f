#include "knitforge/design/shortcolumn/turbo_optimize.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include <fmt/core.h>

#include "knitforge/util/errors.h"

namespace knitforge {

namespace {

uint64_t splitmix64(uint64_t& x) {
  uint64_t z = (x += 0x9E3779B97F4A7C15ull);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

uint64_t rotl(uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }

}  // namespace

TurboRandom::TurboRandom(uint64_t seed) {
  uint64_t x = seed;
  for (uint64_t& s : s_) s = splitmix64(x);
}

uint64_t TurboRandom::next() {
  const uint64_t result = rotl(s_[1] * 5, 7) * 9;
  const uint64_t t = s_[1] << 17;
  s_[2] ^= s_[0];
  s_[3] ^= s_[1];
  s_[1] ^= s_[2];
  s_[0] ^= s_[3];
  s_[2] ^= t;
  s_[3] = rotl(s_[3], 45);
  return result;
}

double TurboRandom::uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }

double TurboRandom::normal() {
  if (has_spare_) {
    has_spare_ = false;
    return spare_;
  }
  double u = 0.0;
  while (u <= 0.0) u = uniform();
  const double v = uniform();
  const double r = std::sqrt(-2.0 * std::log(u));
  spare_ = r * std::sin(2.0 * std::numbers::pi * v);
  has_spare_ = true;
  return r * std::cos(2.0 * std::numbers::pi * v);
}

Eigen::MatrixXd latin_hypercube(int n, int dim, TurboRandom& rng) {
  Eigen::MatrixXd X(n, dim);
  std::vector<int> perm(static_cast<size_t>(n));
  for (int j = 0; j < dim; ++j) {
    for (int i = 0; i < n; ++i) perm[static_cast<size_t>(i)] = i;
    for (int i = n - 1; i > 0; --i) {  // Fisher-Yates
      const int k = static_cast<int>(rng.next() % static_cast<uint64_t>(i + 1));
      std::swap(perm[static_cast<size_t>(i)], perm[static_cast<size_t>(k)]);
    }
    for (int i = 0; i < n; ++i) X(i, j) = (perm[static_cast<size_t>(i)] + rng.uniform()) / n;
  }
  return X;
}

TurboResult turbo_optimize(const TurboProblem& pr, const TurboOptions& o) {
  const int d = static_cast<int>(pr.lower.size());
  if (d < 1 || pr.upper.size() != d) throw InvalidInput("TuRBO: the box needs lower and upper bounds of one size >= 1");
  for (int i = 0; i < d; ++i)
    if (!(pr.lower[i] < pr.upper[i]) || !std::isfinite(pr.lower[i]) || !std::isfinite(pr.upper[i]))
      throw InvalidInput(fmt::format("TuRBO: box dimension {} is [{}, {}]; it must be finite with lower < upper", i,
                                     pr.lower[i], pr.upper[i]));
  if (!pr.objective) throw InvalidInput("TuRBO: no objective");
  if (o.max_evaluations < 1) throw InvalidInput("TuRBO: the budget must be at least one evaluation");
  const int n_init = o.initial_points > 0 ? o.initial_points : std::max(2 * d, 5);
  const int n_cand = o.candidates > 0 ? o.candidates : std::min(100 * d, 5000);
  const Eigen::VectorXd span = pr.upper - pr.lower;
  auto to_unit = [&](const Eigen::VectorXd& x) { return Eigen::VectorXd((x - pr.lower).array() / span.array()); };
  auto from_unit = [&](const Eigen::VectorXd& u) { return Eigen::VectorXd(pr.lower.array() + u.array() * span.array()); };
  auto check_size = [&](const Eigen::VectorXd& x, const char* what) {
    if (x.size() != d || !x.allFinite())
      throw InvalidInput(fmt::format("TuRBO: the {} returned a point of size {} (or not finite); expected {}", what,
                                     x.size(), d));
  };

  TurboRandom rng(o.seed);
  TurboResult r;
  r.best_value = std::numeric_limits<double>::infinity();

  auto evaluate = [&](const Eigen::VectorXd& suggested, bool initial, int region, double length,
                      std::vector<Eigen::VectorXd>& X, std::vector<double>& Y) {
    Eigen::VectorXd at = suggested;
    if (pr.project) {
      at = pr.project(suggested);
      check_size(at, "projection");
    }
    TurboEvaluation e;
    e.index = static_cast<int>(r.history.size());
    e.region = region;
    e.initial = initial;
    e.suggested = suggested;
    e.evaluated = at;
    e.projected = (at - suggested).norm() > 1e-12 * (1.0 + suggested.norm());
    e.value = pr.objective(at);
    if (!std::isfinite(e.value)) {
      std::string p;
      for (int i = 0; i < d; ++i) p += fmt::format("{}{}", i ? "," : "", at[i]);
      throw InvalidInput(fmt::format("TuRBO: the objective is not finite at ({})", p));
    }
    e.penalised = e.projected ? e.value + std::exp((at - suggested).squaredNorm()) : e.value;
    e.trust_length = length;
    X.push_back(to_unit(at));
    Y.push_back(e.value);
    if (e.projected) {
      X.push_back(to_unit(suggested));
      Y.push_back(e.penalised);
    }
    if (e.value < r.best_value) {
      r.best_value = e.value;
      r.best_x = at;
      r.best_index = e.index;
    }
    e.best = r.best_value;
    r.history.push_back(e);
    if (o.on_evaluation) o.on_evaluation(r.history.back());
    return e.value;
  };

  GpHyperparameters previous;
  bool have_previous = false;
  while (static_cast<int>(r.history.size()) < o.max_evaluations) {
    const int region = r.regions++;
    TrustRegionState tr = make_trust_region(o.trust_region);
    std::vector<Eigen::VectorXd> X;  // unit cube
    std::vector<double> Y;
    // Feasible data only decide the centre (penalised pairs are model hints).
    std::vector<char> feasible;
    const Eigen::MatrixXd design = latin_hypercube(n_init, d, rng);
    for (int i = 0; i < n_init && static_cast<int>(r.history.size()) < o.max_evaluations; ++i) {
      Eigen::VectorXd x = pr.sample_feasible ? pr.sample_feasible(design.row(i).transpose())
                                             : from_unit(design.row(i).transpose());
      check_size(x, "feasible sampler");
      const size_t before = X.size();
      const double v = evaluate(x, true, region, 0.0, X, Y);
      for (size_t k = before; k < X.size(); ++k) feasible.push_back(k == before ? 1 : 0);
      if (!tr.has_best || v < tr.best) tr.best = v, tr.has_best = true;
    }
    have_previous = false;  // a fresh model per trust region (TuRBO-1)
    while (static_cast<int>(r.history.size()) < o.max_evaluations && !tr.restart) {
      Eigen::MatrixXd Xm(static_cast<Eigen::Index>(X.size()), d);
      Eigen::VectorXd Ym(static_cast<Eigen::Index>(Y.size()));
      for (size_t k = 0; k < X.size(); ++k) Xm.row(static_cast<Eigen::Index>(k)) = X[k].transpose(), Ym[static_cast<Eigen::Index>(k)] = Y[k];
      const GaussianProcess gp = fit_gaussian_process(Xm, Ym, o.gp, have_previous ? &previous : nullptr);
      previous = gp.hyper;
      have_previous = true;
      size_t centre = 0;
      double best = std::numeric_limits<double>::infinity();
      for (size_t k = 0; k < X.size(); ++k)
        if (feasible[k] && Y[k] < best) best = Y[k], centre = k;
      Eigen::VectorXd lo, hi;
      trust_region_box(tr, X[centre], gp.hyper.kernel.lengthscale, lo, hi);
      Eigen::MatrixXd C(n_cand, d);
      for (int c = 0; c < n_cand; ++c)
        for (int i = 0; i < d; ++i) C(c, i) = lo[i] + (hi[i] - lo[i]) * rng.uniform();
      Eigen::VectorXd z(n_cand);
      for (int c = 0; c < n_cand; ++c) z[c] = rng.normal();
      const Eigen::VectorXd sample = gp_posterior_sample(gp, C, z);
      Eigen::Index pick = 0;
      sample.minCoeff(&pick);
      const size_t before = X.size();
      const double v = evaluate(from_unit(C.row(pick).transpose()), false, region, tr.length, X, Y);
      for (size_t k = before; k < X.size(); ++k) feasible.push_back(k == before ? 1 : 0);
      update_trust_region(tr, v, d, o.trust_region);
    }
  }
  return r;
}

}  // namespace knitforge
