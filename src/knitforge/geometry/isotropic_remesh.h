#pragma once
/// \file isotropic_remesh.h
/// Incremental isotropic remeshing (seed §2.C.2, Algorithm 2.3; Botsch and
/// Kobbelt 2004): repeat split long edges, collapse short edges, equalise
/// valences, tangential relaxation, project to the surface. Built on
/// CGAL::Polygon_mesh_processing::isotropic_remeshing (one iteration per
/// call) with our own projection step after every iteration, so that the
/// surface can be an exact analytic one (e.g. z = f(x, y), seed eq. 2.5, 2.7)
/// and the boundary stays on an exact boundary curve.

#include <functional>
#include <vector>

#include "knitforge/geometry/tri_mesh.h"
#include "knitforge/geometry/vec.h"

namespace knitforge {

/// Maps a point (mm) to a nearby point on a surface or curve (mm).
using PointProjection = std::function<Vec3(const Vec3&)>;

/// Options of isotropic_remesh().
struct RemeshOptions {
  /// Target edge length l (mm), > 0. Edges longer than 4/3 l are split,
  /// shorter than 4/5 l collapsed.
  double target_edge_length = 0.0;
  /// Number of iterations of Algorithm 2.3 (>= 0).
  int iterations = 10;
  /// Tangential relaxation sweeps per iteration (>= 1).
  int relaxation_steps = 1;
  /// Projection of interior vertices onto the exact surface. Empty: the
  /// closest point of the input mesh.
  PointProjection project;
  /// Projection of boundary vertices onto the exact boundary curve(s). Empty:
  /// the closest point of the input mesh's boundary polylines.
  PointProjection project_boundary;
  /// Input vertex indices that keep their position and are never removed
  /// (corners of the boundary, feature points).
  std::vector<int> fixed_vertices;
  /// Boundary vertices of the input where the boundary turns by more than
  /// this angle (degrees) are fixed as well (corners); <= 0 disables this.
  double boundary_corner_angle_deg = 40.0;
};

/// Remeshes `mesh` to edges of about options.target_edge_length (most edges
/// within [0.6 l, 1.5 l] after ~5-10 iterations), keeping its topology
/// (components, boundary loops, genus) and orientation. Boundary vertices
/// stay on the boundary (projected with project_boundary), interior vertices
/// are projected with project after every iteration; vertices the input uses
/// in no face are dropped. Deterministic.
/// \pre mesh passes validate_surface() without errors (any topology).
/// \throw InvalidInput for a non-positive or non-finite target length,
///        negative iterations, a fixed vertex index out of range, or a
///        projection that returns a non-finite point.
/// \throw TopologyError when the input is not a valid surface.
/// \throw SolverError if the result's topology differs from the input's.
TriMesh isotropic_remesh(const TriMesh& mesh, const RemeshOptions& options);

}  // namespace knitforge
