#pragma once
/// \file evaluate_stitch_mesh.h
/// Evaluation of a designed stitch mesh against the target surface it was
/// designed for (issue 3 item 7; seed §3.3 "distortion reduction", §2.A.2):
///
///  1. rest shape: relax_stitch_mesh() from the designed geometry (no z
///     warm-up by default), so every stitch moves toward the ideal shape of
///     its type — what the knitted fabric does;
///  2. rigid alignment of the rest shape to the target: first the
///     correspondence fit relaxed -> designed vertices (rigid_align()), then
///     ICP of the relaxed vertices onto the target surface
///     (align_to_surface()) starting from it;
///  3. shape error: distance of every aligned relaxed vertex to the target
///     surface, its RMS and max in mm and relative to the size of the part,
///     defined as the bounding-box diagonal of the target's vertices;
///  4. per-stitch distortion (stitch_distortion()) of the designed mesh and
///     of the rest shape.
///
/// Works on any stitch mesh StitchAdjacency accepts, from any design route.

#include <vector>

#include "knitforge/convert/relax_stitch_mesh.h"
#include "knitforge/core/knit_params.h"
#include "knitforge/core/stitch_mesh.h"
#include "knitforge/evaluate/rigid_align.h"
#include "knitforge/evaluate/scalar_stats.h"
#include "knitforge/evaluate/stitch_distortion.h"
#include "knitforge/geometry/tri_mesh.h"

namespace knitforge {

struct EvaluateOptions {
  /// Rest-shape relaxation; warm_up is 0 here (start from the designed
  /// geometry as it is), unlike RelaxOptions' own default.
  RelaxOptions relax = [] {
    RelaxOptions r;
    r.warm_up = 0.0;
    return r;
  }();
  /// ICP onto the target after the correspondence fit.
  IcpOptions icp;
  /// false: skip ICP, keep the correspondence fit (relaxed -> designed).
  bool refine_with_icp = true;
};

/// Wall-clock seconds per stage.
struct EvaluateTimings {
  double relax = 0.0;       ///< relax_stitch_mesh()
  double align = 0.0;       ///< correspondence fit + BVH build + ICP
  double distance = 0.0;    ///< final distances of relaxed and designed vertices
  double distortion = 0.0;  ///< per-stitch distortion of both meshes
  double total = 0.0;
};

struct StitchMeshEvaluation {
  /// The rest shape, rigidly aligned to the target (mm).
  StitchMesh relaxed;
  /// The rigid motion applied to relax_stitch_mesh()'s output to get `relaxed`.
  RigidTransform alignment;
  int relax_iterations = 0;
  bool relax_converged = false;
  double relax_energy_start = 0.0;  ///< seed eq. 1.1 energy of the designed mesh (mm^4)
  double relax_energy_end = 0.0;    ///< ... and of the rest shape
  int icp_iterations = 0;
  /// RMS distance between corresponding designed and aligned relaxed
  /// vertices (mm): how far the rest shape moved from the design.
  double correspondence_rms = 0.0;

  /// Size of the part: bounding-box diagonal of the target's vertices (mm).
  double target_size = 0.0;
  /// Shape error: distances of the aligned relaxed vertices to the target
  /// surface (mm), RMS over vertices and max, and both / target_size.
  double rms_error = 0.0;
  double max_error = 0.0;
  double relative_rms_error = 0.0;
  double relative_max_error = 0.0;
  /// The same distances for the designed vertices as given (no alignment):
  /// how well the design itself lies on the target.
  double designed_rms_error = 0.0;
  double designed_max_error = 0.0;

  /// Per vertex of `relaxed` (mm); the RMS and max above are over all
  /// vertices, including any that no stitch uses.
  std::vector<double> vertex_error;
  /// Per stitch: mean of its corners' vertex_error (mm), for face colours.
  std::vector<double> stitch_error;
  ScalarStats stitch_error_stats;

  std::vector<StitchDistortion> designed_distortion;  ///< per stitch, designed geometry
  std::vector<StitchDistortion> relaxed_distortion;   ///< per stitch, rest shape
  ScalarStats designed_distortion_stats;              ///< of the `distortion` values
  ScalarStats relaxed_distortion_stats;

  EvaluateTimings seconds;
};

/// Relaxes `designed`, aligns it to `target` and measures shape error and
/// distortion (see the file comment).
/// \pre designed is a valid stitch mesh (as for relax_stitch_mesh());
///      target a triangle surface in the same units (mm).
/// \throw InvalidInput for an empty stitch mesh, a target without faces, bad
///        params or options, non-finite coordinates; TopologyError for
///        invalid stitches; SolverError if the relaxation fails.
StitchMeshEvaluation evaluate_stitch_mesh(const StitchMesh& designed, const TriMesh& target,
                                          const KnitParams& params, const EvaluateOptions& options = {});

}  // namespace knitforge
