#pragma once
/// \file design_short_rows.h
/// The short-row design route (seed §3.2), stage by stage:
///
///  0. seams: a surface that is not a disk (several boundary loops, handles)
///     is cut into one (cut_to_disk.h), and the source carried over to it;
///     user cuts (ShortRowOptions::cuts) are made first. A seam between two
///     loops follows the source where a piece of it joins them: the longest
///     such piece for the first seam, so that the wales spread from the
///     source to the seam (cut_to_disk.h, longest_source_seam);
///  1. governing field: geodesic distance from the source (geodesic_distance.h),
///     signed when the source cuts the surface in two;
///  2. wale curves: isocurves every sw, closed ones opened by cuts, sampled at
///     sh (wale_curves.h);
///  3. tessellation of every strip with apex diffusion (tessellate_wales.h);
///  4. post-processing: vertices where stitches of two strips only touch
///     are split (split_nonmanifold_vertices.h), boundary-apex triangles
///     become quads (boundary_apex_quads.h);
///  5. courses by flooding, greedy topological order, support stitches
///     (order_courses.h);
///  6. knitting map (stitch_mesh_to_map()) and knittability of map and mesh;
///  7. evaluation (evaluate_stitch_mesh(): relaxed shape, shape error,
///     per-stitch distortion), optional.
///
/// Deterministic: the same surface, source and options give the same result.

#include <functional>
#include <optional>
#include <string>

#include "knitforge/core/knit_params.h"
#include "knitforge/core/knittability.h"
#include "knitforge/core/knitting_map.h"
#include "knitforge/core/stitch_mesh.h"
#include "knitforge/design/shortrow/boundary_apex_quads.h"
#include "knitforge/design/shortrow/order_courses.h"
#include "knitforge/design/shortrow/tessellate_wales.h"
#include "knitforge/design/shortrow/wale_curves.h"
#include "knitforge/evaluate/apex_spacing.h"
#include "knitforge/evaluate/evaluate_stitch_mesh.h"
#include "knitforge/geometry/cut_to_disk.h"
#include "knitforge/geometry/geodesic_source.h"
#include "knitforge/geometry/tri_mesh.h"

namespace knitforge {

/// Options of design_short_rows().
struct ShortRowOptions {
  KnitParams params;  ///< stitch size (mm)
  /// Accuracy of the governing field, as a fraction of the stitch width:
  /// GeodesicOptions::tolerance = field_tolerance x stitch_width (measured
  /// error at most about that tolerance, docs/geometry.md). The default
  /// 1e-3 is ten times inside the bound (1 % of the stitch width);
  /// 0 computes the exact polyhedral distance.
  double field_tolerance = 1e-3;
  WaleOptions wales;
  TessellateWalesOptions tessellation;  ///< lambda, mu (apex diffusion), D unit
  bool evaluate = true;                 ///< run stage 7
  EvaluateOptions evaluation;
  /// Called at the start of every stage with its name (progress reports).
  std::function<void(const std::string&)> progress;
  /// Cuts (mm, polylines on the surface) made before the seams of stage 0
  /// (cut_to_disk.h, CutToDiskOptions::cuts): a user's own seams.
  std::vector<std::vector<Vec3>> cuts;
  /// Seams between boundary loops follow the source where they can.
  bool seams_on_source = true;
  /// Names the surface in messages (e.g. its file name).
  std::string surface_name = "the surface";
};

/// Wall-clock seconds per stage.
struct ShortRowTimings {
  double seams = 0, field = 0, wales = 0, tessellation = 0, post_processing = 0, courses = 0, map = 0, check = 0,
         evaluation = 0, total = 0;
};

/// Everything the route produces.
struct ShortRowDesign {
  /// The surface designed on: the input, or the disk cut from it (stage 0).
  TriMesh surface;
  /// The source the field was computed from (on `surface`).
  GeodesicSource source;
  /// The seams of stage 0 (none for a disk without cuts) and what they made.
  std::vector<Seam> seams;
  int input_boundary_loops = 1, input_genus = 0;
  bool source_on_seam = false;      ///< CutToDisk::source_on_seam
  int source_seam_candidates = 0;   ///< CutToDisk::source_seam_candidates
  std::vector<double> field;  ///< per vertex of `surface` (mm)
  bool field_signed = false;
  size_t field_windows = 0;
  bool field_approximate = false;  ///< GeodesicField::approximate
  WaleCurves wales;        ///< includes the surface after cuts
  StitchMesh stitch_mesh;  ///< the designed stitch mesh (courses set)
  KnittingMap map;
  KnittabilityReport mesh_check;
  KnittabilityReport map_check;
  /// Tessellation statistics (the mesh itself is moved into stitch_mesh).
  int strips = 0, unpaired_pieces = 0, lambda_growths = 0;
  double max_lambda = 0.0;
  int interior_apexes = 0;  ///< short-row-end pairs placed off the wale ends
  /// Wale samples where stitches of two strips meet at a corner only (no
  /// shared edge), split into one vertex per side in the post-processing
  /// (split_nonmanifold_vertices.h).
  int split_vertices = 0;
  /// How far apart the short-row ends of the final mesh are (what apex
  /// diffusion controls; apex_spacing.h).
  ApexSpacing apex_spacing;
  BoundaryApexQuadStats boundary_quads;
  CourseOrder courses;
  std::optional<StitchMeshEvaluation> evaluation;
  double surface_area = 0.0;  ///< of `surface` (mm^2; the input's)
  ShortRowTimings seconds;
};

/// Runs the route on `surface` (mm, any valid surface of one component)
/// with the field of `source` (on `surface`).
/// \throw InvalidInput / TopologyError / SolverError from the stages, with
///        messages that name the stage and what to change (cut_to_disk()
///        for surfaces that cannot be cut into a disk).
ShortRowDesign design_short_rows(const TriMesh& surface, const GeodesicSource& source,
                                 const ShortRowOptions& options);

}  // namespace knitforge
