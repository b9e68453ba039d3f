#pragma once
/// \file cut_body_region.h
/// Garment regions cut out of a body or a fitted scan (seed §5.5.1,
/// Fig. 5.16: "regions of the garments are segmented directly" from the
/// template fitted to the scan), as a panel for the design routes
/// (`knitforge shortrow`, `flatten`): one connected, disk-like patch with a
/// clean rim. What `knitforge body region` does.
///
/// The region is the positive side of a smooth scalar field on the surface:
///  - on a body of the model (same topology, any shape and pose): the
///    model's part field (body_model.h, part_fields: positive inside,
///    roughly the distance in mm to the region's boundary in the rest
///    pose), or, for a model without fields, its part labels as +-1
///    smoothed by 8 passes of neighbour averaging;
///  - on a scan: the same field carried from the fitted body, at each scan
///    vertex the barycentric interpolation of the field at its closest point
///    on the fitted body (scan_part_field()). The part labels of `body fit`'s
///    scan_parts.csv are the same carrying with the nearest vertex instead of
///    the interpolation, so they agree with the field's sign except within
///    about one edge of the boundary.
///
/// cut_body_region() then
///  1. removes islands: of the connected sets of vertices with a positive
///     value (joined by edges), only the largest is kept, the others are
///     made negative; and fills holes: of the sets with a value <= 0, the
///     largest and those touching the surface's own boundary are kept, the
///     others are made positive;
///  2. cuts along the zero level (clip_mesh_by_field(): new vertices on the
///     edges at the interpolated zero, vertices closer than 0.2 of an edge
///     snapped onto it), so the rim crosses the triangles smoothly instead of
///     zigzagging along their edges;
///  3. keeps the largest connected component (by faces) once more;
///  4. remeshes the panel isotropically (isotropic_remesh(), the boundary
///     projected onto the cut's polyline, corners sharper than 40° kept), so
///     that no sliver triangle of the cut is left, at the mean edge length
///     of the cut unless told otherwise;
///  5. checks that the result is a disk (one component, one boundary loop,
///     genus 0).
/// Deterministic.

#include <vector>

#include "knitforge/body/body_model.h"
#include "knitforge/geometry/tri_mesh.h"

namespace knitforge {

/// The field of `part` on the model's vertices (see the file comment).
/// \throw InvalidInput when the model has neither part fields nor labels.
std::vector<double> body_part_field(const BodyModel& model, BodyPart part);

/// The field of `part` carried from `fitted` (a posed body of `model`: its
/// vertices in the model's order) onto every vertex of `scan`.
/// \throw InvalidInput when `fitted` does not have the model's vertex count
///        or faces, or as body_part_field().
std::vector<double> scan_part_field(const BodyModel& model, const TriMesh& fitted, const TriMesh& scan,
                                    BodyPart part);

/// Options of cut_body_region().
struct BodyRegionOptions {
  /// Edge length of the remeshed panel (mm); 0: the mean edge length of
  /// the cut region.
  double edge_length_mm = 0.0;
  /// Isotropic remeshing iterations (0: the cut as it is, with its slivers).
  int remesh_iterations = 3;
};

/// Result of cut_body_region().
struct BodyRegion {
  TriMesh mesh;              ///< the panel: a disk
  int islands_removed = 0;   ///< positive vertex sets dropped (step 1)
  int holes_filled = 0;      ///< non-positive vertex sets filled (step 1)
  int snapped_vertices = 0;  ///< vertices moved onto the cut (step 2)
  double area_mm2 = 0.0;
  double boundary_length_mm = 0.0;
  double edge_length_mm = 0.0;  ///< the remeshing target used
};

/// Cuts the region field > 0 out of `surface` (see the file comment).
/// \throw InvalidInput when the field does not match the surface or is
///        nowhere positive, or for options out of range;
///        TopologyError when the region is not a disk after the clean-up
///        (naming its boundary loops and genus).
BodyRegion cut_body_region(const TriMesh& surface, const std::vector<double>& field,
                           const BodyRegionOptions& options = {});

}  // namespace knitforge
