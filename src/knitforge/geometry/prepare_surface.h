#pragma once
/// \file prepare_surface.h
/// The repair-free clean-up a design route makes before it works on an
/// input surface, for what mesh exports commonly carry and what does not
/// change the surface:
///
///  - vertices used by no face are dropped (exports often keep them; they
///    would otherwise enter bounding boxes, fields and statistics);
///  - vertices at exactly the same position that share no face are welded
///    into one (exports split vertices along texture or normal seams, which
///    would make the surface fall apart into pieces along them), unless
///    welding makes the surface invalid (more validate_surface() errors,
///    e.g. two sheets that only touch): then nothing is welded. Vertices at
///    one position that share a face (a zero-length edge) are not a split
///    and stay.
///
/// Everything else is kept as it is: degenerate faces and slivers stay (the
/// routes handle them), errors stay for validation to report. Vertex order
/// is kept (the first vertex of a welded group stands for it), face order
/// is kept. Deterministic.

#include <vector>

#include "knitforge/geometry/tri_mesh.h"

namespace knitforge {

/// The cleaned surface and how it relates to the input.
struct PreparedSurface {
  TriMesh mesh;
  /// For every input vertex, its vertex in `mesh`, or -1 when it was used by
  /// no face.
  std::vector<int> vertex_map;
  int unused_vertices = 0;  ///< input vertices dropped as unused
  int welded_vertices = 0;  ///< input vertices merged into an earlier one
};

/// Cleans `mesh` (see the file comment). Never throws for any mesh content:
/// faces with out-of-range indices are kept as they are (for validation to
/// report), and their vertices count as used.
PreparedSurface prepare_surface(const TriMesh& mesh);

}  // namespace knitforge
