#include "knitforge/sim/newton_solve.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/core.h>

#include "knitforge/util/errors.h"
#include "knitforge/util/timer.h"

namespace knitforge {

double max_vertex_force(const Eigen::VectorXd& g, const std::vector<char>& fixed) {
  double m = 0.0;
  for (Eigen::Index v = 0; v < g.size() / 3; ++v) {
    double s = 0.0;
    bool free = fixed.empty();
    for (int k = 0; k < 3; ++k) {
      if (fixed.empty() || !fixed[3 * v + k]) {
        s += g[3 * v + k] * g[3 * v + k];
        free = true;
      }
    }
    if (free) m = std::max(m, std::sqrt(s));
  }
  return m;
}

double hold_fixed_unknowns(const HessianPattern& pattern, const std::vector<char>& fixed, std::vector<double>& values) {
  const auto& starts = pattern.column_starts();
  const auto& rows = pattern.rows();
  const int dim = 3 * pattern.num_vertices();
  double diag = 0.0;
  int free = 0;
  for (int c = 0; c < dim; ++c) {
    const bool fc = !fixed.empty() && fixed[c];
    for (int64_t k = starts[c]; k < starts[c + 1]; ++k) {
      const int r = rows[k];
      const bool fr = !fixed.empty() && fixed[r];
      if (fc || fr) values[k] = r == c ? 1.0 : 0.0;
    }
    if (!fc) {
      diag += values[starts[c]];
      ++free;
    }
  }
  return free > 0 ? diag / free : 1.0;
}

NewtonResult newton_solve(const Eigen::VectorXd& x0, const std::vector<char>& fixed, const EvaluateEnergy& evaluate,
                          const MaxStep& max_step, const NewtonOptions& options, SparseSolver& solver,
                          const EvaluateEnergy& projected) {
  if (!fixed.empty() && static_cast<Eigen::Index>(fixed.size()) != x0.size()) {
    throw InvalidInput(fmt::format("Newton: {} fixed flags for {} unknowns", fixed.size(), x0.size()));
  }
  if (!x0.allFinite()) throw InvalidInput("Newton: the start positions are not finite");
  if (!(options.max_iterations >= 0 && options.force_tolerance_mn > 0 && options.max_line_search_steps > 0)) {
    throw InvalidInput("Newton: max_iterations >= 0, force_tolerance_mn > 0 and max_line_search_steps > 0 needed");
  }
  if (!(options.max_step_growth >= 1 && options.max_step_growth <= 1024 &&
        std::exp2(std::round(std::log2(options.max_step_growth))) == options.max_step_growth)) {
    throw InvalidInput(fmt::format("Newton: max_step_growth {} must be a power of two in [1, 1024]",
                                   options.max_step_growth));
  }
  NewtonResult res;
  res.x = x0;
  double mu = 0.0;
  // The projected start: until the exact Hessian first factors.
  bool projected_start = static_cast<bool>(projected);
  constexpr double kMuMin = 1e-8, kMuMax = 1e6;
  for (int it = 0;; ++it) {
    Timer t;
    EnergyEval ev = evaluate(res.x, Derivatives::Hessian);
    res.seconds.evaluate += t.seconds();
    if (!std::isfinite(ev.value)) {
      if (it == 0) throw InvalidInput("Newton: the start positions are inadmissible (infinite energy)");
      throw SolverError("Newton: the energy became non-finite at an accepted iterate");
    }
    Eigen::VectorXd g = ev.gradient;
    for (Eigen::Index k = 0; k < g.size(); ++k)
      if (!fixed.empty() && fixed[k]) g[k] = 0.0;
    if (!g.allFinite()) throw SolverError("Newton: the energy gradient is not finite");
    res.energy = ev.value;
    res.energies.push_back(ev.value);
    res.max_force_mn = max_vertex_force(g, fixed);
    if (res.max_force_mn <= options.force_tolerance_mn) {
      res.converged = true;
      res.stop_reason = "converged";
      break;
    }
    if (it >= options.max_iterations) {
      res.stop_reason = "iteration limit";
      break;
    }
    double scale = hold_fixed_unknowns(*ev.pattern, fixed, ev.hessian_values);
    NewtonIterate rec;
    rec.energy = ev.value;
    rec.max_force_mn = res.max_force_mn;
    bool stepped = false;
    while (!stepped) {
      // Factor H + mu s I, raising mu until it factors.
      t.reset();
      Eigen::VectorXd p;
      for (;;) {
        std::vector<double> vals = ev.hessian_values;
        if (mu > 0) {
          for (int c = 0; c < static_cast<int>(g.size()); ++c)
            if (fixed.empty() || !fixed[c]) vals[ev.pattern->diagonal_index(c)] += mu * scale;
        }
        ++res.factorizations;
        ++rec.factorizations;
        try {
          solver.refactor(ev.pattern->matrix(vals));
          p = solver.solve(-g);
          if (!rec.projected) projected_start = false;
          break;
        } catch (const SolverError&) {
          if (projected_start && !rec.projected) {
            // The exact Hessian is indefinite: take the projected one's step.
            Timer te;
            EnergyEval pe = projected(res.x, Derivatives::Hessian);
            res.seconds.evaluate += te.seconds();
            ev.hessian_values = std::move(pe.hessian_values);
            scale = hold_fixed_unknowns(*ev.pattern, fixed, ev.hessian_values);
            rec.projected = true;
            mu = 0.0;
            continue;
          }
          mu = mu == 0.0 ? kMuMin : mu * 10.0;
          if (mu > kMuMax) break;
        }
      }
      res.seconds.factor += t.seconds();
      if (p.size() == 0) {
        res.stop_reason = "factorisation failed";
        return res;
      }
      const double slope = g.dot(p);
      if (!(slope < 0)) {
        mu = std::max(mu * 10.0, kMuMin);
        if (mu > kMuMax) {
          res.stop_reason = "no descent (round-off)";
          return res;
        }
        continue;
      }
      t.reset();
      const Eigen::VectorXd x1 = res.x + p;
      const double alpha_max = std::clamp(max_step(res.x, x1), 0.0, 1.0);
      res.seconds.max_step += t.seconds();
      t.reset();
      double alpha = alpha_max;
      bool accepted = false;
      Eigen::VectorXd trial;
      double e_trial = ev.value;
      for (int ls = 0; ls < options.max_line_search_steps && alpha > 0; ++ls) {
        trial = res.x + alpha * p;
        e_trial = evaluate(trial, Derivatives::Value).value;
        ++rec.energy_trials;
        if (std::isfinite(e_trial) && e_trial <= ev.value + options.armijo * alpha * slope) {
          accepted = true;
          break;
        }
        alpha *= 0.5;
      }
      res.seconds.line_search += t.seconds();
      if (accepted && alpha == 1.0 && options.max_step_growth > 1) {
        // Step growth: the full step was accepted at once; go on while the
        // energy keeps falling by more than its round-off.
        t.reset();
        const double growth = options.max_step_growth;
        const double alpha_cap = growth * std::clamp(max_step(res.x, res.x + growth * p), 0.0, 1.0);
        res.seconds.max_step += t.seconds();
        t.reset();
        bool grown = false;
        for (double a = 2.0; a <= alpha_cap; a *= 2.0) {
          Eigen::VectorXd bigger = res.x + a * p;
          const double e = evaluate(bigger, Derivatives::Value).value;
          ++rec.energy_trials;
          if (!(std::isfinite(e) && e < e_trial - 1e-12 * std::abs(e_trial))) break;
          trial = std::move(bigger);
          e_trial = e;
          alpha = a;
          grown = true;
        }
        if (grown) ++res.grown_steps;
        res.seconds.line_search += t.seconds();
      }
      // Round-off: the predicted decrease is below the energy's resolution.
      const double resolution = 1e-14 * (std::abs(ev.value) + 1e-300);
      if (!accepted) {
        if (-slope <= resolution || mu >= kMuMax) {
          res.stop_reason = "no descent (round-off)";
          return res;
        }
        mu = std::max(mu * 100.0, kMuMin);
        continue;
      }
      res.x = std::move(trial);
      ++res.iterations;
      stepped = true;
      rec.shift = mu;
      rec.step = alpha;
      res.history.push_back(rec);
      if (alpha >= 0.5 * alpha_max && alpha_max == 1.0) {
        mu = mu <= kMuMin ? 0.0 : mu * 0.1;
      } else if (alpha < 0.1 * alpha_max) {
        mu = std::max(mu * 4.0, kMuMin);
      }
    }
  }
  return res;
}

}  // namespace knitforge
