#pragma once
/// \file predict_shape.h
/// The predicted shape of a knitted piece (docs/sim.md): the static
/// equilibrium of its SimModel (every stitch at rest at its ideal size),
/// started from the designed geometry, either free (no gravity: where the
/// stitches' disagreement balances) or resting under gravity on a support
/// (a kinematic body, as knitted samples are shown on a form).
///
///  - Free: the six rigid motions are removed by holding six coordinates of
///    three far-apart vertices (a "3-2-1" support: all of the first, two of
///    the farthest from it, one of the farthest from their line). They
///    carry no force at a free equilibrium, and the result reports the
///    largest force on any other coordinate.
///  - On a support: the piece is first centred above it (x, y of the
///    bounding-box centres; optional) and lifted along +z by the least amount
///    that puts every vertex on the support's outer side (the side its face
///    normals point to) at a distance of at least `start_gap_mm`; then it
///    settles by backward-Euler steps of 1/60 s with kinetic damping (the
///    velocities are zeroed whenever the kinetic energy passes a peak; a
///    dynamic relaxation) until no vertex moves faster than
///    `settle_speed_mm_s`, and the static equilibrium (gravity, contact
///    barrier, static friction with the settled normal forces) is solved
///    from there by Newton.
///
/// The result says whether Newton converged (largest free vertex force at
/// most the tolerance, mN) and how many iterations it took; a shape that did
/// not converge is returned too, labelled so.

#include <vector>

#include "knitforge/core/knit_params.h"
#include "knitforge/core/stitch_mesh.h"
#include "knitforge/sim/kinematic_body.h"
#include "knitforge/sim/membrane_energy.h"
#include "knitforge/sim/step_simulation.h"

namespace knitforge {

/// L-BFGS iterations of the quasi-Newton phase allowed per Newton
/// iteration (set_predict_iterations()): one factorisation costs about as
/// much as 20-30 of them at 11k unknowns (docs/sim.md, "Solver").
inline constexpr int kQuasiNewtonPerNewton = 20;

struct PredictOptions {
  SimModelOptions model;
  bool gravity = false;  ///< -9810 mm/s² along z (needs a support)
  EquilibriumOptions equilibrium = [] {
    EquilibriumOptions e;
    e.newton.force_tolerance_mn = 1e-5;
    e.newton.max_iterations = 500;
    e.projection = PsdProjection::None;  // exact Hessians, shifted when indefinite
    // L-BFGS first (docs/sim.md, "Solver"); Newton finishes and decides.
    e.quasi_newton.max_iterations = kQuasiNewtonPerNewton * 500;
    return e;
  }();
  /// Smallest distance of the piece to the support at the start (mm); must
  /// be below the contact distance so the barrier holds the piece from the
  /// first iteration.
  double start_gap_mm = 0.3;
  /// On a support: first move the piece in x and y so that the centre of its
  /// bounding box is above the centre of the support's.
  bool centre_on_support = true;
  /// Settling (on a support): stop when every vertex is slower than this.
  double settle_speed_mm_s = 1.0;
  int max_settle_steps = 600;  ///< 10 s of simulated time
  StepOptions settle = [] {
    StepOptions s;
    s.newton.force_tolerance_mn = 1e-5;
    return s;
  }();
};

struct PredictResult {
  StitchMesh predicted;  ///< the designed mesh with the equilibrium positions
  EquilibriumResult solve;
  double lift_mm = 0.0;  ///< how far the piece was lifted onto the support
  int settle_steps = 0;  ///< time steps of the settling (0 when free)
  bool settled = true;   ///< the settling reached settle_speed_mm_s
  double settle_seconds = 0.0;
  /// Per stitch: the largest principal Cauchy stress of its triangles (kPa),
  /// and its largest course and wale strains.
  std::vector<double> stitch_stress_kpa;
  std::vector<double> stitch_course_strain;
  std::vector<double> stitch_wale_strain;
  int num_elements = 0;
};

/// The iteration budget of the equilibrium solve: at most `newton_iterations`
/// Newton iterations (> 0) after at most kQuasiNewtonPerNewton times as many
/// L-BFGS iterations (the default: 500 and 10 000).
void set_predict_iterations(PredictOptions& options, int newton_iterations);

/// \throw InvalidInput for an empty mesh, bad params or options, gravity
///        without a support, a piece that cannot be lifted clear of the
///        support within 10 times its size; TopologyError for bad stitches;
///        SolverError when the energy becomes non-finite.
PredictResult predict_shape(const StitchMesh& designed, const KnitParams& params, const KinematicBody* support,
                            const PredictOptions& options = {});

/// The 3-2-1 coordinates of a free piece at positions x (3n): flags per
/// coordinate (see the file comment).
std::vector<char> free_body_constraints(const Eigen::VectorXd& x);

/// How far (mm, >= 0) the points x (3n) must move along +z so that each is
/// on the outer side of `body` (the side of the closest face's normal) and
/// at least `gap_mm` from it. \throw InvalidInput when no lift up to
/// `max_lift_mm` does.
double lift_clear_of_body(const KinematicBody& body, const Eigen::VectorXd& x, double gap_mm, double max_lift_mm);

}  // namespace knitforge
