#pragma once
/// \file simulate_cloth.h
/// A garment on a moving body (docs/sim.md, "Garments on a moving body";
/// seed ch. 4 §4.2-4.3, where the seed ran ARCSim with per-triangle
/// materials and Coulomb friction): backward-Euler steps of
/// step_simulation() while the body moves through its poses, with
/// per-frame measures; or the projective-dynamics preview
/// (ClothOptions::solver).
///
/// Frame f (1..frames) ends at t = f / frame_rate; it is `substeps` steps of
/// h = 1 / (frame_rate substeps), the body moving linearly between its pose
/// of frame f - 1 and that of frame f (vertex by vertex). Pinned vertices
/// (SimModel::pinned) stay where they start, except the `attached` ones,
/// which ride on the body: each keeps its closest body point at the start
/// (face, barycentrics) and its offset from it in that face's frame (first
/// edge, normal x edge, normal), so a rigid motion of the body carries it
/// rigidly.
///
/// Per frame (frame 0 = the start): positions; per element the largest
/// principal Cauchy membrane stress / thickness (kPa, 0 when compressed;
/// membrane_stress()); per vertex the sliding over the body (mm,
/// body_sliding.h); the smallest distance of a free vertex to the body (the
/// barrier with collision-free steps keeps it > 0: the body is never
/// penetrated); elastic, kinetic and gravitational energy (µJ); Newton
/// iterations, whether every solve converged, steps taken (more than
/// `substeps` when the body's motion split a step), contacts, the largest
/// residual force; and the maxima over time per element and vertex.
///
/// Cost: about vertices x frames x substeps x Newton iterations; the CLI
/// refuses more than kMaxClothWork vertex-steps unless told otherwise.

#include <functional>
#include <vector>

#include "knitforge/geometry/tri_mesh.h"
#include "knitforge/sim/contact_energy.h"
#include "knitforge/sim/newton_solve.h"
#include "knitforge/sim/projective_dynamics.h"
#include "knitforge/sim/psd_projection.h"
#include "knitforge/sim/quasi_newton_solve.h"
#include "knitforge/sim/sim_model.h"

namespace knitforge {

/// The default limit on vertices x frames x substeps of one run: about
/// 40 minutes at the rate measured on the 2-core machine (docs/sim.md).
inline constexpr double kMaxClothWork = 5e6;
/// The preview's (ClothSolver::Preview) default limit on vertices x frames
/// x substeps x rounds / 30: about 15 minutes at its measured rate (20 k
/// vertex-steps of 30 rounds a second, docs/benchmarks.md) and 1.6 GB of
/// frames at 2 substeps.
inline constexpr double kMaxPreviewWork = 5e7;

/// How the steps are solved.
///  - Implicit: backward Euler by step_simulation() (FEM energies, barrier
///    contact with collision-free steps, converged to Newton's tolerance).
///  - Preview: projective dynamics (projective_dynamics.h): a quadratic
///    surrogate of the material and contact by projection, a fixed budget
///    of iterations a step; fast, not the FEM answer; the same
///    collision-free steps (split while the body would pass through the
///    fabric), so no vertex reaches the body either.
enum class ClothSolver { Implicit, Preview };

struct ClothOptions {
  ClothSolver solver = ClothSolver::Implicit;
  /// The preview's iterations and tolerance (solver Preview only).
  PreviewOptions preview;
  int frames = 30;
  double frame_rate_hz = 30.0;
  int substeps = 2;
  Vec3 gravity_mm_s2{0.0, 0.0, -9810.0};
  ContactParams contact;
  NewtonOptions newton{20, 1e-2};
  PsdProjection projection = PsdProjection::Clamp;
  /// The L-BFGS phase before each step's Newton solve (StepOptions::
  /// quasi_newton; 0 iterations = off, Newton alone). On the built-in
  /// sleeve (docs/sim.md, "Solver") it reaches Newton's tolerance itself in
  /// every step (Newton confirms it, no factorisation) with ~5
  /// factorisations a step where Newton alone takes ~17 and still stops at
  /// its iteration limit in 26 of 30 frames. A refresh when the last 10
  /// iterations lowered the energy by less than 0.1 of its decrease since
  /// the factor (0.3: ~20 % more factorisations; 0: never refreshed, 5x the
  /// iterations: the barrier's curvature changes within a step).
  QuasiNewtonOptions quasi_newton = [] {
    QuasiNewtonOptions q;
    q.max_iterations = 400;
    q.stall_decrease = 0.1;
    return q;
  }();
  /// A vertex touches the body (for the sliding measure) within this distance (mm).
  double sliding_distance_mm = 1.0;
  /// The closest distance per frame is searched within this range (mm);
  /// farther gives +inf (no vertex near the body).
  double distance_range_mm = 50.0;
};

struct ClothFrame {
  int frame = 0;
  double time_s = 0.0;
  std::vector<Vec3> positions;     ///< garment vertices (mm)
  std::vector<Vec3> body;          ///< body vertices at this frame (mm)
  std::vector<double> stress_kpa;  ///< per element
  std::vector<double> sliding_mm;  ///< per vertex
  int touching = 0;                ///< vertices touching the body (sliding measured)
  double min_distance_mm = 0.0;    ///< smallest free-vertex-to-body distance over the frame's steps
  double elastic_energy_uj = 0.0, kinetic_energy_uj = 0.0, gravity_energy_uj = 0.0;
  int newton_iterations = 0;
  int quasi_newton_iterations = 0;  ///< L-BFGS steps before Newton (StepOptions::quasi_newton)
  int factorizations = 0;           ///< Cholesky factorisations, failed ones included
  int preview_iterations = 0;       ///< local-global rounds (solver Preview)
  double preview_last_move_mm = 0.0;  ///< solver Preview: the largest last-round move of the frame's steps
  bool converged = true;
  int solves_at_iteration_limit = 0;  ///< Newton solves of the frame that hit the iteration limit
  int steps = 0;  ///< backward-Euler steps (substeps, more when split)
  int contacts = 0;
  double max_force_mn = 0.0;  ///< largest residual force of the frame's last solve
  /// Wall seconds. Preview: `factor` = assembly and factorisation,
  /// `evaluate` = the local-global rounds (projections and
  /// back-substitutions), `max_step` = the contact half-spaces and the final
  /// projection; `line_search` unused.
  NewtonTimings seconds;
};

struct ClothResult {
  std::vector<ClothFrame> frames;       ///< frames + 1 (frame 0 = the start)
  std::vector<double> max_stress_kpa;   ///< per element, over time
  std::vector<double> max_sliding_mm;   ///< per vertex, over time
  bool converged = true;                ///< every Newton solve converged (Preview: every step's rounds reached the tolerance)
  int newton_iterations = 0;
  int quasi_newton_iterations = 0;
  int factorizations = 0;
  int preview_iterations = 0;
  int steps = 0;
  double min_distance_mm = 0.0;         ///< over every frame
  NewtonTimings seconds;
  double measure_seconds = 0.0;         ///< stress, sliding and distances
};

/// Runs the garment `model` (pins: SimModel::pinned, a superset of
/// `attached`) against the body `body` (its frame-0 pose) moving through
/// `body_frames` (frames + 1 vertex arrays of body's mesh, or empty: the body
/// stays). `on_frame` (optional) sees every frame as it is made.
/// \throw InvalidInput for bad options, a frame count that does not match,
///        an attached vertex that is not pinned, or a fabric vertex that
///        starts inside the contact distance of the body (give a clearance);
///        SolverError from step_simulation() (the body moves through the
///        fabric, non-finite energy), naming the frame.
ClothResult simulate_cloth(const SimModel& model, const TriMesh& body, const std::vector<std::vector<Vec3>>& body_frames,
                           const std::vector<int>& attached, const ClothOptions& options,
                           const std::function<void(const ClothFrame&)>& on_frame = {});

/// Refuses a run of vertices x frames x substeps above `limit`
/// (check_work()). For the preview, `preview_rounds` > 0 is its rounds a
/// step at most, and the count is scaled by max(1, rounds / 30).
void check_cloth_work(int vertices, int frames, int substeps, double limit = kMaxClothWork, int preview_rounds = 0);

}  // namespace knitforge
