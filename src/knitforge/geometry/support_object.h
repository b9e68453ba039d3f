#pragma once
/// \file support_object.h
/// A rigid support object for a knitted sample (seed §2.C.2 and §2.C.4):
/// the knitted fabric is pulled over the support, so the support's top is the
/// target surface offset inwards (against its normals) by the fabric
/// thickness; "we add a rectangle as the base. The original shape and the
/// base are connected with a graph-based tessellation" (loop_tessellation.h,
/// seed Fig. 2.12, eq. 2.6), and the base is closed with a planar cap. The
/// result is a watertight, outward-oriented solid ready for slicing (STL).
///
/// Alternatively (shell_thickness > 0) the support is a shell: the offset
/// surface thickened inwards (thicken_surface.h), which saves material.

#include "knitforge/geometry/loop_tessellation.h"
#include "knitforge/geometry/tri_mesh.h"

namespace knitforge {

/// The base loop the surface's boundary is connected to.
enum class SupportBase {
  Projected,  ///< the boundary loop projected onto the base plane (vertical walls)
  Rectangle,  ///< the seed's rectangle: the projected loop's bounding rectangle plus a margin
};

/// Options of support_object(); lengths in mm.
struct SupportOptions {
  /// Inward offset of the surface (the fabric thickness), >= 0.
  double offset = 1.0;
  /// Distance of the base plane below the lowest point of the offset
  /// surface (along `up`), > 0.
  double base_height = 10.0;
  SupportBase base = SupportBase::Projected;
  /// Rectangle base: margin around the projected boundary, >= 0.
  double base_margin = 5.0;
  /// > 0: make a shell of this thickness instead of a solid with a base.
  double shell_thickness = 0.0;
  /// The direction from the base to the surface (normalised internally).
  Vec3 up = Vec3(0.0, 0.0, 1.0);
  /// Objective of the band between the boundary and the base loop.
  LoopTessellationCost cost = LoopTessellationCost::BridgeLength;
};

/// A support object.
struct SupportObject {
  /// Closed, consistently oriented, outward-facing solid: the offset surface
  /// (its vertices first, in input order, unused ones dropped), then the base
  /// loop, then (if any) the centre of the base cap.
  TriMesh solid;
  /// The surface's normals pointed towards the base, so it was reoriented
  /// (faces reversed) first: the support lies on the side opposite to the
  /// normals, towards the base.
  bool reoriented = false;
  /// Faces turned inside out by the offset, plus (shell) those of the
  /// thickening (offset or thickness larger than the local radius of
  /// curvature: the solid self-intersects); 0 for a clean result.
  int flipped_faces = 0;
  /// Triangles and cost of the band between the boundary and the base loop
  /// (0 for a shell).
  int band_triangles = 0;
  double band_cost = 0.0;
};

/// Builds the support object of `surface` (see the file comment).
/// \pre the surface is an oriented manifold; for a solid support it has
///      exactly one boundary loop whose projection along `up` is a simple
///      polygon (Projected base).
/// \throw InvalidInput for a negative offset, non-positive base height,
///        negative margin or shell thickness, a zero `up`, non-finite values,
///        or a surface that is edge-on when seen along `up`.
/// \throw TopologyError when the surface is not an oriented manifold, has no
///        or several boundary loops (solid support), or the projected
///        boundary intersects itself (the message suggests the rectangle base).
SupportObject support_object(const TriMesh& surface, const SupportOptions& options = {});

}  // namespace knitforge
