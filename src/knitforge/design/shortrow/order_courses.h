#pragma once
/// \file order_courses.h
/// Courses of a short-row stitch mesh and their knitting order (seed §3.2.4),
/// with the second post-processing operator of §3.2.3 (support stitches,
/// Fig. 3.5(b)).
///
/// Courses by flooding: two stitches are in the same course when they share
/// a wale edge (Left/Right sides). The course graph has an edge c -> d when
/// a stitch of c has a Top neighbour in d; it is a DAG for a knittable mesh.
/// The knitting order is a topological order chosen greedily: after course
/// c, the next course is the ready course (all predecessors knitted) whose
/// first stitch is knitted right after the last stitch of c when one is
/// (the yarn goes straight up), otherwise the ready course whose first
/// stitch is nearest (3D distance of stitch centroids) to c's last stitch —
/// the seed's "connect it to the nearest one". Ties go to the smaller course
/// id (smallest stitch index), so the order is deterministic. The first
/// course is the source course with the smallest stitch index among those
/// knitted left to right (or among all when none is).
///
/// Support stitches (§3.2.4 conditions): where the last stitch e of course c
/// is not followed by the first stitch f of the next course d at the
/// boundary, quads are added, never forming a tree in the course graph:
///  - "extend c": e's Top neighbour lies in d but is not f; the stitches of
///    d from f up to it all have an open Bottom side (no other course is
///    connected to d there). c is continued under them, so that its new last
///    stitch lies below f.
///  - "extend d": e has no Top neighbour; f's Bottom neighbour lies in c and
///    the stitches of c from it to e all have an open Top side (c is
///    connected to no other course there). d is started above them, so that
///    its new first stitch lies above e.
/// New corners are translated copies (a support stitch is a parallelogram
/// on the stitch it leans on). Breaks that neither rule can fix are left and
/// reported.
///
/// Output: Stitch::course of every stitch = the position of its course in
/// the knitting order (0 = knitted first); stitch_mesh_to_map() then
/// reproduces this order.

#include <vector>

#include "knitforge/core/stitch_mesh.h"

namespace knitforge {

/// Result of order_courses().
struct CourseOrder {
  int num_courses = 0;
  int support_stitches = 0;  ///< quads added by the second post-processing operator
  int fixed_breaks = 0;      ///< course transitions joined by support stitches
  /// Transitions that stay broken: {last stitch of a course, first stitch of
  /// the next one}.
  std::vector<std::pair<int, int>> breaks;
  /// Course graph edges that go against the order (a cycle): none for a
  /// knittable mesh.
  int cyclic_edges = 0;
};

/// Floods the courses, orders them, adds support stitches and writes the
/// course index of every stitch (in place; support stitches are appended).
/// \throw TopologyError when the mesh is not an oriented manifold;
///        InvalidInput when the stitches of one course disagree on the
///        knitting direction (the message names them).
CourseOrder order_courses(StitchMesh& mesh);

}  // namespace knitforge
