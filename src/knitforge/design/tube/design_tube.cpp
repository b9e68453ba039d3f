#include "knitforge/design/tube/design_tube.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include <fmt/format.h>

#include "knitforge/convert/map_knittability.h"
#include "knitforge/convert/stitch_mesh_to_map.h"
#include "knitforge/design/shortcolumn/harmonic_field.h"
#include "knitforge/design/tube/tube_crown.h"
#include "knitforge/geometry/halfedges.h"
#include "knitforge/geometry/mesh_measures.h"
#include "knitforge/geometry/surface_checks.h"
#include "knitforge/util/errors.h"
#include "knitforge/util/timer.h"

namespace knitforge {

namespace {

// The crown point of an initial field on a disk: its extreme away from the
// rim (the sign whose rim mean lies below its mean over the vertices).
int crown_vertex_of(const TriMesh& disk, const std::vector<double>& f) {
  const Halfedges he = build_halfedges(disk.num_vertices(), disk.faces);
  double rim = 0.0, all = 0.0;
  const std::vector<int> loop = he.boundary_loops().front();
  for (int v : loop) rim += f[static_cast<size_t>(v)] / static_cast<double>(loop.size());
  for (double x : f) all += x / static_cast<double>(f.size());
  const double sign = rim > all ? -1.0 : 1.0;
  int top = 0;
  for (size_t v = 0; v < f.size(); ++v)
    if (sign * f[v] > sign * f[static_cast<size_t>(top)]) top = static_cast<int>(v);
  return top;
}

// The start-rim point under `crown_end`: the round starts chained from the
// crown ring down to the rim (tube_round_curves() on the reversed field).
Vec3 rim_point_below(const TriMesh& annulus, const TubeField& field, const Vec3& crown_end) {
  TubeField down = field;
  std::swap(down.start_loop, down.end_loop);
  for (double& u : down.value) u = 1.0 - u;
  constexpr int kSteps = 64;
  std::vector<double> levels(kSteps + 1);
  for (int k = 0; k <= kSteps; ++k) levels[static_cast<size_t>(k)] = static_cast<double>(k) / kSteps;
  return tube_round_curves(annulus, down, levels, crown_end).back().points.front();
}

}  // namespace

TubeDesign design_tube(const TriMesh& surface0, const TubeDesignOptions& options) {
  auto begin = [&](const char* stage) {
    if (options.progress) options.progress(stage);
  };
  Timer all, t;
  TubeDesign d;
  begin("tube field");
  // One boundary loop: a closed tube, knitted to its crown (tube_crown.h).
  const bool closed_end = validate_surface(surface0).num_boundary_loops == 1;
  if (closed_end && (options.crown_stitches < 8 || options.crown_stitches > 64))
    throw InvalidInput(
        fmt::format("closed tube: the crown round must have 8..64 stitches, got {}", options.crown_stitches));
  if (options.crown_directions < 1 || options.crown_directions > 36)
    throw InvalidInput(fmt::format("closed tube: the crown segment's directions tried must be 1..36, got {}",
                                   options.crown_directions));
  const double sw = options.params.stitch_width;
  DivergenceOptions dv;
  dv.along_gradient = true;
  std::string init_error;
  try {
    d.initial = initial_fields(surface0);
  } catch (const Error& e) {  // not one piece, a solver failure: the harmonic field may still do
    init_error = e.what();
  }
  struct Built {
    TubeField field;
    TubeCrown crown;
  };
  std::vector<std::optional<Built>> built;
  std::vector<double> rim_d;  // closed tubes: the rim distance, once for every candidate's crown
  for (TubeFieldKind kind : {TubeFieldKind::Harmonic, TubeFieldKind::Fiedler, TubeFieldKind::Orthogonal}) {
    TubeFieldCandidate c;
    c.kind = kind;
    const std::vector<double>* init = kind == TubeFieldKind::Fiedler      ? &d.initial.fiedler
                                      : kind == TubeFieldKind::Orthogonal ? &d.initial.orthogonal
                                                                          : nullptr;
    std::optional<Built> b;
    try {
      if (init && init->empty()) throw InvalidInput(fmt::format("no initial field: {}", init_error));
      if (init) c.initial_estimate = divergence_metric(surface0, *init, dv).transfer_estimate(sw);
      if (closed_end) {
        CrownOptions co;
        co.crown_length = options.crown_stitches * sw;
        co.stitch_width = sw;
        co.directions = options.crown_directions;
        if (rim_d.empty()) rim_d = rim_distance(surface0, sw);
        co.rim_distance = rim_d;
        if (init) co.crown_vertex = crown_vertex_of(surface0, *init);
        // The same crown point as an earlier candidate: the same field.
        const Built* same = nullptr;
        for (const auto& e : built)
          if (e && co.crown_vertex && e->crown.crown_vertex == *co.crown_vertex) same = &*e;
        if (same) {
          c.estimate = divergence_metric(same->crown.annulus, same->field.value, dv).transfer_estimate(sw);
          c.knittable = true;
          if (!init) c.initial_estimate = c.estimate;
          Built copy = *same;
          d.candidates.push_back(c);
          built.push_back(std::move(copy));
          continue;
        }
        TubeCrown crown = cut_crown(surface0, co, options.surface_name);
        TubeField f = tube_field(crown.annulus, options.surface_name);
        round_levels(crown.annulus, f, options.params.stitch_height);
        c.estimate = divergence_metric(crown.annulus, f.value, dv).transfer_estimate(sw);
        b = Built{std::move(f), std::move(crown)};
      } else {
        TubeField f = tube_field(surface0, options.surface_name);
        if (init) f = levelled_field(surface0, *init, f);
        round_levels(surface0, f, options.params.stitch_height);
        c.estimate = divergence_metric(surface0, f.value, dv).transfer_estimate(sw);
        b = Built{std::move(f), {}};
      }
      if (!init) c.initial_estimate = c.estimate;
      c.knittable = true;
    } catch (const InvalidInput& e) {
      c.why_not = e.what();
    } catch (const Error& e) {  // an initial field's solver or topology failure leaves the others
      if (!init) throw;
      c.why_not = e.what();
    }
    d.candidates.push_back(c);
    built.push_back(std::move(b));
  }
  int pick = -1;
  if (options.field != TubeFieldKind::Auto) {
    pick = static_cast<int>(options.field) - 1;
    const TubeFieldCandidate& c = d.candidates[static_cast<size_t>(pick)];
    if (!c.knittable)
      throw InvalidInput(
          fmt::format("{}: the {} field cannot be knitted in rounds: {}; try --tube-field auto",
                      options.surface_name, tube_field_name(c.kind), c.why_not));
  } else {
    for (size_t i = 0; i < d.candidates.size(); ++i) {
      const TubeFieldCandidate& c = d.candidates[i];
      if (!c.knittable) continue;
      if (pick < 0 || c.estimate <= d.candidates[static_cast<size_t>(pick)].estimate - 1.0)
        pick = static_cast<int>(i);
    }
    if (pick < 0) throw InvalidInput(d.candidates.front().why_not);
  }
  d.field_kind = d.candidates[static_cast<size_t>(pick)].kind;
  Built& chosen = *built[static_cast<size_t>(pick)];
  d.field = std::move(chosen.field);
  if (closed_end) {
    TubeCrown& crown = chosen.crown;
    d.cut_surface = std::move(crown.annulus);
    d.crown_radius = crown.cap_radius;
    d.crown_area = crown.cap_area;
    d.rim_to_crown = crown.rim_to_crown;
    d.crown_segment = crown.segment_length;
    d.crown_ring = crown.ring_length;
    d.crown_direction = crown.direction_degrees;
    d.crown_direction_scores = crown.direction_scores;
  }
  const TriMesh& surface = closed_end ? d.cut_surface : surface0;
  d.divergence = divergence_metric(surface, d.field.value, dv);
  // A closed tube's seam: on the rim below an end of the crown segment.
  std::vector<Vec3> seam_choices;
  if (closed_end) {
    const TubeCrown& crown = chosen.crown;
    for (const Vec3& end : {crown.segment_start, crown.segment_end})
      seam_choices.push_back(rim_point_below(surface, d.field, end));
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
    so.seam_choices = seam_choices;
    sr = tube_short_rows(surface, d.field, so);
  }
  const bool wedges = sr.wedges > 0;
  if (!wedges) {
    d.levels = round_levels(surface, d.field, options.params.stitch_height);
    d.rounds =
        tube_round_curves(surface, d.field, d.levels.levels,
                          seam_choices.empty() ? std::nullopt : std::optional<Vec3>(seam_choices.front()));
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
