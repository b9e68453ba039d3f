#pragma once
/// \file column_wales.h
/// Wale curves of the short-column route (seed §3.3.4, Algorithms 3.1-3.3):
/// wales follow the isocurves of a governing field f (harmonic_field.h),
/// a stitch width apart, with short wales where the isocurves spread.
///
/// ## Fronts (Alg. 3.1)
///
/// The remaining region R starts as the whole surface, its front (the
/// active curve) as the boundary where f is minimal (R_s; a point when b0 =
/// b1). Every step advances the active curve C_a, the whole front or parts
/// of it: the geodesic distance d from C_a is computed in R (exactly,
/// geodesic_distance.h, on a band of R around C_a that provably holds the
/// level d = sw: the band is widened until its artificial border lies beyond
/// d = sw), R is split along the isocurve d = sw (split_mesh_along_path.h)
/// and the part d < sw is removed. Each piece of that isocurve is a new wale
/// (an "arc"); the new front is the old one with the advanced part replaced
/// by the arcs. The seed cuts the mesh too ("Cut the mesh along the isocurve
/// ... Remove the region with d < sw", L1338); when R falls apart, each
/// component continues with its part of the front.
///
/// ## Fronts along the boundary
///
/// Where the front runs closer than sw to the surface boundary (the rim),
/// the isocurve d = sw leaves the surface there and comes back: it falls
/// into several pieces whose ends lie on the rim, and the stretch of rim
/// between two consecutive pieces lies in the removed part d < sw. Each
/// piece on its own would be a wale facing only part of the old front; the
/// old front's samples facing the stretch would go to one of them (a strip
/// whose old side is much longer than the new one: stacked short-row ends)
/// or to none (their stitches, if any, unreachable by the knitting order).
/// Such pieces are joined along the rim (ColumnWaleOptions::
/// join_along_boundary): the front gets one wale across the stretch it
/// removes, running along the rim there, and one strip. Afterwards only the
/// parts of that wale off the rim are front (the region is cut along the
/// pieces only; it usually falls apart at the stretch).
///
/// ## Reference isovalue (Alg. 3.2, 3.3) — our reading
///
/// The reference isocurve of a wale is "the maximal isovalue among all points
/// on its previous wale curve" (L1401): after an advance of the whole front
/// W_k -> W_k+1, tau = max f over W_k. Parts of W_k+1 where f < tau lag
/// behind it and are filled by short wales: while some run of the front
/// with f < tau_step is longer than min_segment_factor x sh
/// (SegmentAcceptable, L1373: length(s) > 2 sh), only those runs advance
/// (several runs advance together, so a symmetric shape stays symmetric;
/// the seed takes one segment and does not say which); then the whole front
/// advances again. tau stays fixed while the gap is filled (Alg. 3.1 line 5
/// read literally would raise it every step, and the lag would never be
/// filled). Alg. 3.3 (refine_reference) lowers the step's reference when the
/// gap is larger than one wale: x* = argmin f over the front, and when the
/// tau-isocurve lies farther than sw from x* (the geodesic disk of radius sw
/// around x* holds no point with f >= tau), tau_step = max f over that disk's
/// boundary; otherwise tau_step = tau. The seed says to call it "between Step
/// 8 and 9 in Algorithm 3.2", which has no such steps; we call it before
/// every UpdateActiveCurve, as SEED-NOTES §1.E suggests.
///
/// ## Samples and strips
///
/// Every front carries stitch samples about sh apart with an even number of
/// segments (seed: "an even number of segments are sampled on each wale
/// curve"); each sample has a course-parity label, consecutive samples
/// alternating. An arc is resampled into an even number m >= 2 (>= 4 for a
/// short wale) of equal segments; where it leaves or rejoins the old front it
/// starts or ends AT an even-indexed sample of the front (the fork): that
/// sample is the apex of the Increase (bottom triangle) that starts the short
/// column, or of the Decrease (top triangle) that ends it. The strip between
/// the old front's samples a_p..a_q and the arc is one ColumnStrip; the front
/// then continues as a_0..a_p, arc, a_q..a_end, so every front keeps an even
/// segment count and the parities agree across every shared wale segment.
/// Arcs that end on the surface boundary are ordinary strip ends. Forks never
/// reuse a sample that is already the apex of an Increase (or joins one of a
/// Decrease), which would put two increases (decreases) side by side in a
/// course (§1.2.2).

#include <vector>

#include "knitforge/core/knit_params.h"
#include "knitforge/geometry/tri_mesh.h"
#include "knitforge/geometry/vec.h"

namespace knitforge {

/// Options of extract_column_wales().
struct ColumnWaleOptions {
  /// SegmentAcceptable: a lagging run must be longer than this many stitch
  /// heights (the seed's 2, L1373).
  double min_segment_factor = 2.0;
  /// Alg. 3.3 (see the file comment).
  bool refine_reference = true;
  /// Accuracy of the distance fields, as a fraction of the stitch width
  /// (GeodesicOptions::tolerance); 0 = exact.
  double distance_tolerance = 1e-3;
  /// Initial band radius around the active curve, in stitch widths (plus two
  /// mean edge lengths); doubled until the band holds d = sw.
  double band_factor = 1.6;
  /// At most this many advances (0 = 4 x area / (sw sh) + 100).
  int max_steps = 0;
  /// A piece of the remaining region smaller than this many stitches
  /// (sw x sh) is left uncovered instead of getting strips of its own (see
  /// ColumnWales::dropped_remnants); 0 keeps every piece.
  double min_region_stitches = 2.0;
  /// Where the front lies along the surface boundary (closer than sw), the
  /// isocurve d = sw leaves the surface and comes back: join its pieces
  /// along the boundary into one wale (see "Fronts along the boundary" in
  /// the file comment).
  bool join_along_boundary = true;
};

/// The strip between an old front's samples (left, A) and a new wale (right,
/// B), both bottom to top; indices into ColumnWales::samples.
struct ColumnStrip {
  std::vector<int> a;
  std::vector<int> b;
  bool start_increase = false;  ///< b[0] == a[0]: a short column starts (Increase apex a[0])
  bool end_decrease = false;    ///< b.back() == a.back(): it ends (Decrease apex)
  int column = 0;               ///< the advance that made it (increasing to the right)
  bool short_wale = false;      ///< B replaced only part of the front (a fill step)
};

/// Result of extract_column_wales().
struct ColumnWales {
  std::vector<Vec3> samples;   ///< stitch-mesh vertices (mm), on the surface
  std::vector<int> parity;     ///< per sample, 0 or 1: the course parity of the segment starting there
  std::vector<ColumnStrip> strips;
  /// The wales as polylines of sample positions (the first front, then every
  /// arc), for wales.obj.
  std::vector<std::vector<Vec3>> wales;
  int steps = 0;           ///< advances (Alg. 3.1 loop iterations with an isocurve)
  int whole_steps = 0;     ///< of which the whole front advanced
  int fill_steps = 0;      ///< of which only lagging runs advanced (short wales)
  int refined_steps = 0;   ///< fill steps whose reference Alg. 3.3 lowered
  int region_splits = 0;   ///< times the remaining region fell into pieces
  int dropped_pieces = 0;  ///< front pieces no region continued (e.g. a pinched-off corner)
  /// Pieces of the remaining region smaller than min_region_stitches left
  /// uncovered (their area is in uncovered_area): a strip of their own would
  /// meet the rest of the fabric at a corner only.
  int dropped_remnants = 0;
  int moved_forks = 0;     ///< forks moved off a sample that already was an apex of that type
  /// Isocurve pieces joined to the previous one along the surface boundary
  /// (ColumnWaleOptions::join_along_boundary).
  int joined_arcs = 0;
  /// Isocurve pieces shorter than sh / 2 that only cut the region (no wale).
  int tiny_arcs = 0;
  /// Regions whose front has no stitch samples (its piece dropped), left
  /// uncovered (their area is in uncovered_area).
  int sampleless_regions = 0;
  int band_growths = 0;    ///< band radius doublings
  int pinched_vertices = 0; ///< vertices split where the remaining region touched itself (split_nonmanifold_vertices.h)
  int last_strips = 0;          ///< regions closed by a last strip to the surface boundary
  double last_strip_area = 0.0; ///< their area (mm^2), less than a stitch width wide
  double uncovered_area = 0.0;  ///< area of R no strip covers (mm^2): islands, slivers too short for a strip
  double surface_area = 0.0;    ///< mm^2
};

/// Runs Alg. 3.1-3.3 on `mesh` (mm) with the governing field `field` (one
/// value per vertex, its minimum on the boundary).
/// \pre mesh is a valid disk (require_disk()).
/// \throw InvalidInput for a field of the wrong size or non-finite values, a
///        minimum of f that is not on the boundary (wales must start there),
///        non-positive stitch sizes, bad options; TopologyError from the
///        mesh operations; SolverError when max_steps is exceeded (the
///        message gives the count).
ColumnWales extract_column_wales(const TriMesh& mesh, const std::vector<double>& field, const KnitParams& params,
                                 const ColumnWaleOptions& options = {});

}  // namespace knitforge
