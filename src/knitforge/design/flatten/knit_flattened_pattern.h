#pragma once
/// \file knit_flattened_pattern.h
/// The second step of the flattening route (seed §2.3.2): rasterise the
/// flattened pattern into a knitting map (rasterize_pattern()), check its
/// knittability (check_knittability()), place its stitch mesh on the target
/// (lift_map_to_surface(): each stitch corner at its cell's pattern row, so
/// a band's stitches lie where the pattern has them, and a dart's stitches
/// meet on its seam) and evaluate it against the target surface
/// (evaluate_stitch_mesh(): relaxed rest shape, shape error, per-stitch
/// distortion).
#include <optional>
#include "knitforge/convert/map_knittability.h"
#include "knitforge/core/knit_params.h"
#include "knitforge/core/stitch_mesh.h"
#include "knitforge/design/flatten/flatten_surface.h"
#include "knitforge/design/flatten/rasterize_pattern.h"
#include "knitforge/evaluate/evaluate_stitch_mesh.h"

namespace knitforge {

struct KnitPatternOptions {
  RasterizeOptions raster;
  /// Evaluate the stitch mesh against the target (relaxation + alignment,
  /// the most expensive step).
  bool evaluate = true;
  EvaluateOptions evaluation;
};

struct KnitPatternTimings {
  double rasterize = 0.0;
  double check = 0.0;
  double lift = 0.0;
  double evaluate = 0.0;
};

struct KnitPatternResult {
  RasterizedPattern raster;
  KnittabilityReport knittability;
  /// The map's stitch mesh on the target (mm); empty when the map is not
  /// knittable (no stitch mesh to build).
  StitchMesh designed;
  /// Evaluation of `designed` against the target, when knittable and asked for.
  std::optional<StitchMeshEvaluation> evaluation;
  KnitPatternTimings seconds;
};

/// Runs the steps above on a flattening. `target` is the surface the
/// flattening was made from (mm).
/// \throw InvalidInput from rasterize_pattern(); the evaluation's exceptions.
KnitPatternResult knit_flattened_pattern(const Flattening& flattening, const TriMesh& target,
                                         const KnitParams& params, const KnitPatternOptions& options = {});

}  // namespace knitforge
