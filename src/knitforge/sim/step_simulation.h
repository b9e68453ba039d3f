#pragma once
/// \file step_simulation.h
/// Time stepping (backward Euler) and static equilibrium of a SimModel,
/// with contact and friction against a kinematic body (docs/sim.md).
///
/// One step of length h from (x_n, v_n), the body moving from its pose at
/// t_n to its pose at t_{n+1}:
///  1. the start of the step is made collision free: vertices within reach
///     of the body are carried with their closest body point, pins go to
///     their targets, and the simultaneous motion of fabric and body is
///     checked by collision_free_step(); if the body would pass through a
///     vertex the step is split in two (up to 8 levels) — and if even that
///     fails, SolverError names the step;
///  2. friction pairs are built at x_n (lagged normal forces);
///  3. newton_solve() minimises the incremental potential (inertia_energy.h)
///     with membrane, bending, contact and friction energies, each step of
///     it limited to the collision-free fraction; with
///     StepOptions::quasi_newton on, the L-BFGS phase of
///     quasi_newton_solve.h goes first (its initial inverse Hessian the
///     factor of the Clamp-projected Hessian at the step's start, dominated
///     by the inertia term M/h²) and Newton finishes from where it stopped:
///     Newton's criterion decides convergence, as without the phase;
///  4. v_{n+1} = (x_{n+1} - x_n) / h.
/// `friction_iterations` > 1 repeats 2-3 with the normal forces of the
/// last solution (IPC's lagged iterations).
///
/// Static equilibrium (solve_equilibrium()) minimises membrane + bending
/// (+ gravity + contact + friction against slipping from the start) over x;
/// a free piece without gravity settles where its stitches balance. Friction
/// in statics takes its normal forces from the start in the first round and
/// from the last solution in the next ones, so start from a settled state
/// (settle_on_support()): from a piece barely touching a smooth support the
/// first round is nearly frictionless and the piece may slide off.

#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "knitforge/geometry/sparse_solver.h"
#include "knitforge/sim/contact_energy.h"
#include "knitforge/sim/energy_eval.h"
#include "knitforge/sim/kinematic_body.h"
#include "knitforge/sim/newton_solve.h"
#include "knitforge/sim/psd_projection.h"
#include "knitforge/sim/quasi_newton_solve.h"
#include "knitforge/sim/sim_model.h"
#include "knitforge/sim/sim_state.h"

namespace knitforge {

/// What every solve of one model reuses: the Hessian pattern and the sparse
/// solver (symbolic analysis). Cheap to move, not to copy.
class SimWorkspace {
 public:
  /// \pre model outlives the workspace.
  explicit SimWorkspace(const SimModel& model);
  const SimModel& model() const { return *model_; }
  const std::shared_ptr<const HessianPattern>& pattern() const { return pattern_; }
  SparseSolver& solver() { return solver_; }
  /// Fixed flags (3n) of the model's pinned vertices, and vertex flags (n).
  const std::vector<char>& fixed_dofs() const { return fixed_; }
  const std::vector<char>& pinned_vertices() const { return pinned_; }

 private:
  const SimModel* model_;
  std::shared_ptr<const HessianPattern> pattern_;
  SparseSolver solver_;
  std::vector<char> fixed_, pinned_;
};

struct StepOptions {
  double time_step_s = 1.0 / 60.0;
  Vec3 gravity_mm_s2{0.0, 0.0, -9810.0};
  ContactParams contact;
  NewtonOptions newton;
  PsdProjection projection = PsdProjection::Clamp;
  int friction_iterations = 1;
  /// The quasi-Newton phase before each Newton solve (quasi_newton_solve.h;
  /// off when max_iterations is 0): L-BFGS on the incremental potential
  /// with the factor of its Clamp-projected Hessian at the start as initial
  /// inverse Hessian (refreshed when progress stalls), then Newton from
  /// where it stopped. Its force tolerance is set to Newton's.
  QuasiNewtonOptions quasi_newton;
};

struct StepResult {
  SimState state;
  bool converged = false;   ///< every Newton solve of the step converged
  int newton_iterations = 0;
  int quasi_newton_iterations = 0;  ///< L-BFGS steps before Newton
  /// Cholesky factorisations (Newton's and the quasi-Newton phase's, failed
  /// ones included).
  int factorizations = 0;
  /// Newton solves of the step that stopped at NewtonOptions::max_iterations.
  int solves_at_iteration_limit = 0;
  int substeps = 1;         ///< 1, or more when the body's motion split the step
  int contacts = 0;         ///< contact pairs at the end
  double min_distance_mm = 0.0;  ///< smallest vertex-body distance at the end (+inf: none near)
  double energy = 0.0;      ///< elastic energy (membrane + bending) at the end (µJ)
  double max_force_mn = 0.0;
  NewtonTimings seconds;
};

/// One backward-Euler step from `state`; the body is at its t_n pose in
/// `body` and moves to `body_end` (vertex positions, same mesh; empty = it
/// stays). `pin_targets` holds the end positions of the model's pinned
/// vertices in the order of SimModel::pinned (empty = they stay).
/// \throw InvalidInput for mismatched sizes or bad options; SolverError when
///        the body passes through the fabric or the energy becomes non-finite.
StepResult step_simulation(SimWorkspace& ws, const SimState& state, const KinematicBody& body,
                           const std::vector<Vec3>& body_end, const std::vector<Vec3>& pin_targets,
                           const StepOptions& options);

struct EquilibriumOptions {
  /// Gravity (mm/s²); zero for the free shape.
  Vec3 gravity_mm_s2 = Vec3::Zero();
  ContactParams contact;
  /// Friction in statics resists slipping from the start positions, smoothed
  /// over this slip (mm) instead of ε_v h.
  double friction_slip_mm = 0.5;
  NewtonOptions newton;
  PsdProjection projection = PsdProjection::Clamp;
  /// With exact Hessians (projection None): the projection of the Newton
  /// steps taken while the exact Hessian does not factor, until it first
  /// does (newton_solve()'s `projected`); None = Levenberg-Marquardt shifts
  /// from the start. Measured on the free short-row hemisphere (3688
  /// stitches): 250 -> 114 iterations with Clamp (docs/sim.md).
  PsdProjection start_projection = PsdProjection::Clamp;
  /// The quasi-Newton phase before Newton (quasi_newton_solve.h; off when
  /// max_iterations is 0): L-BFGS on the energy with a factor of the
  /// Clamp-projected Hessian (at the start, refreshed when progress stalls)
  /// as its initial inverse Hessian, then Newton from where it stopped (the
  /// convergence criterion is Newton's). Its force tolerance is set to
  /// Newton's. Each friction round runs it before its Newton solve.
  QuasiNewtonOptions quasi_newton;
  int friction_iterations = 3;
  /// Coordinates held at their start values besides the pins: empty, or one
  /// flag per coordinate (3n), e.g. free_body_constraints() (predict_shape.h).
  std::vector<char> held_coordinates;
};

struct EquilibriumResult {
  Eigen::VectorXd positions_mm;
  bool converged = false;
  int iterations = 0;  ///< Newton iterations over all friction iterations
  int factorizations = 0;  ///< Cholesky factorisations (more than iterations when shifts were needed; the quasi-Newton phase's included)
  /// Converged, and the exact Hessian there (held coordinates and pins
  /// fixed) is positive definite (it factors; one more factorisation, not
  /// counted above): a strict local minimum, not a saddle.
  bool local_minimum = false;
  int quasi_newton_iterations = 0;  ///< L-BFGS steps before Newton (over all friction iterations)
  int quasi_newton_evaluations = 0; ///< their energy values and gradients
  double energy = 0.0; ///< elastic energy at the end (µJ)
  double max_force_mn = 0.0;
  int contacts = 0;
  double min_distance_mm = 0.0;
  std::string stop_reason;
  NewtonTimings seconds;
  /// Every Newton iteration of every friction round, in order.
  std::vector<NewtonIterate> history;
};

/// Static equilibrium from x0 (3n), resting on `support` when it is given
/// (non-empty) and x0 is at a positive distance from it.
/// \throw InvalidInput when x0 touches or is inside the support's barrier
///        zone... (distance 0), for gravity without a support or pins (a
///        falling piece has no equilibrium), bad sizes or options.
EquilibriumResult solve_equilibrium(SimWorkspace& ws, const Eigen::VectorXd& x0, const KinematicBody* support,
                                    const EquilibriumOptions& options);

/// Membrane + bending energy of the model at x (µJ).
double elastic_energy(const SimModel& model, const Eigen::VectorXd& x);

}  // namespace knitforge
