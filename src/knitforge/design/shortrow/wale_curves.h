#pragma once
/// \file wale_curves.h
/// Wale curves of the short-row route (seed §3.2.1): isocurves of the
/// governing field F every stitch width, opened where they close, sampled at
/// the stitch height into an even number of segments.
///
/// Levels: F = k sw for every integer k with min F <= k sw <= max F (so the
/// source itself, F = 0, is a wale when it lies on the surface). Each level
/// may give several open pieces (the isocurve of a disk can fall apart into
/// several arcs, e.g. around a peak); they are kept as separate wales of the
/// same level, ordered as extract_isocurves() returns them.
///
/// Closed isocurves (seed §3.2.1, Fig. 3.2(a)) cannot be wales (topological
/// constraint of §1.2.2). Inside a closed isocurve the field has a local
/// extremum p (a maximum of |F|); the surface is cut along the shortest path
/// from p to the boundary (geodesic_path_to_boundary(), then
/// split_mesh_along_path() and cut_mesh_along_path(), seed §2.B) and the
/// isocurves are extracted again, until no closed one is left. The field is
/// carried over to the cut surface unchanged (it is piecewise linear, so
/// values on the new vertices are exact interpolations): the wales are the
/// same curves, opened at the cut.
///
/// Orientation: every wale runs along n x grad F (isocurves.h), i.e. up in
/// the knitting direction, with larger field values to its right.
///
/// Sampling: an even number of segments of about the stitch height
/// (resample_polyline()). Wales of at least extend_below x sh take the
/// nearest even number of equal segments (each within sh / n of the stitch
/// height, and every sample on the surface); shorter ones have their ends
/// extended when the natural count is odd, as the seed does ("a wale
/// curve's two ends are slightly extended when odd segments are obtained").
/// Extending every odd wale puts up to 3/4 of a segment off the surface at
/// both ends, which over the many short wales of a grazing boundary (the
/// monkey saddle's sides) added about 2 % to the stitch count; squeezing a
/// wale of up to three stitches (L < 3.5 sh) to an even count would stretch
/// or shrink its few segments by 25-50 % instead, and such short pieces next
/// to a cut then lost their partner wale. Pieces shorter than
/// min_length_fraction x sh are dropped and counted (they are slivers where
/// a level grazes the boundary; at most one stitch of area each).
///
/// Saddles on cuts: a cut from a peak to the boundary runs along the field's
/// ridge behind the peak (where the shortest paths from the source meet), and
/// F along it can dip to a saddle. A level at (or within rounding of) the
/// saddle value runs along the cut's lips for a while instead of crossing
/// the cut, breaking into pieces that bound no strip of fabric and cannot be
/// paired (seen on the built-in triple-peak with the source x = 0 at
/// 3 x 2 mm: level 81 mm against a saddle at about 81 mm). A level with a
/// piece lying entirely within cut_hug_fraction x sw plus the mean edge
/// length of the surface of a cut's path (such a piece runs through the
/// faces the cut crosses), or with a closed piece, is therefore moved by +-k/4 x max_level_shift x sw,
/// k = 1..4, smallest shift first, positive before negative, keeping at
/// least sw / 2 to its neighbouring levels; the first shift whose pieces all
/// cross the cuts is kept and recorded in shifted_levels. The wales there
/// are up to max_level_shift x sw closer to or further from their
/// neighbours.

#include <utility>
#include <vector>

#include "knitforge/core/knit_params.h"
#include "knitforge/geometry/tri_mesh.h"
#include "knitforge/geometry/vec.h"

namespace knitforge {

/// Options of compute_wale_curves().
struct WaleOptions {
  /// Pieces shorter than this fraction of the stitch height are dropped.
  double min_length_fraction = 0.5;
  /// A piece lying entirely within this fraction of the stitch width, plus
  /// the mean edge length, of a cut's path runs along the cut (see the file
  /// comment).
  double cut_hug_fraction = 0.25;
  /// Largest shift of a level that runs along a cut, as a fraction of the
  /// stitch width (0 = never shift).
  double max_level_shift = 0.4;
  /// At most this many cuts for closed isocurves before giving up.
  int max_cuts = 64;
  /// Wales shorter than this many stitch heights are extended at their ends
  /// to an even segment count; longer ones use the nearest even count of
  /// equal segments (see the file comment).
  double extend_below = 3.5;
};

/// One wale: an open, sampled isocurve piece.
struct WaleCurve {
  int level = 0;       ///< index into WaleCurves::values
  double value = 0.0;  ///< the field value k sw of the level
  /// Samples (mm), an odd number >= 3 (an even number of segments), running
  /// along n x grad F.
  std::vector<Vec3> points;
  std::vector<Vec3> isocurve;  ///< the isocurve before resampling (mm)
  double length = 0.0;         ///< length of `isocurve` (mm)
  double extension = 0.0;      ///< added at each end when resampling (mm)
};

/// A cut made to open closed isocurves.
struct WaleCut {
  double level_value = 0.0;      ///< field value of the closed isocurve that asked for it
  Vec3 extremum = Vec3::Zero();  ///< the local extremum it starts from (mm)
  std::vector<Vec3> path;        ///< the cut, from the extremum to the boundary (mm)
  double length = 0.0;           ///< mm
};

/// Result of compute_wale_curves().
struct WaleCurves {
  TriMesh surface;             ///< the surface after the cuts (the input when none)
  std::vector<double> field;   ///< F per vertex of `surface`
  std::vector<double> values;  ///< the levels, increasing
  /// wales[l]: the pieces of level l (possibly none), in a deterministic order.
  std::vector<std::vector<WaleCurve>> wales;
  std::vector<WaleCut> cuts;
  int dropped_pieces = 0;  ///< pieces shorter than min_length_fraction x sh
  /// Levels moved off a saddle on a cut: {level index, shift in mm}.
  std::vector<std::pair<int, double>> shifted_levels;
  int num_wales() const;   ///< total number of pieces over all levels
};

/// Extracts, opens and samples the wale curves of `field` on `mesh`.
/// \pre mesh is a disk-like manifold surface (validate_surface /
///      require_disk), field has one finite value per vertex.
/// \throw InvalidInput for a field of the wrong size or non-finite values,
///        non-positive stitch sizes, a field whose range is below one stitch
///        width (no two wales: the message gives the range and the width);
///        TopologyError when a closed isocurve cannot be opened (no boundary
///        reachable, or more than max_cuts cuts needed — the message gives
///        the level and where the loop is).
WaleCurves compute_wale_curves(const TriMesh& mesh, const std::vector<double>& field,
                               const KnitParams& params, const WaleOptions& options = {});

}  // namespace knitforge
