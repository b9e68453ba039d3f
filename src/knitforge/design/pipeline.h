#pragma once
/// \file pipeline.h
/// The design routes of knitforge, stage by stage (read this first).
///
/// Every stage is a free function with plain data in and out, so a caller can
/// stop after any stage, write the intermediate result, and resume
/// (ARCHITECTURE.md, "The data flow").
///
/// ## Short-row route (seed §3.2) — design/shortrow/
///
///   TriMesh surface (mm), GeodesicSource (geometry/geodesic_source.h)
///   0. cut_to_disk()                 geometry/cut_to_disk.h         seams, when the surface is not a disk
///   1. geodesic_distance()           geometry/geodesic_distance.h   governing field F
///   2. compute_wale_curves()         shortrow/wale_curves.h         isocurves every sw, closed ones cut
///   3. tessellate_wales()            shortrow/tessellate_wales.h    strips, tessellate_strip() + apex diffusion
///   4. boundary_apex_quads()         shortrow/boundary_apex_quads.h boundary-apex triangles -> quads
///   5. order_courses()               shortrow/order_courses.h       courses, greedy order, support stitches
///   6. stitch_mesh_to_map()          convert/stitch_mesh_to_map.h   the knitting map (Alg. 1.1)
///      check_knittability()          core/knittability.h, convert/map_knittability.h
///   7. evaluate_stitch_mesh()        evaluate/evaluate_stitch_mesh.h
///   All in one: design_short_rows()  shortrow/design_short_rows.h   (CLI: knitforge shortrow)
///
/// ## Flattening with darts (seed ch. 2) — design/flatten/
///
///   TriMesh surface (mm), darts (DartSpec, flatten/dart.h; JSON in flatten/dart_json.h)
///   0. cut_to_disk()                 geometry/cut_to_disk.h         seams, when the surface is not a disk (CLI)
///   1. cut_darts()                   flatten/dart.h                 split + cut along the dart paths
///   2. flatten_surface()             flatten/flatten_surface.h      Tutte start, ARAP with notch constraints
///      flattening_distortion()       flatten/flattening_distortion.h per-triangle singular values
///      add_darts_automatically()     flatten/dart_hints.h           where darts help most
///   3. knit_flattened_pattern()      flatten/knit_flattened_pattern.h rasterise, check, lift, evaluate
///                                                                   (CLI: knitforge flatten)
///
/// ## After any route
///
///   stitch_mesh_to_yarn()            convert/stitch_mesh_to_yarn.h  the yarn model
///   write_knitout()                  machine/knitout_writer.h       the machine program (CLI: knitout)
///   yarn_tubes(), vector_drawing(), rasterize()  render/           pictures (CLI: render)
///   write_report_html()              report/report_html.h               report.html (CLI: report)

#include "knitforge/design/flatten/flatten_surface.h"
#include "knitforge/design/flatten/knit_flattened_pattern.h"
#include "knitforge/design/shortrow/design_short_rows.h"
