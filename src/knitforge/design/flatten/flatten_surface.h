#pragma once
/// \file flatten_surface.h
/// Flattening a 3D surface with knittable darts (seed §2.3.1): cut the
/// darts (dart.h), start from Tutte's barycentric embedding, run ARAP
/// (arap_flatten.h) without constraints and turn the pattern into the
/// reference frame (below), then continue ARAP with the notch alignment
/// constraints (same x for horizontal darts, same y for vertical darts) as
/// hard constraints; measure the distortion (flattening_distortion.h) and
/// each dart's angle against the knittability limit.
///
/// The pattern never folds: ARAP has no barrier against flipped triangles
/// (it folds near the tips of darts on strongly curved surfaces), so when
/// its result has one, the pattern is computed instead by slim_flatten()
/// (symmetric Dirichlet energy, injective by construction) from a fold-free
/// start: the unconstrained ARAP pattern when it has no fold, else Tutte's
/// embedding of the surface with the darts closed. When the dart constraints
/// cannot be met without a fold, the dart is rejected (InvalidInput). A
/// pattern ARAP nearly folds (a face beyond max_arap_log_sigma) is
/// recomputed the same way and the one with the lower maximum is kept.
///
/// Reference frame (so that "horizontal" means along the courses): the
/// pattern is rigidly rotated and translated to best fit (least squares) the
/// projection of the 3D vertices onto the plane perpendicular to the mean
/// (area-weighted) normal, with x along the projection of the world x axis
/// (world y if x is nearly parallel to the normal). For the built-in shapes
/// (z up) the pattern's x and y follow the world x and y.
#include <functional>
#include <string>
#include <vector>
#include "knitforge/design/flatten/dart.h"
#include "knitforge/design/flatten/flattening_distortion.h"
#include "knitforge/geometry/arap_flatten.h"
#include "knitforge/geometry/tri_mesh.h"

namespace knitforge {

struct FlattenOptions {
  int max_iterations = 300;  ///< ARAP iterations per phase
  double tolerance = 1e-6;   ///< relative energy change that stops ARAP
  /// Stitch size (mm) for the dart angle limit (dart_angle_limit()).
  double stitch_width = 3.5;
  double stitch_height = 2.8;
  /// Throw when a dart's angle exceeds the limit (the seed: such darts
  /// cannot be knitted closed, they become boundaries sewn afterwards).
  /// false: report it in DartResult::angle_ok only.
  bool enforce_dart_angle = true;
  /// An ARAP pattern with a face stretched or squashed beyond this
  /// (|log σ| > 1.1: a factor of 3) nearly folds; it is recomputed by the
  /// injective solver, whose pattern is kept when its largest |log σ| is lower.
  double max_arap_log_sigma = 1.1;
  /// Without darts, ARAP is abandoned once its pattern has stayed folded for
  /// this many iterations in a row (the fold-free solver then computes the
  /// pattern from Tutte's start, as for any folded ARAP result): ARAP's
  /// remaining iterations would be discarded. A pattern that folds only
  /// for a while and unfolds later is then the fold-free solver's too.
  /// 0: ARAP always runs to convergence.
  int abandon_folded_arap_after = 10;
  /// Told, now and then, which solver runs and its iteration ("ARAP,
  /// iteration 40 of at most 300"): progress for long runs. May be empty.
  std::function<void(const std::string&)> progress;
};

/// A flattened surface.
struct Flattening {
  TriMesh mesh;          ///< the input cut along the darts (3D, mm)
  std::vector<Vec2> uv;  ///< 2D pattern per vertex of `mesh` (mm)
  std::vector<DartResult> darts;
  std::vector<FaceDistortion> distortion;  ///< per face of `mesh`
  DistortionStats stats;
  /// The largest |log σ| at the scale of a stitch: patch_max_abs_log_sigma()
  /// with the stitch width as radius (the maximum the automatic darts lower).
  double stitch_max_abs_log_sigma = 0.0;
  int iterations = 0;  ///< ARAP iterations, both phases (+ SLIM iterations)
  bool converged = false;
  /// ARAP: E / Σ a_f²; with injective_solver: the symmetric Dirichlet energy / (4 x area).
  double relative_energy = 0.0;
  /// Faces the ARAP flattening folded (flipped or degenerate); when > 0 the
  /// pattern is the fold-free SLIM flattening (injective_solver).
  int arap_flipped_faces = 0;
  double arap_max_abs_log_sigma = 0.0;  ///< the largest |log σ| of the ARAP pattern
  /// The pattern is slim_flatten()'s (symmetric Dirichlet energy, no fold by construction).
  bool injective_solver = false;
  /// Faces of `mesh` flipped in the pattern: empty (the flattening never
  /// folds; kept for the callers' checks and reports).
  std::vector<int> flipped_faces;
  double seconds_cut = 0.0;        ///< wall time of cutting the darts
  double seconds_flatten = 0.0;    ///< Tutte + ARAP
};

/// Flattens `mesh` with `darts` (see the file comment).
/// \throw TopologyError when the mesh is not a disk (the message says how to
///        cut it); InvalidInput from cut_darts() naming the dart, when a
///        dart's angle exceeds the limit and enforce_dart_angle is set (the
///        message names the dart, its angle and the limit), or when a dart
///        cannot be flattened without a fold (names the dart); SolverError.
Flattening flatten_surface(const TriMesh& mesh, const std::vector<DartSpec>& darts = {},
                           const FlattenOptions& options = {});

/// The flattening steps of flatten_surface() on darts already cut
/// (cut_darts() / append_dart()); `cut` is consumed.
/// \throw as flatten_surface() (except the disk check).
Flattening flatten_cut(CutDarts cut, const FlattenOptions& options = {});

/// Rigid motion of the 2D positions uv (of mesh's vertices) that best fits
/// the projection described in the file comment.
/// \throw InvalidInput when the sizes differ or the mesh has zero area.
std::vector<Vec2> align_pattern_to_reference(const TriMesh& mesh, const std::vector<Vec2>& uv);

}  // namespace knitforge
