#pragma once
/// \file finish_stitch_mesh.h
/// The stages both 3D design routes (short rows, design_short_rows.h; short
/// columns, design_short_columns.h) end with once their strips are
/// tessellated: bow-tie vertices split, then courses (order_courses.h), the
/// knitting map (stitch_mesh_to_map()) and both knittability checks.

#include <functional>
#include <string>
#include <utility>

#include "knitforge/core/knit_params.h"
#include "knitforge/core/knittability.h"
#include "knitforge/core/knitting_map.h"
#include "knitforge/core/stitch_mesh.h"
#include "knitforge/design/shortrow/order_courses.h"

namespace knitforge {

/// Gives every stitch fan of a bow-tie vertex (two stitches of different
/// strips meeting at one wale sample without sharing an edge) its own copy
/// of the vertex (split_nonmanifold_vertices.h); returns the number of
/// vertices split.
int split_touching_vertices(StitchMesh& mesh);

/// Result of courses_map_and_checks().
struct MapStages {
  CourseOrder courses;
  KnittingMap map;
  KnittabilityReport mesh_check, map_check;
  double seconds_courses = 0.0, seconds_map = 0.0, seconds_check = 0.0;
};

/// Orders the courses of `mesh` (in place), lays it out as a map and checks
/// both; `stage` (may be empty) is called with "courses", "knitting map" and
/// "knittability" as each begins.
/// \throw InvalidInput "<route>: the stitch mesh cannot be laid out as a
///        knitting map: ..." when stitch_mesh_to_map() refuses it.
MapStages courses_map_and_checks(StitchMesh& mesh, const KnitParams& params, const std::string& route,
                                 const std::function<void(const std::string&)>& stage);

/// courses_map_and_checks() on d.stitch_mesh, its results stored in a route's
/// design d (members courses, map, mesh_check, map_check, seconds.courses,
/// seconds.map, seconds.check: ShortRowDesign, ShortColumnDesign).
template <class Design>
void map_stages_into(Design& d, const KnitParams& params, const std::string& route,
                     const std::function<void(const std::string&)>& stage) {
  MapStages m = courses_map_and_checks(d.stitch_mesh, params, route, stage);
  d.courses = std::move(m.courses);
  d.map = std::move(m.map);
  d.mesh_check = std::move(m.mesh_check);
  d.map_check = std::move(m.map_check);
  d.seconds.courses = m.seconds_courses;
  d.seconds.map = m.seconds_map;
  d.seconds.check = m.seconds_check;
}

}  // namespace knitforge
