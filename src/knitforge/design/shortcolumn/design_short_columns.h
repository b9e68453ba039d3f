#pragma once
/// \file design_short_columns.h
/// The short-column design route (seed §3.3), stage by stage, for a given
/// governing field (the harmonic field of a boundary vector b, an optimised
/// one (optimise_boundary.h), the Fiedler field, or a user's field):
///
///  1. divergence metric of the field (divergence_metric.h, eq. 3.5/3.6);
///  2. wale curves with short wales, Alg. 3.1-3.3 (column_wales.h);
///  3. tessellation of every strip with Increase / Decrease triangles at the
///     forks (tessellate_columns.h, the §3.2.2 graph);
///  4. post-processing: boundary-apex short-row triangles to quads
///     (boundary_apex_quads.h) and boundary-apex increases / decreases to
///     edge stitches (boundary_shaping_quads.h), then courses by flooding with
///     support stitches on the boundaries (order_courses.h), as §3.3.4 lists;
///  5. knitting map (stitch_mesh_to_map()) and knittability of map and mesh
///     (every rule of §1.2.2, including no neighbouring increases or
///     decreases in a course);
///  6. evaluation (evaluate_stitch_mesh()), optional.
///
/// Deterministic: the same surface, field and options give the same result.

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "knitforge/core/knit_params.h"
#include "knitforge/core/knittability.h"
#include "knitforge/core/knitting_map.h"
#include "knitforge/core/stitch_mesh.h"
#include "knitforge/design/shortcolumn/boundary_shaping_quads.h"
#include "knitforge/design/shortcolumn/column_wales.h"
#include "knitforge/design/shortcolumn/divergence_metric.h"
#include "knitforge/design/shortcolumn/tessellate_columns.h"
#include "knitforge/design/shortrow/boundary_apex_quads.h"
#include "knitforge/design/shortrow/order_courses.h"
#include "knitforge/design/shortrow/tessellate_wales.h"
#include "knitforge/evaluate/evaluate_stitch_mesh.h"
#include "knitforge/geometry/tri_mesh.h"

namespace knitforge {

/// Options of design_short_columns().
struct ShortColumnOptions {
  KnitParams params;
  ColumnWaleOptions wales;
  TessellateWalesOptions tessellation;  ///< lambda, mu (apex diffusion), D unit
  bool evaluate = true;
  EvaluateOptions evaluation;
  /// Called at the start of every stage with its name.
  std::function<void(const std::string&)> progress;
};

/// Wall-clock seconds per stage.
struct ShortColumnTimings {
  double metric = 0, wales = 0, tessellation = 0, post_processing = 0, courses = 0, map = 0, check = 0,
         evaluation = 0, total = 0;
};

/// Stitch counts of a design; transfers = increases + decreases (the
/// seed's measure, L1195).
struct ShortColumnCounts {
  int stitches = 0, knit = 0, short_row_ends = 0, increases = 0, decreases = 0;
  int transfers() const { return increases + decreases; }
};

/// Everything the route produces.
struct ShortColumnDesign {
  std::vector<double> field;  ///< per vertex of the input surface
  DivergenceMetric metric;
  ColumnWales wales;
  StitchMesh stitch_mesh;     ///< the designed stitch mesh (courses set)
  KnittingMap map;
  KnittabilityReport mesh_check;
  KnittabilityReport map_check;
  ShortColumnCounts counts;
  int lambda_growths = 0;
  double max_lambda = 0.0;
  int split_vertices = 0;     ///< bow-tie vertices split (split_touching_vertices())
  BoundaryApexQuadStats boundary_quads;
  BoundaryShapingQuadStats boundary_shaping;  ///< boundary-apex increases / decreases made quads
  CourseOrder courses;
  std::optional<StitchMeshEvaluation> evaluation;
  double surface_area = 0.0;
  ShortColumnTimings seconds;
  bool knittable() const { return mesh_check.ok() && map_check.ok(); }
};

/// Counts of a stitch mesh by type.
ShortColumnCounts count_short_column_stitches(const StitchMesh& mesh);

/// Runs the route on `surface` (mm) with the governing field `field`.
/// \throw InvalidInput / TopologyError / SolverError from the stages, with
///        messages that name the stage and what to change.
ShortColumnDesign design_short_columns(const TriMesh& surface, const std::vector<double>& field,
                                       const ShortColumnOptions& options);

}  // namespace knitforge
