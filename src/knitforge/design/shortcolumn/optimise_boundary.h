#pragma once
/// \file optimise_boundary.h
/// The optimisation of seed §3.3.5: the boundary vector b of the harmonic
/// governing field that minimises the divergence metric (eq. 3.6), by TuRBO
/// (turbo_optimize.h) over the feasible set eq. 3.8 with the projection QP
/// eq. 3.9 and the penalty for infeasible suggestions (feasible_set.h), or
/// over the 2D symmetric variant (L1484) for a mirror-symmetric surface.
///
/// Objective: the transfer estimate 3/2 I(f_b) / sw (divergence_metric.h), a
/// number of stitches, so that the seed's penalty exp(|b' - b|^2) (>= 1) is
/// "at least one transfer stitch more". It is evaluated on a proxy: the
/// surface remeshed isotropically to about `proxy_faces` triangles (the
/// metric is resolution-robust, Fig. 3.17; docs/shortcolumn.md measures it),
/// or the surface itself (proxy_faces = 0 or more faces than the surface
/// has). b means the same boundary points on both, since the boundary is
/// parameterised by arc length from the same geometric start
/// (boundary_intervals.h). Each evaluation is one numeric Cholesky
/// factorisation and solve (HarmonicFieldSolver) and one metric.
///
/// Alternatives (Fig. 3.18): the K evaluated feasible points of smallest
/// value that are at least `distinct_distance` apart (circular distance of
/// b, feasible_set.h) — each is the best evaluated point within that radius,
/// i.e. a local-minimum candidate of the evaluated landscape.

#include <functional>
#include <optional>
#include <vector>

#include "knitforge/design/shortcolumn/boundary_intervals.h"
#include "knitforge/design/shortcolumn/turbo_optimize.h"
#include "knitforge/geometry/tri_mesh.h"
#include "knitforge/geometry/vec.h"

namespace knitforge {

/// A mirror plane {x : normal . x = offset}.
struct MirrorPlane {
  Vec3 normal = Vec3::UnitX();
  double offset = 0.0;
};

/// One evaluation in the history.
struct BoundaryEvaluation {
  BoundaryVector suggested{};  ///< what the optimiser asked for (may be infeasible)
  BoundaryVector evaluated{};  ///< the feasible b the field was solved for
  bool projected = false;      ///< eq. 3.9 was applied
  bool initial = false;        ///< part of an initial design
  int region = 0;              ///< trust region
  double metric = 0.0;         ///< I(f) on the proxy (mm), eq. 3.6
  double value = 0.0;          ///< objective: 3/2 I / sw (estimated transfer stitches)
  double penalised = 0.0;      ///< value + exp(|b' - b|^2) when projected
  double best = 0.0;           ///< best value so far
  double trust_length = 0.0;
};

/// Options of optimise_boundary().
struct BoundaryOptimisationOptions {
  double stitch_width = 3.5;  ///< mm, scales the objective (transfer estimate)
  TurboOptions turbo;          ///< budget (max_evaluations, default 100), seed (on_evaluation is not used)
  bool symmetric = false;      ///< optimise the 2D symmetric variant
  /// Mirror plane of the symmetric variant; empty = the better of the planes
  /// x = centre and y = centre of the bounding box (see mirror_plane()).
  std::optional<MirrorPlane> mirror;
  int alternatives = 3;             ///< K best distinct points kept
  double distinct_distance = 0.1;   ///< minimal distance between alternatives (in b)
  int proxy_faces = 3000;           ///< proxy size; 0 = optimise on the surface itself
  /// Called after every evaluation with it and its index (progress).
  std::function<void(const BoundaryEvaluation&, int)> progress;
};

/// Result of optimise_boundary().
struct BoundaryOptimisation {
  BoundaryVector best{};
  double best_value = 0.0;
  std::vector<BoundaryEvaluation> history;
  std::vector<int> alternatives;  ///< indices into history, best first (alternatives[0] = best)
  int regions = 0;
  /// Evaluations whose b the proxy's boundary could not place
  /// (dirichlet_sets() found no vertices for R_e); scored as the worst so far.
  int unplaceable = 0;
  bool symmetric = false;
  MirrorPlane mirror;             ///< when symmetric
  double mirror_error = 0.0;      ///< mean distance of the mirrored boundary to the boundary (mm)
  double mirror_p = 0.0, mirror_gap = 0.0;  ///< the mirror's boundary parameters p and q - p
  int proxy_faces = 0, proxy_vertices = 0;  ///< of the mesh the objective was evaluated on
  double proxy_edge_length = 0.0;           ///< target edge length of the proxy (0 = the surface itself)
  double seconds = 0.0, seconds_proxy = 0.0, seconds_evaluations = 0.0;
};

/// The mirror plane of a surface's boundary among x = centre and y = centre
/// of its bounding box (or `given`), and the mean distance (mm) from the
/// mirrored boundary vertices to the boundary polyline.
/// \throw TopologyError unless the surface has one boundary loop.
MirrorPlane mirror_plane(const TriMesh& surface, double& mean_error, const std::optional<MirrorPlane>& given = {});

/// The surface remeshed to about `faces` triangles (the proxy), or a copy
/// when faces <= 0 or >= the surface's face count.
TriMesh optimisation_proxy(const TriMesh& surface, int faces, double* edge_length = nullptr);

/// Minimises the transfer estimate over b.
/// \throw InvalidInput for bad options; TopologyError unless the surface is
///        a disk; for the symmetric variant, InvalidInput when the surface is
///        not mirror-symmetric within 2 % of its bounding-box diagonal about
///        the plane (the message gives the error) or the plane does not cross
///        the boundary twice.
BoundaryOptimisation optimise_boundary(const TriMesh& surface, const BoundaryOptimisationOptions& options);

/// The K best distinct feasible evaluations (see the file comment).
std::vector<int> distinct_alternatives(const std::vector<BoundaryEvaluation>& history, int k, double distance);

}  // namespace knitforge
