#pragma once
/// \file tube_short_rows.h
/// Short rows inside a tube where the surface bends (issue #15 item 2, an
/// elbow or a heel; docs/tubes.md "Short rows in a bend").
///
///  1. Where: the spacing table (tube_spacing.h) with the seam (left fold) on
///     the inside line, so that the outside of the bend is at the right fold,
///     far from line 0 (an open row of a tubular map may not cross it).
///  2. Full rounds spaced by the SMALLEST distance between levels (the inside
///     line): K = round(inside(1) / sh) rounds at inside(u) = k inside(1) / K;
///     their wales as the plain route (round_wales()).
///  3. Wedges: before round row k (k >= 1) the wales whose surface distance
///     since the start rim exceeds the rows knitted there by at least one
///     stitch height get a wedge of short rows: depth d = floor((excess + 1)
///     / 2) turning pairs (two rows each), the arc of depth >= t the run of
///     wales round the deepest one (at least 2 wales wide, never the first or
///     last wale of the round: no short row covers the round), each arc strictly
///     inside the one before (a wale holds one turn pair at most; what does
///     not fit waits for the next rounds). A wedge of m nested
///     arcs [l_t, r_t] knits, from the column where the round before ended
///     (r_in): < [l_1, r_in], then > [l_t, r_t+1], < [l_t+1, r_t+1] for t < m,
///     and > [l_m, r_1]; the next round goes on from r_1 + 1 (its seam). Every
///     wale of arc t but the edges gets 2 t rows; as a sock heel is knitted
///     (docs/tubes.md "Rules": the first short row turns back where the round
///     ended, the last ends where the next round starts).
///  4. The knitting map of rounds and wedges, its stitch mesh topology
///     (map_to_stitch_mesh_topology()), and the positions: the corner of a
///     wale after t of the T stitches it gets between full rounds k and k + 1
///     lies on the level u_k + (u_k+1 - u_k) t / T, at the wale's place round
///     the round (its fraction of arc length, as sample_round()); a vertex
///     is the mean of its map grid corners, each the mean of the two wales
///     beside it.
/// Deterministic.

#include <vector>

#include "knitforge/core/knit_params.h"
#include "knitforge/core/knitting_map.h"
#include "knitforge/core/stitch_mesh.h"
#include "knitforge/design/tube/tessellate_rounds.h"
#include "knitforge/design/tube/tube_field.h"
#include "knitforge/design/tube/tube_spacing.h"
#include "knitforge/geometry/tri_mesh.h"

namespace knitforge {

/// Options of tube_short_rows().
struct TubeShortRowOptions {
  KnitParams params;
  int table_levels = 256;  ///< rounds of the spacing table
  int table_fractions = 128;  ///< places round each table round
  /// A closed tube (tube_crown.h): the halves of the full rounds kept equal
  /// (round_wales() with equal_halves), so that the closing seam can pair them.
  bool equal_halves = false;
  /// Where the seam (the left fold) may start on the start rim. Empty: on
  /// the inside line of the bend (see the file comment). Otherwise: at the
  /// one of these points (projected onto the start rim) from which the
  /// outside line lies nearest three quarters of the way round (the middle
  /// of the back half): the wedges there stay away from the seam, which no
  /// open row may cross, and a wedge's first short row, from the seam back
  /// to the wedge, stays short (a closed tube's crown segment ends,
  /// design_tube.h).
  std::vector<Vec3> seam_choices;
};

/// A tube with short-row wedges.
struct TubeShortRows {
  TubeSpacing spacing;             ///< the table, started on the inside line
  std::vector<double> levels;      ///< u of the full rounds 0..K
  std::vector<RoundCurve> rounds;  ///< the full rounds
  RoundWales wales;                ///< live wales of the full rounds
  KnittingMap plan;                ///< rounds and wedges as planned
  StitchMesh mesh;                 ///< topology of `plan`, positioned on the surface
  int wedges = 0, short_rows = 0, turns = 0;  ///< turns: between two short rows of a wedge
};

/// Plans and builds the tube with short rows (see the file comment).
/// `wedges` = 0 means no place needs one (a straight tube): the caller then
/// knits plain rounds.
/// \throw InvalidInput as tube_round_curves(), round_wales(), and
///        map_to_stitch_mesh_topology() (a wedge the map cannot hold).
TubeShortRows tube_short_rows(const TriMesh& mesh, const TubeField& field, const TubeShortRowOptions& options);

}  // namespace knitforge
