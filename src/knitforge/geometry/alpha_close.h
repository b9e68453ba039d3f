#pragma once
/// \file alpha_close.h
/// Closing a mesh or point set into a watertight surface (seed §2.C.3: "the
/// foot mesh is converted to the sock mesh by computing its alpha shape ...
/// similar to morphological closing, i.e. dilation followed by erosion ... It
/// can be achieved by mesh offsetting"). Implemented with CGAL's 3D alpha
/// wrapping (CGAL::alpha_wrap_3, CGAL >= 5.5): the input is wrapped from the
/// outside by a surface that no ball of radius `alpha` can pass through
/// (gaps narrower than about 2 alpha, such as those between toes, are
/// bridged), at distance `offset` from the input. Unlike the regular facets
/// of an alpha shape (CGAL::Alpha_shape_3), which may be non-manifold, the
/// wrap is guaranteed watertight, 2-manifold and free of self-intersections.
/// The implementation is alpha_wrap_cgal.cpp.
///
/// Open inputs: the wrap of an open surface is a thin closed shell around
/// it (the wrapping ball enters through the holes). To get the solid a sock
/// or a support needs (a foot scan open at the ankle), the boundary loops
/// are first closed by planar fans from their centroids (cap_holes).

#include <vector>

#include "knitforge/geometry/tri_mesh.h"

namespace knitforge {

/// Options of alpha_close(); lengths in mm.
struct AlphaCloseOptions {
  /// Radius of the wrapping ball; 0: automatic, the input's bounding-box
  /// diagonal / 20 (CGAL's suggested default). Smaller: tighter and finer
  /// (and slower); larger: closer to the convex hull.
  double alpha = 0.0;
  /// Distance of the result from the input; 0: automatic, alpha / 30.
  double offset = 0.0;
  /// Close the boundary loops of an open (manifold) input mesh with planar
  /// centroid fans before wrapping, so the result is a solid.
  bool cap_holes = true;
  /// Refuse, before wrapping, when the result would have more triangles
  /// than this: about 2 x area / alpha² (measured on the hemisphere: 104k
  /// triangles at alpha 1 mm in 17 s); the default 2 million is ~5 minutes.
  double max_faces = 2e6;
};

/// A closed surface.
struct AlphaCloseResult {
  /// Closed, 2-manifold, outward-oriented triangle mesh (every edge shared by
  /// exactly two faces); may have several components if the input has
  /// parts farther apart than about 2 alpha.
  TriMesh mesh;
  double alpha = 0.0;    ///< the alpha used (mm)
  double offset = 0.0;   ///< the offset used (mm)
  int capped_holes = 0;  ///< boundary loops of the input closed before wrapping
  double volume = 0.0;   ///< enclosed volume of `mesh` (mm³)
};

/// Wraps `input` (a triangle mesh; or, when it has no faces, the point set
/// of its vertices) into a closed surface (see the file comment).
/// \throw InvalidInput when the estimated result exceeds max_faces (the
///        message gives the estimate and the smallest alpha within the limit);
///        when alpha or offset is negative or not finite, the
///        input has fewer than 4 points (or 1 face), a coordinate is not
///        finite, a face index is out of range, or the input has no extent.
/// \throw SolverError when the wrap is not a closed manifold (not expected
///        from CGAL; reported rather than returned).
AlphaCloseResult alpha_close(const TriMesh& input, const AlphaCloseOptions& options = {});

/// Enclosed (signed) volume of a closed oriented triangle mesh (mm³):
/// positive when the faces point outwards.
double enclosed_volume(const TriMesh& mesh);

}  // namespace knitforge
