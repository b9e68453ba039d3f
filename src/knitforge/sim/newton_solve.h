#pragma once
/// \file newton_solve.h
/// Newton's method with line search for the simulator's energies (static
/// equilibrium and every backward-Euler step, docs/sim.md).
///
/// Each iteration evaluates value, gradient and Hessian, solves
/// (H + μ s I) p = -g with CHOLMOD (geometry/sparse_solver.h, refactor(): the symbolic
/// analysis is reused while the pattern stays; s = the mean
/// diagonal entry, μ >= 0 a Levenberg-Marquardt shift that is 0 whenever the
/// Hessian factors and the full step is taken, raised tenfold when the
/// factorisation fails or the step is poor), limits the step to the
/// collision-free fraction max_step(x, x + p) (at most 1) and backtracks
/// (halving) until the Armijo condition E(x + αp) <= E(x) + 10⁻⁴ α gᵀp holds.
/// When the first trial is the full Newton step (not cut by the collision-
/// free limit) and is accepted, the step may be too short: a barrier's
/// curvature falls as a vertex moves away from the body, and a projected
/// (Clamp) Hessian overestimates the curvature of compressed fabric, so
/// Newton's model stops short. **Step growth** then tries α = 2, 4, ... up
/// to max_step_growth (64) times the Newton step, each within the
/// collision-free limit max_step(x, x + max_step_growth p), and keeps the
/// largest α up to the first that does not lower the energy by more than
/// its round-off (10⁻¹² |E|): a decrease at the level of round-off is not
/// taken for progress. Each trial costs one energy value (no
/// factorisation). max_step_growth = 1 switches it off.
/// Fixed unknowns (pins) keep their values: their rows and columns are
/// replaced by the identity and their gradient entries ignored.
///
/// Converged means: the largest force on a free vertex, max_i |g_i| (the
/// Euclidean norm of vertex i's three gradient entries, mN), is at most
/// force_tolerance_mn. The result says so honestly: `converged` is false
/// when the iteration limit is reached, the line search cannot decrease the
/// energy any more (round-off) or the factorisation keeps failing; x is then
/// the last iterate (the lowest energy found). Deterministic: the same inputs
/// give the same iterates.

#include <functional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "knitforge/geometry/sparse_solver.h"
#include "knitforge/sim/energy_eval.h"

namespace knitforge {

struct NewtonOptions {
  int max_iterations = 200;
  /// Converged when the largest free vertex force is at most this (mN).
  double force_tolerance_mn = 1e-6;
  int max_line_search_steps = 40;  ///< halvings at most per iteration
  double armijo = 1e-4;
  /// Step growth (see the file comment): the largest multiple of an
  /// accepted full Newton step tried, a power of two >= 1 (1 = off).
  double max_step_growth = 64.0;
};

/// Wall-clock seconds per part of the solve.
struct NewtonTimings {
  double evaluate = 0.0;     ///< value, gradient and Hessian evaluations
  double factor = 0.0;       ///< Cholesky factorisations and solves
  double max_step = 0.0;     ///< collision-free step computations
  double line_search = 0.0;  ///< energy evaluations of the line search
};

/// One Newton iteration, for saying where the iterations go.
struct NewtonIterate {
  double energy = 0.0;        ///< before the step (µJ)
  double max_force_mn = 0.0;  ///< before the step (mN)
  int factorizations = 0;     ///< attempted in this iteration (failed ones included)
  double shift = 0.0;         ///< μ of the factor whose step was taken (0: unshifted)
  double step = 0.0;          ///< α of the accepted step (1 = the full step; > 1 grown)
  int energy_trials = 0;      ///< energy values of the line search and step growth
  bool projected = false;     ///< the step is the projected Hessian's (the exact one did not factor)
};

struct NewtonResult {
  Eigen::VectorXd x;
  bool converged = false;
  int iterations = 0;        ///< Newton steps taken
  int factorizations = 0;    ///< Cholesky factorisations attempted (failed ones raise the shift)
  int grown_steps = 0;       ///< iterations whose step was grown past the Newton step
  double energy = 0.0;       ///< at x (µJ)
  double max_force_mn = 0.0; ///< largest free vertex force at x (mN)
  /// Energy before each iteration and at the end.
  std::vector<double> energies;
  /// One record per iteration taken (iterations entries).
  std::vector<NewtonIterate> history;
  /// "converged", "iteration limit", "no descent (round-off)", "factorisation failed".
  std::string stop_reason;
  NewtonTimings seconds;
};

/// evaluate(x, what): the energy at x (3n) with the requested derivatives;
/// an infinite value marks an inadmissible x (e.g. inside a barrier).
using EvaluateEnergy = std::function<EnergyEval(const Eigen::VectorXd& x, Derivatives what)>;
/// max_step(x0, x1): the largest fraction t in [0, 1] such that the straight
/// path x0 + s (x1 - x0), s in [0, t], is admissible (collision free).
using MaxStep = std::function<double(const Eigen::VectorXd& x0, const Eigen::VectorXd& x1)>;

/// Minimises the energy from x0. `fixed` is empty or one flag per unknown
/// (3n). `solver` keeps the factorisation between calls (pass the same one
/// for every solve with one model, so the symbolic analysis can be reused).
/// `projected` (optional) evaluates the same energy with a positive
/// semi-definite Hessian (element Hessians projected, e.g. Clamp): the
/// **projected start**. While the exact Hessian (evaluate's) has not yet
/// factored in this solve, an iteration whose exact Hessian does not factor
/// takes the projected Hessian's step (shifted only if that one does not
/// factor either) instead of raising the Levenberg-Marquardt shift; from the
/// first iteration whose exact (possibly shifted) Hessian factors on, it is
/// Newton with LM shifts as without `projected`. Far from equilibrium the
/// exact Hessian of buckling fabric is indefinite and the shifted steps are
/// short; near it the projected model is poor (docs/sim.md, "Solver").
/// Convergence is judged on the exact gradient either way.
/// \throw InvalidInput for mismatched sizes, a non-finite x0 or an
///        inadmissible (infinite-energy) x0; SolverError when the energy
///        becomes non-finite in a way no step size avoids.
NewtonResult newton_solve(const Eigen::VectorXd& x0, const std::vector<char>& fixed, const EvaluateEnergy& evaluate,
                          const MaxStep& max_step, const NewtonOptions& options, SparseSolver& solver,
                          const EvaluateEnergy& projected = {});

/// Replaces the rows and columns of the `fixed` unknowns (empty: none) of a
/// Hessian with `pattern`'s values by the identity's; returns the mean
/// diagonal entry of the free unknowns (1 when there is none), the scale of
/// a Levenberg-Marquardt shift.
double hold_fixed_unknowns(const HessianPattern& pattern, const std::vector<char>& fixed, std::vector<double>& values);

/// The largest vertex force max_i |g_i| over vertices whose three unknowns
/// are not all fixed (mN).
double max_vertex_force(const Eigen::VectorXd& gradient, const std::vector<char>& fixed);

}  // namespace knitforge
