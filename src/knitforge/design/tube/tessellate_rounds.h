#pragma once
/// \file tessellate_rounds.h
/// Rounds -> tubular stitch mesh (docs/tubes.md, "Design"): each round is
/// sampled at one point per stitch, the wales are traced from round to
/// round as column labels, and every row between two rounds becomes a ring
/// of stitches, with an increase or a decrease where a wale starts or ends.
///
/// Stitch counts. Round k gets round(length_k / sw) stitches (at least 8),
/// split into a front half of ceil(m/2) and a back half of floor(m/2)
/// (the two needle beds; the halves lie on the two halves of the round by
/// arc length from the seam). The counts of the first and the last row are
/// those of their inner round (a shaping stitch's apex may not lie on a
/// rim, rule boundary-apex), and a half changes by at most max(1, h/4)
/// stitches from one round to the next (so that its decreases never touch);
/// a round whose length changes faster lags behind, and RoundsTessellation
/// reports both counts.
///
/// Wales. The map has N = 2 ceil(max m / 2) columns, 0..N/2-1 the front half
/// and N/2..N-1 the back half (knitting_map.h). The live wales of a half are
/// spread evenly over its columns in round 0. A half that loses d stitches
/// from round k to k + 1 ends d of its wales there (decreases, apex on round
/// k + 1): at evenly spaced positions turned by the golden ratio from one
/// shaping row to the next (so the decreases spiral round the tube, as a
/// knitter spaces them), never the first or last wale of the half (next to
/// a fold) and never two side by side (rule neighbouring-decreases). A half
/// that gains stitches starts new wales (increases, apex on round k) in the
/// free column between two live wales, evenly spaced, at most one per gap
/// (rule neighbouring-increases); next to a fold only when no gap between
/// wales is free.
///
/// Stitches. Row r (between round r and r + 1) holds, in column order from
/// the seam, a Knit stitch for each wale live on both rounds, a Decrease for
/// each wale that ends, an Increase for each that starts; corners as
/// stitch.h (counter-clockwise seen from outside). Stitches are numbered in
/// knitting order, Stitch::course = r, Stitch::wale = column, direction +1
/// (every round knitted the same way, the seam at the left fold): what
/// stitch_mesh_to_map() reads back as a tubular map.

#include <vector>

#include "knitforge/core/knit_params.h"
#include "knitforge/core/stitch_mesh.h"
#include "knitforge/design/tube/tube_rounds.h"

namespace knitforge {

/// The wales of the rounds (the first part of tessellate_rounds()): which
/// map columns are live on each round.
struct RoundWales {
  int columns = 0;                       ///< N
  std::vector<std::vector<int>> live;    ///< per round: its live columns, sorted (front half first)
  std::vector<int> stitches;             ///< per round: live[k].size()
  std::vector<int> ideal;                ///< per round: max(8, round(length / sw))
  int increases = 0, decreases = 0;      ///< wales started / ended between rounds
};

/// The live wales of every round (see the file comment: counts, halves,
/// where wales end and start).
/// With `equal_halves` (a closed tube, tube_crown.h) the back half follows
/// the front half's count instead of floor(m/2), so that the last round's
/// halves hold equally many stitches (the closing seam joins them in pairs),
/// and a half may lose up to floor((h - 1) / 2) stitches in one round (every
/// other wale but the first and last: still never two decreases side by
/// side) where its round narrows faster than a quarter of it per round (the
/// crown), and the round below the last takes the last one's ideal count
/// (the last row may not shape), so that the last round reaches the asked
/// count.
/// \throw InvalidInput for fewer than two rounds or an invalid stitch size;
///        with equal_halves, when the last round's halves still differ.
RoundWales round_wales(const std::vector<RoundCurve>& rounds, const KnitParams& params, bool equal_halves = false);

/// The tubular stitch mesh and its counts.
struct RoundsTessellation {
  StitchMesh mesh;
  int columns = 0;                 ///< N
  std::vector<int> stitches;       ///< per round: the stitches sampled on it (m_k)
  std::vector<int> ideal;          ///< per round: max(8, round(length / sw))
  int increases = 0, decreases = 0;
};

/// Tessellates the rounds (at least two: the two rims).
/// \throw InvalidInput for fewer than two rounds or an invalid stitch size
///        (and as round_wales() with equal_halves).
RoundsTessellation tessellate_rounds(const std::vector<RoundCurve>& rounds, const KnitParams& params,
                                     bool equal_halves = false);

}  // namespace knitforge
