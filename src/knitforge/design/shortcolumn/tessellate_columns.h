#pragma once
/// \file tessellate_columns.h
/// The stitch mesh between the wales of the short-column route (seed §3.3.4,
/// "Wale Mesh Generation"): every ColumnStrip of extract_column_wales() is
/// tessellated by the §3.2.2 graph (tessellate_strip()) in the order the
/// strips were made, with apex diffusion against the short-row ends placed
/// so far; a strip that starts at a fork begins with an Increase (bottom
/// triangle, apex at the fork) and one that ends at a join ends with a
/// Decrease (top triangle) — "the starting and ending elements of
/// short-columns need to be considered specially" (L1422).
///
/// Vertices are the wale samples (ColumnWales::samples); a strip's faces
/// take the samples of its two wales, so strips that share a wale share its
/// vertices. Directions: the course parity of a face is its segments'
/// label parity (ColumnWales::parity), equal on both wales of a strip by
/// construction, so neighbouring strips agree on every shared course.
/// Stitch::wale = the strip's column (the advance that made it), which
/// increases to the right; courses are left to order_courses().

#include <vector>

#include "knitforge/core/knit_params.h"
#include "knitforge/core/stitch_mesh.h"
#include "knitforge/design/shortcolumn/column_wales.h"
#include "knitforge/design/shortrow/tessellate_wales.h"

namespace knitforge {

/// Result of tessellate_columns().
struct ColumnTessellation {
  StitchMesh mesh;                ///< vertices = all samples (unused ones included), courses -1
  std::vector<int> stitch_strip;  ///< per stitch, its strip
  std::vector<Vec3> apexes;       ///< short-row-end apexes placed (mm)
  int increases = 0, decreases = 0;
  int lambda_growths = 0;
  double max_lambda = 0.0;
  double cost = 0.0;
};

/// Tessellates all strips of `wales`.
/// \throw InvalidInput when there is no strip (the message says to use a
///        smaller stitch width) or a strip's wales are invalid;
///        SolverError from tessellate_strip() naming the strip.
ColumnTessellation tessellate_columns(const ColumnWales& wales, const KnitParams& params,
                                      const TessellateWalesOptions& options = {});

}  // namespace knitforge
