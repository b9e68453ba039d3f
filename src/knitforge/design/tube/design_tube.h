#pragma once
/// \file design_tube.h
/// The tube design route (seed §3.3.8, issue #15 item 2; docs/tubes.md,
/// "Design"): a surface with two boundary loops (an annulus) -> a tubular
/// stitch mesh whose courses are closed rounds -> a tubular knitting map.
///
///  1. field: by default the lowest-scoring knittable candidate of
///     tube_field_candidates.h (the harmonic u, 0 on the start rim, the
///     longer one, and 1 on the other, tube_field.h; the Fiedler vector; the
///     field orthogonal to it), scored by the divergence of its normalised
///     gradient, which estimates the shaping (seed §3.3.8); every level is
///     one closed loop;
///  2. rounds: levels one stitch height apart on average (round_levels()),
///     extracted as closed isocurves, oriented and started at the seam
///     (tube_rounds.h); with short rows (the default) on a bent tube: full
///     rounds one stitch height apart on the inside of the bend and wedges
///     of short rows where the outside lies further apart
///     (tube_short_rows.h);
///  3. tessellation: each round sampled at its stitch count, wales traced
///     as column labels with increases and decreases where the count
///     changes (tessellate_rounds.h);
///  4. knitting map (stitch_mesh_to_map(), read as a tube from the wale
///     labels) and both knittability checks (the mesh check with closed
///     courses).
///
/// A tube that needs no wedge (a straight tube), or short_rows = false,
/// is knitted in plain rounds, each once round the whole tube.
///
/// A surface with one boundary loop (a disk: a beanie) is a closed tube:
/// it is cut open along a short geodesic segment at its crown, whose
/// direction lowers the metric and whose length makes the last round the
/// asked size (tube_crown.h); the seam (left fold) is started on the rim
/// below one end of the segment (the end farther from the outside of a
/// bend), so that the last round's halves are the segment's two sides. The
/// annulus left is knitted
/// from the rim to the crown ring as an open tube is (with wedges where it
/// bends: a sock's heel), with the halves of every round kept equal from
/// the first decrease on, and the
/// last round is joined across the beds and bound off (the map's
/// closed_end; docs/tubes.md, "Closed tubes").
/// Deterministic.

#include <functional>
#include <string>
#include <vector>

#include "knitforge/core/knit_params.h"
#include "knitforge/core/knittability.h"
#include "knitforge/core/knitting_map.h"
#include "knitforge/core/stitch_mesh.h"
#include "knitforge/design/shortcolumn/divergence_metric.h"
#include "knitforge/design/tube/tessellate_rounds.h"
#include "knitforge/design/tube/tube_field.h"
#include "knitforge/design/tube/tube_field_candidates.h"
#include "knitforge/design/tube/tube_rounds.h"
#include "knitforge/design/tube/tube_short_rows.h"
#include "knitforge/design/tube/tube_spacing.h"
#include "knitforge/geometry/tri_mesh.h"

namespace knitforge {

/// Options of design_tube().
struct TubeDesignOptions {
  KnitParams params;
  /// Called at the start of every stage with its name (progress reports).
  std::function<void(const std::string&)> progress;
  std::string surface_name = "the surface";  ///< names the surface in messages
  /// Short-row wedges where the rounds lie further apart than on the inside
  /// of a bend (tube_short_rows.h); false: plain rounds, one stitch height
  /// apart on average.
  bool short_rows = true;
  /// A closed tube (a surface with one boundary loop, tube_crown.h): the
  /// stitches of its last round, where the closing seam joins the halves in
  /// pairs (8..64; 12 by default: a 42 mm crown ring at sw 3.5).
  int crown_stitches = 12;
  /// The governing field (tube_field_candidates.h): Auto knits the
  /// lowest-scoring knittable candidate (the harmonic one unless another
  /// scores at least one stitch lower); any other kind is forced.
  TubeFieldKind field = TubeFieldKind::Auto;
  /// A closed tube: directions of the crown segment tried (1..36, CrownOptions).
  int crown_directions = 6;
};

/// Wall-clock seconds per stage.
struct TubeTimings {
  double field = 0, rounds = 0, tessellation = 0, map = 0, check = 0, total = 0;
};

/// Everything the route produces.
struct TubeDesign {
  TubeField field;
  TubeFieldKind field_kind = TubeFieldKind::Harmonic;  ///< the candidate knitted
  std::vector<TubeFieldCandidate> candidates;          ///< harmonic, fiedler, orthogonal
  InitialFields
      initial;  ///< the Fiedler vector and its orthogonal field on the input surface (empty if they failed)
  /// Divergence of the field's normalised gradient on the surface it lives
  /// on (DivergenceOptions::along_gradient, seed §3.3.8): its
  /// transfer_estimate() is an ESTIMATE of increases + decreases.
  DivergenceMetric divergence;
  RoundLevels levels;
  std::vector<RoundCurve> rounds;
  std::vector<int> round_stitches;  ///< per round (RoundsTessellation::stitches)
  std::vector<int> ideal_stitches;  ///< per round (RoundsTessellation::ideal)
  int increases = 0, decreases = 0;
  StitchMesh stitch_mesh;  ///< course = round row, wale = map column
  KnittingMap map;         ///< tubular
  KnittabilityReport mesh_check, map_check;
  double surface_area = 0.0;  ///< mm^2
  int wedges = 0, short_rows = 0, turns = 0;  ///< short-row wedges, their rows and turns
  double bend_ratio = 1.0;  ///< TubeSpacing::ratio: outside over inside rim-to-rim distance
  CourseSpacing course_spacing;  ///< stitch heights / sh along the inside and the outside line
  /// Closed tubes (tube_crown.h; zero otherwise): the cap cut off round the
  /// crown (its geodesic depth, mm, and area, mm^2) and the crown's distance
  /// from the rim (mm). The map has closed_end set.
  double crown_radius = 0, crown_area = 0, rim_to_crown = 0;
  /// Closed tubes: the crown segment (TubeCrown): its length (mm), the crown
  /// ring's length as cut (mm), the direction chosen (degrees) and the
  /// score of every direction tried (stitches, estimate).
  double crown_segment = 0, crown_ring = 0, crown_direction = 0;
  std::vector<double> crown_direction_scores;
  TriMesh cut_surface;  ///< closed tubes: the surface without its crown cap (where `field` lives)
  TubeTimings seconds;
};

/// Runs the route on `surface` (mm).
/// \throw InvalidInput when the surface is not an annulus (tube_field()) or
///        a disk with one crown (cut_crown()), or a round is not one closed
///        loop (no candidate is knittable: the harmonic one's message); when
///        a forced field is not knittable (why); when crown_stitches or
///        crown_directions is out of range; SolverError from the field.
TubeDesign design_tube(const TriMesh& surface, const TubeDesignOptions& options);

}  // namespace knitforge
