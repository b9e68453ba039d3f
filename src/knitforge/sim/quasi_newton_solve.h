#pragma once
/// \file quasi_newton_solve.h
/// A quasi-Newton phase before Newton (newton_solve.h) for the simulator's
/// energies: L-BFGS whose initial inverse Hessian is the Cholesky factor of
/// a positive definite matrix A, e.g. the Clamp-projected Hessian at the
/// start, kept for many iterations (refreshed now and then, below; the idea
/// of Liu, Bouaziz and Kavan 2017, "Quasi-Newton methods for real-time
/// simulation of hyperelastic materials"). An iteration costs one energy
/// value and gradient per line-search trial and one back-substitution with
/// the factor (milliseconds), where a Newton iteration costs a Hessian
/// assembly and a factorisation (~0.1 s at 11k unknowns), so L-BFGS takes
/// the long, cheap descent of a buckling piece and Newton whatever is left
/// (on the free predictions measured in docs/sim.md L-BFGS reaches Newton's
/// tolerance itself and Newton only confirms it).
///
/// Each iteration: the direction p = -H_k g by the L-BFGS two-loop
/// recursion over the last `history` pairs (s, y) = (x_{k+1} - x_k,
/// g_{k+1} - g_k), with H_0 = A⁻¹ (A the factored matrix; no scaling: A is
/// a Hessian, so it has the right units); limited to the collision-free
/// fraction max_step(x, x + p) (at most 1), shortened until the Armijo
/// condition E(x + αp) <= E(x) + 10⁻⁴ α gᵀp holds (next_trial_step(): the
/// quadratic's minimiser, where halving took 2.1 trials an iteration on the
/// free hemisphere and the interpolation 1.6). A pair whose curvature
/// sᵀy is not positive is not stored (the energy is not convex). When p is
/// not a descent direction or no step length satisfies Armijo, the history
/// is dropped and the step is -A⁻¹ g (always a descent direction).
///
/// **Refresh**: A is a good model only near where it was assembled, and a
/// buckling piece moves far. When, over the last `stall_window` iterations,
/// the energy fell by less than `stall_decrease` times its decrease since A
/// was factored, A is re-assembled and factored at the current x (the
/// history dropped), at most `max_refreshes` times; after that the phase
/// stops ("stalled"). Also stops when the
/// largest free vertex force is at most `force_tolerance_mn` ("small
/// force"), at the iteration limit, or when even -A⁻¹ g gives no decrease
/// ("no descent"). It never claims convergence: the caller finishes with
/// Newton, whose criterion decides. Fixed unknowns keep their values (their
/// rows and columns of A replaced by the identity, their gradient entries
/// ignored). Deterministic: the same inputs give the same iterates.

#include <string>
#include <vector>

#include <Eigen/Core>

#include "knitforge/geometry/sparse_solver.h"
#include "knitforge/sim/newton_solve.h"

namespace knitforge {

struct QuasiNewtonOptions {
  int max_iterations = 0;  ///< 0 switches the phase off
  int history = 8;         ///< (s, y) pairs kept
  /// Refresh A when the energy fell by less than stall_decrease times its
  /// decrease since A was factored over the last stall_window iterations
  /// (see the file comment). Measured on the free short-row hemisphere
  /// (docs/sim.md): 0.3 and 10 take 21 factorisations, 0.1 takes 17 but
  /// 50 % more iterations and line-search trials, 0.01 of the decrease
  /// since the start 46.
  int stall_window = 10;
  double stall_decrease = 0.3;
  /// Re-factorisations of A at the current x (0: A is the start's only).
  int max_refreshes = 200;
  /// Stop (hand over to Newton) when the largest free vertex force is at
  /// most this (mN).
  double force_tolerance_mn = 1e-6;
  int max_line_search_steps = 30;
  double armijo = 1e-4;
};

struct QuasiNewtonResult {
  Eigen::VectorXd x;
  int iterations = 0;      ///< steps taken
  int factorizations = 0;  ///< of A, failed ones (shifted again) included
  int evaluations = 0;     ///< energy values and gradients (line-search trials included)
  double energy = 0.0;     ///< at x (µJ)
  double max_force_mn = 0.0;
  /// Energy before each iteration and at the end.
  std::vector<double> energies;
  /// "small force", "stalled", "iteration limit", "no descent".
  std::string stop_reason;
  NewtonTimings seconds;  ///< evaluate: values and gradients; factor: A's assembly, factors and solves
};

/// Minimises the energy from x0 by L-BFGS (see the file comment).
/// `evaluate` gives values and gradients (Derivatives::Value or Gradient);
/// `matrix(x)` gives the positive semi-definite Hessian A is made of
/// (Derivatives::Hessian, e.g. the Clamp-projected energy); when A does not
/// factor, A + μ s I (s its mean diagonal entry) is factored with μ raised
/// tenfold from 10⁻⁸. `solver` must be analysed for matrix()'s pattern or
/// empty; it holds A's factor afterwards. With options.max_iterations == 0
/// returns x0 unchanged (no evaluation).
/// \throw InvalidInput for mismatched sizes, a non-finite or inadmissible
///        x0, bad options; SolverError when A does not factor even shifted
///        or the gradient is not finite.
QuasiNewtonResult quasi_newton_solve(const Eigen::VectorXd& x0, const std::vector<char>& fixed,
                                     const EvaluateEnergy& evaluate, const EvaluateEnergy& matrix,
                                     const MaxStep& max_step, const QuasiNewtonOptions& options,
                                     SparseSolver& solver);

/// The next step length of a backtracking line search after the trial
/// E(x + alpha p) = `trial_energy` failed Armijo: the minimiser of the
/// quadratic through E(x) = `energy`, its slope gᵀp = `slope` (< 0) and the
/// trial, kept within [0.1, 0.5] alpha; half of alpha when the trial energy
/// is not finite (an inadmissible state) or the quadratic has no minimum.
double next_trial_step(double alpha, double energy, double slope, double trial_energy);

/// The L-BFGS two-loop recursion: -H g for the inverse-Hessian approximation
/// H built from the pairs (s[i], y[i]) (oldest first, every sᵀy > 0) on top
/// of H_0 = `apply_h0` (a symmetric positive definite operator).
Eigen::VectorXd lbfgs_direction(const Eigen::VectorXd& g, const std::vector<Eigen::VectorXd>& s,
                                const std::vector<Eigen::VectorXd>& y,
                                const std::function<Eigen::VectorXd(const Eigen::VectorXd&)>& apply_h0);

}  // namespace knitforge
