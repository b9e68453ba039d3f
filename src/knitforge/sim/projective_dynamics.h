#pragma once
/// \file projective_dynamics.h
/// The fast preview of `cloth` (docs/sim.md, "Preview"): projective dynamics
/// (Bouaziz, Martin, Liu, Kavan and Pauly 2014, "Projective dynamics: fusing
/// constraint projections for fast simulation") on the same SimModel as the
/// implicit solver, with contact and Coulomb friction against the kinematic
/// body as projections. A preview, not the FEM answer: its energy is a
/// quadratic surrogate of the knit material, and it runs a fixed budget of
/// iterations per step.
///
/// **The surrogate.** Every term is w/2 |Σ c_i x_i - p|², a linear
/// combination of vertex positions (coefficients c, summing to 0) pulled
/// towards a projection p of itself:
///  - per membrane element, its course line element a = F e_x and wale line
///    element b = F e_y (F as in MembraneElement) each pulled to the length
///    1 + e, where the tension curve's segment at the step's start strain
///    (slope k, tension T at strain ε) is the spring k (ε - e)², e = ε - T/k:
///    exact on that segment, so the stiffening of a knit at large stretch
///    is kept, one step late; weight k A;
///  - per element, the shear: the pair (a, b) pulled to the nearest pair of
///    perpendicular vectors (closed form, project_perpendicular_pair());
///    weight 2 k_s A (k_s the shear curve's initial slope: the shear
///    stiffening and the course-wale coupling ν_cw are left out);
///  - per hinge, d = Σ α_i x_i with α the affine dependency of the flat rest
///    hinge scaled so that |d| = 2 sin(θ/2) for a fold by θ (Bergou, Wardetzky,
///    Harmon, Zorin and Grinspun 2006, "A quadratic bending model for
///    inextensible surfaces"), pulled to 0: weight 2 k for the hinge energy
///    k θ²; quadratic, no projection;
///  - per vertex near the body, one term per body part it is near: the
///    half-space of the part's tangent plane at the vertex's closest point at
///    the step's start, carried with the body to the step's end and offset by
///    the contact distance d̂; while the vertex is inside, the projection
///    moves it out along the normal by the depth δ and takes back its
///    tangential motion relative to the body up to μ δ (Coulomb: the
///    friction pull never exceeds μ times the normal pull); weight
///    `contact_weight_factor` x the vertex's own diagonal of the system
///    matrix (so the depth at which a pressed vertex balances is of the
///    order of its strain); only the half-spaces the vertex touches at its
///    start carried with the body or at its inertial guess (within 1.5 d̂)
///    are in the matrix.
///
/// **A step** (backward Euler, time step h): the system matrix
/// M/h² + D/h + Σ w c cᵀ (one scalar n_free x n_free matrix for the three
/// coordinates, pins eliminated) is factored once per step (its weights
/// follow the tension segments and the contacts; the symbolic analysis is
/// done once); then up to `max_iterations` rounds of local projections
/// (all cores) and one back-substitution with three right-hand sides, until
/// no vertex moves more than `tolerance_mm` in a round (converged: of the
/// surrogate, not of the FEM energy). Then every vertex still inside a
/// half-space is put on it (alternating projections), and last every
/// vertex keeps only the collision-free fraction of its move
/// (collision_free_step(), as the implicit solver's steps): against a
/// moving body a step whose simultaneous motion of body and fabric is not
/// collision free is split in two halves (body poses and pin targets
/// halfway), up to 8 levels, as the implicit solver splits its steps; so
/// **no vertex ever reaches the body**, and one that was near it at the
/// step's start ends at least d̂ from its tangent planes unless held back.
/// v_{n+1} = (x_{n+1} - x_n) / h.
///
/// **Limits.** The contact term's weight is isotropic (the three
/// coordinates share one scalar matrix), so while a vertex is in contact its
/// tangential motion is also pulled towards the last round's: fabric driven
/// along the body by its tension or its pins slides (the pull is of the
/// stiffness's order), but fabric sliding under its own weight alone creeps
/// (the weight is far below the stiffness): the preview is stickier than
/// Coulomb friction. A vertex farther than the reach (d̂ + twice the body's
/// largest motion in the step + twice its own inertial move + 1 mm) at the
/// step's start gets no half-space (only the collision-free check), and a
/// body's edge or corner may pass between fabric vertices (as for the
/// implicit solver: contact is vertex against body).

#include <array>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "knitforge/geometry/sparse_solver.h"
#include "knitforge/geometry/vec.h"
#include "knitforge/sim/kinematic_body.h"
#include "knitforge/sim/knit_material.h"
#include "knitforge/sim/sim_model.h"
#include "knitforge/sim/sim_state.h"

namespace knitforge {

/// Options of a preview step.
struct PreviewOptions {
  /// Local-global rounds per step at most.
  int max_iterations = 30;
  /// A step has converged (its surrogate) when no vertex moved more than this
  /// in the last round (mm).
  double tolerance_mm = 1e-3;
  /// A contact term's weight, as a multiple of the vertex's diagonal of the
  /// system matrix without contacts.
  double contact_weight_factor = 1.0;
};

/// One term of the surrogate: w/2 |Σ c_i x_i - p|² over up to 4 vertices
/// (unused slots have vertex -1).
struct PreviewRow {
  std::array<int, 4> v{-1, -1, -1, -1};
  std::array<double, 4> c{};
};

/// The rows of a model: 2 per element (course a = F e_x, then wale
/// b = F e_y; rows 2e and 2e + 1), then 1 per hinge.
/// \throw InvalidInput for a hinge whose triangles are not elements of the
///        model or whose rest triangle is degenerate (naming the hinge).
std::vector<PreviewRow> build_preview_rows(const SimModel& model);

/// The spring of a tension curve at `strain`: stiffness k (N/m, the
/// segment's slope) and rest strain e with tension k (strain - e) on that
/// segment.
struct FiberSpring {
  double stiffness_n_per_m = 0.0;
  double rest_strain = 0.0;
};
FiberSpring fiber_spring(const TensionCurve& curve, double strain);

/// The nearest pair (a', b') to (a, b) with a' · b' = 0 (in the sum of
/// squared distances): a' = (a - λ b) / (1 - λ²), b' = (b - λ a) / (1 - λ²),
/// λ the root of (a · b) λ² - (|a|² + |b|²) λ + a · b = 0 with |λ| < 1.
std::pair<Vec3, Vec3> project_perpendicular_pair(const Vec3& a, const Vec3& b);

/// What every preview step of one model reuses: the rows, the matrix pattern
/// over the free (not pinned) vertices with the value index of every entry a
/// row adds to, and the solver's symbolic analysis. Cheap to move, not to
/// copy.
struct PreviewWorkspace {
  /// \pre model outlives the workspace. \throw as build_preview_rows(), and
  ///        InvalidInput for a pinned vertex out of range.
  explicit PreviewWorkspace(const SimModel& model);

  const SimModel* model;
  std::vector<PreviewRow> rows;
  std::vector<char> pinned;       ///< per vertex
  std::vector<int> free_index;    ///< vertex -> row of the reduced system, -1 when pinned
  std::vector<int> free_vertex;   ///< reduced row -> vertex
  SparseMatrix matrix;            ///< lower triangle over the free vertices
  std::vector<int> diagonal_slot; ///< per free vertex, its diagonal's index in matrix's values
  /// Per row, the value index of each coefficient pair (a, b), a <= b over
  /// its 4 slots in the order (0,0), (0,1), ..., (3,3) (-1 when a vertex is
  /// pinned or unused).
  std::vector<std::array<int, 10>> row_slots;
  SparseSolver solver;
};

struct PreviewStepResult {
  SimState state;
  bool converged = false;  ///< the last round moved no vertex more than the tolerance
  int iterations = 0;      ///< local-global rounds
  int contacts = 0;        ///< vertex-part half-spaces in the step
  int held_back = 0;       ///< vertices held back by the collision-free check (a body that stays)
  int substeps = 1;        ///< 1, or more when the body's motion split the step
  double last_move_mm = 0.0;  ///< the largest vertex move of the last round
  double min_distance_mm = 0.0;  ///< smallest free vertex-body distance at the end (+inf: none within the reach)
  double factor_seconds = 0.0, iterate_seconds = 0.0, contact_seconds = 0.0;
};

/// One preview step of length h from `state`: the body is at its t_n pose in
/// `body` and moves to `body_end` (empty = it stays); `pin_targets` holds the
/// end positions of the model's pinned vertices in SimModel::pinned's order
/// (empty = they stay); damping and gravity as in step_simulation().
/// \throw InvalidInput for mismatched sizes or bad options; SolverError when
///        the positions become non-finite, or the body moves through the
///        fabric even in steps split 8 times.
PreviewStepResult preview_step(PreviewWorkspace& ws, const SimState& state, const KinematicBody& body,
                               const std::vector<Vec3>& body_end, const std::vector<Vec3>& pin_targets, double h,
                               const Vec3& gravity_mm_s2, double contact_distance_mm, double friction,
                               const PreviewOptions& options);

}  // namespace knitforge
