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
/// Support stitches (§3.2.3 Fig. 3.5(b), §3.2.4 conditions), in map space:
/// every stitch sits in the cell (row = position of its course in the order,
/// column = Stitch::wale). Where the last stitch e of course c is not
/// followed by the first stitch f of the next course d, quads are added over
/// as many wales as needed, never forming a tree in the course graph:
///  - d reaches beyond e on the side where c ends: c is continued in its row
///    from e to the cell below f (under d's stitches there, whose Bottom
///    sides must be open);
///  - otherwise d is started in its row from the cell above e (whose Top
///    side must be open) up to f.
/// Every new cell must be free and not crossed by a wale or course that
/// passes it (a collapsed cell), every stitch right below or above it in the
/// map must have an open facing side (it becomes its neighbour), and corners
/// shared with neighbours must agree (no two existing vertices are merged);
/// otherwise the transition is left and reported. New corners are translated
/// copies (a support stitch is a parallelogram on the stitch it leans on).
/// This subsumes the one-stitch "extend c / extend d" rules and also bridges
/// transitions where neither course touches the other (a widening over
/// several wales).
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
