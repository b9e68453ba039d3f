#pragma once
/// \file tessellate_strip.h
/// Knittable tessellation of the strip between two neighbouring wale curves
/// by a shortest path on the graph of anchor bridges (seed §3.2.2), with the
/// apex-diffusion term of §3.2.3.
///
/// ## Conventions
///
/// The two wales are given as sampled polylines running upwards (knitting
/// order, bottom to top): A = a_0..a_{2na} is the LEFT wale, B = b_0..b_{2nb}
/// the RIGHT wale, both in the stitch frame of core/stitch.h (x from A to B,
/// the "left-to-right" knitting direction; y up along the wales; z the
/// surface normal n, towards the viewer). In 3D, x = y cross z = d x n; with
/// the seed's wale direction d = n x grad F this is grad F, so B is the wale
/// with the LARGER field value. For planar input in the xy plane with A at
/// smaller x than B and both running in +y, every output face is
/// counter-clockwise seen from +z.
///
/// Vertex ids of the output faces: a_k -> k, b_l -> a.size() + l.
///
/// A bridge is a segment a_k b_l (a course boundary). An anchor bridge joins
/// even samples a_{2i} b_{2j}; it is written as the node (i, j) below.
/// Faces are stacked bottom to top; the course index of a face within the
/// strip is its position in that stack (0 = bottom). Even courses are knitted
/// left to right (direction +1, from A to B), odd ones right to left (-1).
/// Every operator adds an even number of faces, so each operator starts on an
/// even course (the caller offsets the indices by the strip's first global
/// course, which must be even for the parities to hold).
///
/// ## The operators (edges of the graph Gamma), from node (i, j)
///
/// Q = Knit (BL BR TR TL), R = ShortRowRight (BL A TL), L = ShortRowLeft
/// (A BR TR). Course c is the index of the face within the operator.
///
/// AB-advance, to (i+1, j+1); new bridges a_{2i+1}b_{2j+1}, a_{2i+2}b_{2j+2}:
/// \code
///   a2i+2 ---- b2j+2      c1: Q (a2i+1, b2j+1, b2j+2, a2i+2)   R->L
///     |   Q    |
///   a2i+1 ---- b2j+1      c0: Q (a2i,   b2j,   b2j+1, a2i+1)   L->R
///     |   Q    |
///   a2i ------ b2j
/// \endcode
///
/// A-advance (right-end pair, apex b_{2j}), to (i+1, j); new bridges
/// a_{2i+1}b_{2j}, a_{2i+2}b_{2j}:
/// \code
///   a2i+2 .
///     | R  ` .
///   a2i+1 ---- b2j        c1: R (a2i+1, b2j, a2i+2)  head of a R->L course
///     | R  . `            c0: R (a2i,   b2j, a2i+1)  tail of a L->R course
///   a2i  '
/// \endcode
///
/// B-advance (quad, left-end pair with apex a_{2i+1}, quad), to (i+1, j+2);
/// new bridges a_{2i+1}b_{2j+1}, a_{2i+1}b_{2j+2}, a_{2i+1}b_{2j+3},
/// a_{2i+2}b_{2j+4}. The left-end pair sits on courses 1 (odd, its lower
/// triangle is the tail of a R->L course) and 2 (even, head of a L->R one):
/// \code
///   a2i+2 ------ b2j+4     c3: Q (a2i+1, b2j+3, b2j+4, a2i+2)
///     |     Q    |
///     |   .----- b2j+3     c2: L (a2i+1, b2j+2, b2j+3)
///   a2i+1 ------ b2j+2
///     |   `----- b2j+1     c1: L (a2i+1, b2j+1, b2j+2)
///     |     Q    |         c0: Q (a2i,   b2j,   b2j+1, a2i+1)
///   a2i -------- b2j
/// \endcode
///
/// BB-advance (quad, two left-end pairs at apex a_{2i+1}, quad), to
/// (i+1, j+3); new bridges a_{2i+1}b_{2j+1..2j+5}, a_{2i+2}b_{2j+6}:
/// c0: Q (a2i, b2j, b2j+1, a2i+1); c1..c4: L (a2i+1, b2j+k, b2j+k+1) for
/// k = 1..4; c5: Q (a2i+1, b2j+5, b2j+6, a2i+2).
///
/// B-fan (boundary only, below the source and above the target), to (i, j+1); new bridges a_{2i}b_{2j+1},
/// a_{2i}b_{2j+2}; only where a_{2i} is an end of wale A (i = 0 or i = na):
/// c0: L (a2i, b2j, b2j+1); c1: L (a2i, b2j+1, b2j+2). Its apex lies on the
/// boundary of the patch, so the post-processing of §3.2.3 turns the pair
/// into quads; it is how the part of B that extends beyond the end of A is
/// covered (an A-advance with j = 0 or j = nb does the same for A).
///
/// ## Source, target and the ends
///
/// The source and target nodes are the first and last bijective closest
/// pairs (a_{2i}'s closest even sample of B is b_{2j} and vice versa, ties to
/// the lower index), among the pairs of samples where A and B run the same
/// way (their directions, chords from sample k-2 to k+2 clamped at the ends,
/// have a positive dot product): a wale that folds back next to the other,
/// as the two sides of a cut do, must not pair its returning half, or the
/// whole strip collapses into one fan (when no pair runs the same way, the
/// source is (0, 0)); the target is the last such pair that can be reached
/// from the source (j_t >= j_s and j_t - j_s <= 3 (i_t - i_s)). Between them
/// the graph uses the bridge-length limit lambda; lambda starts at
/// options.lambda (default sw + 2 sh) and grows by 10 % until a path exists.
/// The parts below the source (from node (0, 0)) and above the target (to
/// node (na, nb)) are solved by the same shortest-path search without the
/// lambda limit (bridges near the wale ends may be long; these are boundary
/// regions that the post-processing adjusts), with the B-fan available at the
/// wale ends, so they always have a path: no part of the strip is dropped.
///
/// ## Short columns (seed §3.3.4)
///
/// A strip between a front and a short wale that leaves it (or rejoins it)
/// starts (ends) at one point, a_0 = b_0 (a_2na = b_2nb): the fork. With
/// StripOptions::start_increase the first operator, from (0, 0), must be a
/// fork operator: an AB-, B- or BB-advance whose first quad
/// (a0, b0, b1, a1) becomes the Increase (a0 apex, b1 TR, a1 TL) — Increase
/// to (1, 1), IncreaseB to (1, 2), IncreaseBB to (1, 3). With end_decrease
/// the last operator, into (na, nb), is an AB-, B- or BB-advance whose last
/// quad becomes the Decrease (a2na-1 BL, b2nb-1 BR, a2na apex) — Decrease,
/// DecreaseB, DecreaseBB. With both and na = nb = 1, IncreaseDecrease:
/// Increase (a0, b1, a1), Decrease (a1, b1, a2). A longer A is covered by
/// A-advances after the Increase or before the Decrease: an A-advance's
/// right-end pair must start on an even course (the yarn arrives at the apex
/// going right), which a variant starting with the Increase cannot give.
/// These operators take part in the shortest-path search of the middle part
/// (there is no bottom / top part at a fork end), with the same costs; the
/// course parities work out as for the other operators (every one adds an
/// even number of faces). The vertex id of b_0 (b_2nb) is then not used; the
/// caller gives both the same vertex.
///
/// ## Shortest path
///
/// Every operator moves the node forward in the lexicographic order of
/// (i, j) (all advance i except the B-fan, which advances j), so Gamma is
/// acyclic: the shortest path (the seed's Dijkstra, or the dynamic
/// programming of §2.C.2) is found exactly by one sweep over the reached
/// states in that order. Ties keep the label found first (operators tried in
/// the enum order), so the result is deterministic.
///
/// ## Edge weight and apex diffusion
///
/// weight = L + mu * sum_p exp(-D_p^2): L is the total length (mm) of the new
/// bridges; p runs over the short-row-end pairs the operator adds (one for A
/// and B, two for BB; apexes on a wale end are excluded since they become
/// quads); D_p = (distance in mm from the apex of p to the nearest apex placed
/// so far) / diffusion_length (default sw), so exp(-D^2) is e^-1 one stitch
/// width away. "Placed so far" = options.previous_apexes (earlier strips),
/// the apexes of the parts of this strip solved before (bottom part, then
/// middle), the most recent apex on the current search path, and the earlier
/// pair of the same operator (so BB's second pair always pays mu).
/// Path dependence: the search state is (node, most recent in-strip apex on
/// the path); older apexes of the same path part are not seen by the search
/// (they lie further down the strip). The most recent apex is forgotten once
/// it is farther than 3.5 diffusion lengths from both ends of the current
/// anchor bridge (exp(-3.5^2) < 5e-6, i.e. < 5e-4 sw at mu = 100 sw). After
/// the search, the cost of the chosen
/// path is re-evaluated exactly, with every earlier apex, and reported.

#include <array>
#include <optional>
#include <string>
#include <string_view>
#include <cstdint>
#include <vector>

#include "knitforge/core/stitch.h"
#include "knitforge/geometry/vec.h"

namespace knitforge {

/// The operators of §3.2.2 (plus the boundary fan, see the file comment),
/// and the ends of a short column (seed §3.3.4, see "Short columns").
enum class StripOperator : uint8_t {
  ABAdvance, AAdvance, BAdvance, BBAdvance, BFan,
  Increase, IncreaseB, IncreaseBB, Decrease, DecreaseB, DecreaseBB, IncreaseDecrease
};

/// Options of tessellate_strip(). Lengths in mm.
struct StripOptions {
  double stitch_width = 0.0;   ///< sw > 0 (distance between wales)
  double stitch_height = 0.0;  ///< sh > 0 (sample spacing along wales)
  /// Initial bridge limit; std::nullopt = sw + 2 sh.
  std::optional<double> lambda;
  /// Diffusion weight mu in mm; std::nullopt = 100 sw; 0 turns diffusion off.
  std::optional<double> mu;
  /// Length D is divided by; std::nullopt = sw.
  std::optional<double> diffusion_length;
  /// Maximal number of 10 % growths of lambda before giving up.
  int max_lambda_growths = 200;
  /// Apexes placed while tessellating earlier strips (mm).
  std::vector<Vec3> previous_apexes;
  /// Index of the strip, used in error messages only.
  int strip_index = 0;
  /// The strip starts at a fork a_0 = b_0 with an Increase (see "Short columns").
  bool start_increase = false;
  /// The strip ends at a join a_2na = b_2nb with a Decrease.
  bool end_decrease = false;
  /// Allow the operators with two left-end pairs at one apex (BB-advance,
  /// IncreaseBB, DecreaseBB): their four stacked short-row ends violate the
  /// stacked-short-row-ends rule (knittability.md), so a route that must pass
  /// every rule turns them off; B can then be at most twice as long as A.
  /// Off also refuses two A-advances in a row (they share their apex: the
  /// same four stacked ends), unless the strip has no path without them.
  bool allow_double_advance = true;
};

/// One face of the strip.
struct StripFace {
  StitchType type = StitchType::Knit;
  /// Corner vertex ids in the order of core/stitch.h; corners[3] = -1 for
  /// triangles. Ids: a_k -> k, b_l -> a.size() + l.
  std::array<int, 4> corners{-1, -1, -1, -1};
  int course = 0;     ///< position in the strip, 0 = bottom
  int direction = 1;  ///< +1 left to right (even course), -1 right to left
};

/// One operator of the chosen path, applied at node (i, j) = a_{2i} b_{2j}.
struct StripStep {
  StripOperator op = StripOperator::ABAdvance;
  int i = 0;
  int j = 0;
};

/// An apex of a short-row-end pair (two triangles) added in the strip.
struct StripApex {
  int vertex = -1;            ///< vertex id as in StripFace::corners
  Vec3 position = Vec3::Zero();
  bool on_wale_end = false;   ///< apex is a_0, a_2na, b_0 or b_2nb (a boundary pair)
};

/// Result of tessellate_strip().
struct StripTessellation {
  std::vector<StripFace> faces;   ///< bottom to top
  std::vector<StripStep> steps;   ///< the operators of the path, bottom to top
  std::vector<StripApex> apexes;  ///< one entry per triangle pair, bottom to top
  std::array<int, 2> source{0, 0};  ///< source node (i, j)
  std::array<int, 2> target{0, 0};  ///< target node (i, j)
  double cost = 0.0;         ///< exact cost of the whole path (mm)
  double lambda = 0.0;       ///< final lambda (mm)
  int lambda_growths = 0;    ///< how often lambda grew by 10 %
};

/// Direction of a sampled wale w at sample k: the chord from sample k - 2
/// to sample k + 2 (clamped at the ends). Two segments each way, so that an
/// end extension poking across a cut (whose direction is unrelated to the
/// wale's) does not decide it alone. Samples of neighbouring wales whose
/// directions disagree lie on the two sides of a cut or narrow notch and are
/// never paired. \pre 0 <= k < w.size().
Vec3 wale_tangent(const std::vector<Vec3>& w, size_t k);

/// Tessellates the strip between the left wale a and the right wale b.
/// \pre a.size() and b.size() odd and >= 3 (an even number >= 2 of
///      segments), finite points, sw > 0, sh > 0, mu >= 0, lambda > 0.
/// \throw InvalidInput naming the strip and the offending argument, also when
///        a fork end's two points differ (by more than 1e-6 x the strip size).
/// \throw SolverError naming the strip when no path exists between source and
///        target even after max_lambda_growths growths of lambda (or once
///        lambda exceeds every bridge between them).
/// Deterministic (see "Shortest path" above). Seed §3.2.2-3.2.3.
StripTessellation tessellate_strip(const std::vector<Vec3>& a, const std::vector<Vec3>& b,
                                   const StripOptions& options);

/// "AB-advance", "A-advance", "B-advance", "BB-advance", "B-fan", "increase",
/// "increase-B", "increase-BB", "decrease", "decrease-B", "decrease-BB",
/// "increase-decrease".
std::string_view name(StripOperator op);

}  // namespace knitforge
