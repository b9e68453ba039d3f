#include "knitforge/sim/quasi_newton_solve.h"

#include <algorithm>
#include <cmath>

#include <fmt/core.h>

#include "knitforge/util/errors.h"
#include "knitforge/util/timer.h"

namespace knitforge {

Eigen::VectorXd lbfgs_direction(const Eigen::VectorXd& g, const std::vector<Eigen::VectorXd>& s,
                                const std::vector<Eigen::VectorXd>& y,
                                const std::function<Eigen::VectorXd(const Eigen::VectorXd&)>& apply_h0) {
  const size_t m = s.size();
  std::vector<double> a(m), rho(m);
  Eigen::VectorXd q = g;
  for (size_t i = m; i-- > 0;) {
    rho[i] = 1.0 / s[i].dot(y[i]);
    a[i] = rho[i] * s[i].dot(q);
    q -= a[i] * y[i];
  }
  Eigen::VectorXd r = apply_h0(q);
  for (size_t i = 0; i < m; ++i) {
    const double b = rho[i] * y[i].dot(r);
    r += (a[i] - b) * s[i];
  }
  return -r;
}

namespace {

Eigen::VectorXd free_part(Eigen::VectorXd g, const std::vector<char>& fixed) {
  if (!fixed.empty())
    for (Eigen::Index k = 0; k < g.size(); ++k)
      if (fixed[k]) g[k] = 0.0;
  return g;
}

// Assembles matrix(x) with the fixed unknowns held and factors it, shifted
// tenfold from 1e-8 of its mean diagonal entry while it does not factor.
void factor_at(const Eigen::VectorXd& x, const std::vector<char>& fixed, const EvaluateEnergy& matrix,
               SparseSolver& solver, QuasiNewtonResult& res) {
  Timer t;
  EnergyEval a = matrix(x, Derivatives::Hessian);
  if (!a.pattern || !a.wants_hessian()) throw InvalidInput("quasi-Newton: the matrix evaluation gave no Hessian");
  const double scale = hold_fixed_unknowns(*a.pattern, fixed, a.hessian_values);
  for (double mu = 0.0; mu <= 1e6; mu = mu == 0.0 ? 1e-8 : 10.0 * mu) {
    std::vector<double> vals = a.hessian_values;
    if (mu > 0) {
      for (Eigen::Index c = 0; c < x.size(); ++c)
        if (fixed.empty() || !fixed[c]) vals[a.pattern->diagonal_index(static_cast<int>(c))] += mu * scale;
    }
    ++res.factorizations;
    try {
      solver.refactor(a.pattern->matrix(vals));
      res.seconds.factor += t.seconds();
      return;
    } catch (const SolverError&) {
    }
  }
  throw SolverError("quasi-Newton: the initial Hessian does not factor even shifted by 10^6 of its diagonal");
}

}  // namespace

double next_trial_step(double alpha, double energy, double slope, double trial_energy) {
  const double curvature = trial_energy - energy - slope * alpha;
  const double next = std::isfinite(trial_energy) && curvature > 0 ? -slope * alpha * alpha / (2 * curvature)
                                                                    : 0.5 * alpha;
  return std::clamp(next, 0.1 * alpha, 0.5 * alpha);
}

QuasiNewtonResult quasi_newton_solve(const Eigen::VectorXd& x0, const std::vector<char>& fixed,
                                     const EvaluateEnergy& evaluate, const EvaluateEnergy& matrix,
                                     const MaxStep& max_step, const QuasiNewtonOptions& o, SparseSolver& solver) {
  if (!fixed.empty() && static_cast<Eigen::Index>(fixed.size()) != x0.size()) {
    throw InvalidInput(fmt::format("quasi-Newton: {} fixed flags for {} unknowns", fixed.size(), x0.size()));
  }
  if (!x0.allFinite()) throw InvalidInput("quasi-Newton: the start positions are not finite");
  if (!(o.max_iterations >= 0 && o.history >= 0 && o.stall_window >= 1 && o.stall_decrease >= 0 &&
        o.max_refreshes >= 0 && o.force_tolerance_mn > 0 && o.max_line_search_steps > 0 && o.armijo > 0 &&
        o.armijo < 1)) {
    throw InvalidInput("quasi-Newton: bad options (max_iterations, history, max_refreshes >= 0, stall_window >= 1, "
                       "stall_decrease >= 0, force_tolerance_mn > 0, max_line_search_steps > 0, 0 < armijo < 1)");
  }
  QuasiNewtonResult res;
  res.x = x0;
  if (o.max_iterations == 0) {
    res.stop_reason = "iteration limit";
    return res;
  }
  Timer t;
  EnergyEval ev = evaluate(res.x, Derivatives::Gradient);
  res.seconds.evaluate += t.seconds();
  ++res.evaluations;
  if (!std::isfinite(ev.value)) throw InvalidInput("quasi-Newton: the start positions are inadmissible (infinite energy)");
  double energy = ev.value;
  Eigen::VectorXd g = free_part(std::move(ev.gradient), fixed);
  if (!g.allFinite()) throw SolverError("quasi-Newton: the energy gradient is not finite");
  factor_at(res.x, fixed, matrix, solver, res);
  const auto apply_h0 = [&](const Eigen::VectorXd& q) {
    const Timer ts;
    Eigen::VectorXd r = free_part(solver.solve(q), fixed);
    res.seconds.factor += ts.seconds();
    return r;
  };
  std::vector<Eigen::VectorXd> s, y;  // oldest first
  int refreshes = 0;
  size_t window_start = 0;  // index into res.energies of the current factor's first iterate
  for (int it = 0;; ++it) {
    res.energies.push_back(energy);
    res.energy = energy;
    res.max_force_mn = max_vertex_force(g, fixed);
    if (res.max_force_mn <= o.force_tolerance_mn) {
      res.stop_reason = "small force";
      break;
    }
    const size_t k = res.energies.size() - 1;
    if (k >= window_start + static_cast<size_t>(o.stall_window) &&
        res.energies[k - o.stall_window] - energy <= o.stall_decrease * (res.energies[window_start] - energy)) {
      if (refreshes >= o.max_refreshes) {
        res.stop_reason = "stalled";
        break;
      }
      ++refreshes;
      factor_at(res.x, fixed, matrix, solver, res);
      s.clear();
      y.clear();
      window_start = k;
    }
    if (it >= o.max_iterations) {
      res.stop_reason = "iteration limit";
      break;
    }
    bool accepted = false;
    Eigen::VectorXd x1, g1;
    double e1 = energy;
    // First the L-BFGS direction; when it fails, the plain -A⁻¹ g.
    for (int attempt = 0; attempt < 2 && !accepted; ++attempt) {
      if (attempt == 1) {
        if (s.empty()) break;  // that was -A⁻¹ g already
        s.clear();
        y.clear();
      }
      const Eigen::VectorXd p = lbfgs_direction(g, s, y, apply_h0);
      const double slope = g.dot(p);
      if (!(slope < 0)) continue;
      t.reset();
      const double alpha_max = std::clamp(max_step(res.x, res.x + p), 0.0, 1.0);
      res.seconds.max_step += t.seconds();
      t.reset();
      double alpha = alpha_max;
      for (int ls = 0; ls < o.max_line_search_steps && alpha > 0; ++ls) {
        Eigen::VectorXd trial = res.x + alpha * p;
        EnergyEval e = evaluate(trial, Derivatives::Gradient);
        ++res.evaluations;
        if (std::isfinite(e.value) && e.value <= energy + o.armijo * alpha * slope) {
          x1 = std::move(trial);
          e1 = e.value;
          g1 = free_part(std::move(e.gradient), fixed);
          accepted = true;
          break;
        }
        alpha = next_trial_step(alpha, energy, slope, e.value);
      }
      res.seconds.line_search += t.seconds();
    }
    if (!accepted) {
      res.stop_reason = "no descent";
      break;
    }
    if (!g1.allFinite()) throw SolverError("quasi-Newton: the energy gradient is not finite");
    Eigen::VectorXd sk = x1 - res.x, yk = g1 - g;
    if (o.history > 0 && sk.dot(yk) > 1e-12 * sk.norm() * yk.norm()) {
      if (static_cast<int>(s.size()) == o.history) {
        s.erase(s.begin());
        y.erase(y.begin());
      }
      s.push_back(std::move(sk));
      y.push_back(std::move(yk));
    }
    res.x = std::move(x1);
    g = std::move(g1);
    energy = e1;
    ++res.iterations;
  }
  return res;
}

}  // namespace knitforge
