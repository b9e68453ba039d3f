#pragma once
/// \file shape_error.h
/// Shape error of a rest shape (a relaxed or simulated copy of a designed
/// stitch mesh, same vertices) against the target surface the design was
/// made for: rigid alignment (the correspondence fit rest -> designed
/// vertices by rigid_align(), then optionally ICP onto the target), then the
/// distance of every aligned vertex to the target, its RMS and max in mm and
/// relative to the size of the part (the bounding-box diagonal of the
/// target's vertices). Shared by evaluate_stitch_mesh() (the Shape-Up rest
/// shape) and the simulator's predicted shape (knitforge predict).

#include <span>
#include <vector>

#include "knitforge/core/stitch_mesh.h"
#include "knitforge/evaluate/rigid_align.h"
#include "knitforge/evaluate/surface_distance.h"
#include "knitforge/geometry/tri_mesh.h"

namespace knitforge {

struct ShapeError {
  std::vector<Vec3> aligned;   ///< the rest vertices after `alignment`
  RigidTransform alignment;
  int icp_iterations = 0;
  bool icp_converged = false;  ///< ICP reached its tolerance (false without ICP)
  /// RMS distance between corresponding designed and aligned rest vertices (mm).
  double correspondence_rms = 0.0;
  double target_size = 0.0;  ///< bounding-box diagonal of the target (mm)
  double rms_error = 0.0, max_error = 0.0;                    ///< aligned rest vertices to the target (mm)
  double relative_rms_error = 0.0, relative_max_error = 0.0;  ///< ... / target_size
  double designed_rms_error = 0.0, designed_max_error = 0.0;  ///< designed vertices as given (mm)
  std::vector<double> vertex_error;  ///< per rest vertex (mm)
  std::vector<double> stitch_error;  ///< per stitch: mean of its corners' vertex_error (mm)
};

/// \pre rest has designed.num_vertices() points.
/// \throw InvalidInput for mismatched sizes, no points, non-finite points;
///        as SurfaceBvh for a bad target.
ShapeError shape_error_to_target(std::span<const Vec3> rest, const StitchMesh& designed, const TriMesh& target,
                                 const SurfaceBvh& target_tree, bool refine_with_icp, const IcpOptions& icp = {});

}  // namespace knitforge
