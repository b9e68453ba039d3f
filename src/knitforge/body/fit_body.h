#pragma once
/// \file fit_body.h
/// Fitting a body model to a scan (seed §5.2.1, eq. 5.1) or to a partial
/// point cloud (§5.3, eq. 5.4) by Gauss-Newton with Levenberg-Marquardt
/// damping on point-to-plane distances, with exact Jacobians
/// (body_jacobian.h). The seed minimises the same objectives with a
/// gradient-free (1+1) evolution strategy (about a minute); the Jacobians
/// make a few dozen linear solves of N = 3 + 3J + K unknowns enough.
///
///  - TemplateToScan (eq. 5.1): Θ = argmin Σ_{v_i ∈ S(Θ)} w_i d²(v_i, M):
///    every model vertex to the scan surface M (a BVH on the static scan,
///    built once); w_i = the vertex's mixed Voronoi area on the template
///    divided by the total, 0 on the head, hands and feet (the model's
///    part labels; all 1 when it has none).
///  - ScanToTemplate (eq. 5.4): Θ = argmin Σ_{p_i ∈ C} d²(p_i, S(Θ)):
///    every cloud point to the posed model's surface (w_i = 1 / n; parts of
///    the body the camera did not see cost nothing). The BVH of the posed
///    model is rebuilt each iteration.
///
/// d is linearised as the distance to the tangent plane of the closest
/// point (point-to-plane ICP), so the correspondences are recomputed every
/// iteration; pairs farther than `max_distance_mm` are ignored (trimming
/// outliers and unseen parts). Weak priors keep the problem well posed
/// where the data says nothing (the rotations of unweighted parts, shape
/// directions a partial view does not see): `pose_prior` per rad² of
/// rotation away from the initial pose, `shape_prior` per mm² of shape
/// parameter away from the initial shape.
///
/// Deterministic. Cost per iteration: one closest-point query per residual
/// (O(log F)) and a dense 3V x N Jacobian (V = model vertices).

#include <cstdint>
#include <optional>
#include <vector>

#include "knitforge/body/body_model.h"
#include "knitforge/body/skin_body.h"
#include "knitforge/geometry/tri_mesh.h"

namespace knitforge {

/// Which distance the fitter minimises (see the file comment).
/// Both: the sum of the two (each normalised to weights summing to 1), the
/// seed's "or both directions" (L1925): the scan's points then also pull
/// the parts eq. 5.1 ignores, which keeps limbs from twisting into a wrong
/// minimum when the initial pose is far.
enum class BodyFitDirection { TemplateToScan, ScanToTemplate, Both };

/// How fit_body() minimises the objective.
///  - GaussNewton: Levenberg-Marquardt on the point-to-plane linearisation
///    (the file comment); the default.
///  - EvolutionStrategy: the seed's gradient-free (1+1) evolution strategy
///    (one_plus_one_es.h) on the same cost, the true squared distances plus
///    the priors; parameters are increments of the initial ones (the
///    apply_increment() layout) with unit steps of 10 mm (translation),
///    0.05 rad (each joint rotation) and, per shape parameter, the change
///    that moves the template's vertices by 10 mm RMS. Kept for comparison
///    (docs/bodies.md measures both on the same fits): it needs thousands of
///    cost evaluations where Gauss-Newton needs tens of linear solves.
enum class BodyFitOptimizer { GaussNewton, EvolutionStrategy };

/// Options of fit_body().
struct BodyFitOptions {
  BodyFitDirection direction = BodyFitDirection::TemplateToScan;
  BodyFitOptimizer optimizer = BodyFitOptimizer::GaussNewton;
  int max_iterations = 40;        ///< Gauss-Newton iterations (>= 1)
  /// EvolutionStrategy: cost evaluations at most (>= 1), and the seed of
  /// its random steps.
  int max_evaluations = 4000;
  std::uint64_t seed = 1;
  double max_distance_mm = 80.0;  ///< pairs farther apart are ignored (> 0)
  /// Stop when an iteration lowers the objective by less than this fraction.
  double relative_tolerance = 1e-5;
  double pose_prior = 1e-2;   ///< weight per rad² (objective in mm²)
  double shape_prior = 1e-6;  ///< weight per (shape unit)² (mm² for our model)
  bool fit_shape = true;      ///< false: pose and translation only
  /// ScanToTemplate: at most this many cloud points are used (an evenly
  /// strided subset, deterministic), bounding the cost.
  int max_cloud_points = 30000;
};

/// Result of fit_body().
struct BodyFitResult {
  BodyParams params;          ///< the fitted parameters
  PosedBody posed;            ///< the fitted body
  double rms_mm = 0.0;        ///< sqrt of the weighted mean squared distance (trimmed pairs)
  double initial_rms_mm = 0.0;
  int iterations = 0;         ///< Gauss-Newton iterations, or ES generations
  int evaluations = 0;        ///< cost evaluations (each poses the body and queries every pair)
  bool converged = false;     ///< the relative tolerance was reached (ES: its step or stall test)
  /// After each accepted Gauss-Newton iteration; for the evolution
  /// strategy only the final rms.
  std::vector<double> rms_history_mm;
  int chosen_run = 0;         ///< fit_body_multistart(): which run won (0, 1, 2)
  /// fit_body_multistart(): the symmetric rms (mm) of each run, in run order.
  std::vector<double> run_rms_mm;
};

/// Fits `model` to `scan`, starting from `initial`. For TemplateToScan the
/// scan must have faces; for ScanToTemplate its vertices are the cloud
/// (faces ignored).
/// \throw InvalidInput for options out of range, an empty scan, a scan
///        without faces for TemplateToScan, non-finite points, or
///        `initial` not matching the model (naming what).
BodyFitResult fit_body(const BodyModel& model, const TriMesh& scan, const BodyParams& initial,
                       const BodyFitOptions& options = {});

/// The rms (mm) of both directions together (eq. 5.1 + 5.4, each with its
/// weights, pairs beyond options.max_distance_mm ignored) at `params`: the
/// criterion fit_body_multistart() compares runs by.
double symmetric_rms_mm(const BodyModel& model, const TriMesh& scan, const BodyParams& params,
                        const BodyFitOptions& options = {});

/// Shape parameters whose stature, chest, waist and hip girths are the
/// scan's own, measured as measure_body() does on the model but without
/// landmarks: stature the scan's height (it stands upright, z up), each
/// girth the convex-hull perimeter of the horizontal section loop round
/// the scan's vertical centre line, at the landmark's height as a fraction
/// of the stature on the model's rest body; each clamped to 0.55-1.55 x the
/// template's value. A starting shape for a fit, not a measurement (arms
/// touching the torso, a bent posture bias it). std::nullopt when the model
/// cannot be driven by measurements (a loaded SMPL-format model) or a
/// section misses the scan.
std::optional<Eigen::VectorXd> shape_from_scan_girths(const BodyModel& model, const TriMesh& scan);

/// Up to four fits, the one with the lowest symmetric_rms_mm() returned (its
/// rms_mm and initial_rms_mm are then symmetric ones, iterations the sum):
/// 0: eq. 5.1 from `initial`; 1: both directions from run 0's result;
/// 2: both directions from `initial`; when the model allows it, 3: eq. 5.1
/// from `initial` with the shape of shape_from_scan_girths(), placed on the
/// scan (place_on_scan()), and 4: both directions from run 3's result. Each objective alone has
/// cases where it settles in a wrong minimum from a far initial pose (eq.
/// 5.1: a forearm whose hand has no weight twists about its axis; both: an
/// arm stretches to the scan's hand), which the other run avoids; a body
/// much wider than the initial shape puts the initial arms inside its torso,
/// where every run from `initial` keeps them (run 3 starts wide enough).
/// options.direction is ignored. About five times the cost of one fit.
/// \throw as fit_body().
BodyFitResult fit_body_multistart(const BodyModel& model, const TriMesh& scan, const BodyParams& initial,
                                  const BodyFitOptions& options = {});

/// `params` with the translation that puts the posed body's bounding box
/// on the scan's: centres in x and y, lowest points in z (the scan stands
/// upright, z up, as the model does). The initial guess of `body fit`
/// without keypoints. \throw InvalidInput for an empty scan.
BodyParams place_on_scan(const BodyModel& model, const BodyParams& params, const TriMesh& scan);

/// The part of every scan vertex: that of the fitted body's vertex nearest
/// to the closest point of the fitted surface (the seed's garment regions
/// carried onto the scan, §5.2.1). \throw InvalidInput when the model has
/// no part labels or the posed body is not the model's.
std::vector<BodyPart> scan_vertex_parts(const BodyModel& model, const PosedBody& posed, const TriMesh& scan);

/// Unsigned distance (mm) of every vertex of `body` to `scan`'s surface
/// (the per-vertex fit error that `body fit` writes).
/// \throw InvalidInput when the scan has no faces.
std::vector<double> vertex_distances_mm(const TriMesh& body, const TriMesh& scan);

}  // namespace knitforge
