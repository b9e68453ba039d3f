#include "knitforge/design/tube/design_tube.h"

#include <algorithm>

#include <fmt/format.h>

#include "knitforge/convert/map_knittability.h"
#include "knitforge/convert/stitch_mesh_to_map.h"
#include "knitforge/design/tube/tube_crown.h"
#include "knitforge/geometry/mesh_measures.h"
#include "knitforge/geometry/surface_checks.h"
#include "knitforge/util/errors.h"
#include "knitforge/util/timer.h"

namespace knitforge {

TubeDesign design_tube(const TriMesh& surface0, const TubeDesignOptions& options) {
  auto begin = [&](const char* stage) {
    if (options.progress) options.progress(stage);
  };
  Timer all, t;
  TubeDesign d;
  begin("tube field");
  // One boundary loop: a closed tube, knitted to its crown (tube_crown.h).
  const bool closed_end = validate_surface(surface0).num_boundary_loops == 1;
  if (closed_end) {
    if (options.crown_stitches < 8 || options.crown_stitches > 64)
      throw InvalidInput(fmt::format("closed tube: the crown round must have 8..64 stitches, got {}",
                                     options.crown_stitches));
    TubeCrown crown = cut_crown(surface0, options.crown_stitches * options.params.stitch_width, options.surface_name);
    d.cut_surface = std::move(crown.annulus);
    d.crown_radius = crown.cap_radius;
    d.crown_area = crown.cap_area;
    d.rim_to_crown = crown.rim_to_crown;
  }
  const TriMesh& surface = closed_end ? d.cut_surface : surface0;
  d.field = tube_field(surface, options.surface_name);
  {
    DivergenceOptions dv;
    dv.along_gradient = true;
    d.divergence = divergence_metric(surface, d.field.value, dv);
  }
  d.surface_area = total_area(surface0);
  d.seconds.field = t.seconds();

  begin("rounds");
  t.reset();
  TubeShortRows sr;
  if (options.short_rows) {
    TubeShortRowOptions so;
    so.params = options.params;
    so.equal_halves = closed_end;
    sr = tube_short_rows(surface, d.field, so);
  }
  const bool wedges = sr.wedges > 0;
  if (!wedges) {
    d.levels = round_levels(surface, d.field, options.params.stitch_height);
    d.rounds = tube_round_curves(surface, d.field, d.levels.levels);
  } else {
    d.levels.levels = sr.levels;
    for (const auto& a : sr.spacing.along) d.levels.mean_length += a.back() / static_cast<double>(sr.spacing.along.size());
    d.rounds = sr.rounds;
  }
  d.seconds.rounds = t.seconds();

  begin("tessellation");
  t.reset();
  if (!wedges) {
    RoundsTessellation tess = tessellate_rounds(d.rounds, options.params, closed_end);
    d.stitch_mesh = std::move(tess.mesh);
    d.round_stitches = std::move(tess.stitches);
    d.ideal_stitches = std::move(tess.ideal);
    d.increases = tess.increases;
    d.decreases = tess.decreases;
  } else {
    d.stitch_mesh = std::move(sr.mesh);
    d.round_stitches = sr.wales.stitches;
    d.ideal_stitches = sr.wales.ideal;
    d.increases = sr.wales.increases;
    d.decreases = sr.wales.decreases;
    d.wedges = sr.wedges;
    d.short_rows = sr.short_rows;
    d.turns = sr.turns;
  }
  if (closed_end) {
    // the last round: joined across the beds by the closing seam
    int last = 0;
    for (const Stitch& st : d.stitch_mesh.stitches) last = std::max(last, st.course);
    for (Stitch& st : d.stitch_mesh.stitches)
      if (st.course == last) st.roles |= kRoleClosingSeam;
  }
  const TubeSpacing spacing = options.short_rows ? std::move(sr.spacing) : tube_spacing(surface, d.field, 256, 128);
  d.bend_ratio = spacing.ratio;
  d.course_spacing = measure_course_spacing(d.stitch_mesh, spacing, options.params.stitch_width,
                                            options.params.stitch_height);
  d.seconds.tessellation = t.seconds();

  begin("knitting map");
  t.reset();
  try {
    d.map = stitch_mesh_to_map(d.stitch_mesh);
  } catch (const InvalidInput& e) {
    throw InvalidInput(fmt::format("tube design: the stitch mesh cannot be laid out as a knitting map: {}", e.what()));
  }
  d.seconds.map = t.seconds();

  begin("knittability");
  t.reset();
  KnittabilityOptions closed;
  closed.closed_courses = true;
  d.mesh_check = check_knittability(d.stitch_mesh, closed);
  d.map_check = check_knittability(d.map, options.params);
  d.seconds.check = t.seconds();
  d.seconds.total = all.seconds();
  return d;
}

}  // namespace knitforge
