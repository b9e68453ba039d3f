#pragma once
/// \file tube_crown.h
/// Closed tubes (docs/tubes.md, "Closed tubes"; issue #15 item 4): a
/// surface with ONE boundary loop (a disk: a beanie, a sock's toe, a
/// mitten's top) is knitted in the round from its rim to its crown, where
/// the tube is closed by a seam across the top.
///
/// The crown point is the vertex farthest from the rim (the exact geodesic
/// distance d from the rim, geometry/geodesic_distance.h), or one the caller
/// names (CrownOptions::crown_vertex: the extreme of an initial field, tube_
/// field_candidates.h). A harmonic function cannot be pinned at one vertex
/// (its levels shrink to a logarithmic spike there), so the crown's boundary
/// condition is extended from that vertex to a short geodesic curve segment
/// through it, as seed §3.3.8 (L1562) optimises a field: "initial boundary
/// conditions ... on distinct vertices ... are extended as several curve
/// segments to reduce the divergence-based metric".
///
/// The segment: the normal section of the surface through the crown point
/// in a tangent direction phi (source_from_polyline() on the three points
/// crown -+ s/2 t(phi) and the crown, the ends moved out until the section
/// is s long along the surface). The surface within distance
/// w of it (w = the slit's half-width, at least the mean edge length so that
/// the cut finds vertices; the straight-line distance to the segment's
/// polyline, which at a few millimetres is the geodesic one wherever the
/// surface's curvature radius is well above w) is cut off exactly along that
/// level (clip_mesh_by_field.h), which leaves an annulus whose inner rim
/// (the crown ring) runs along both sides of the segment: 2 s + 2 pi w long.
/// s is set so that this is crown_length (crown stitches x sw): the last
/// round closes flat along the segment with the asked count, its halves on
/// the two sides (a sock's toe seam, grafted side to side), and nothing but
/// the thin slit is gathered by the closing seam.
///
/// Direction: `directions` angles phi = j pi / directions (j = 0 ..
/// directions - 1; a segment and its reverse are the same) are tried; each
/// gives the harmonic tube field of its annulus (tube_field.h), scored by
/// the divergence metric of its normalised gradient
/// (DivergenceMetric::transfer_estimate(), seed §3.3.8); the lowest score
/// wins. Scores within kDirectionTie of the lowest are a tie (on a round toe
/// or dome the directions differ by a fraction of a stitch, i.e. by noise):
/// the tie goes to the direction most nearly along the surface's thinnest
/// axis (the smallest principal axis of its area-weighted face centroids),
/// which on a tube bent in a plane (a sock: leg and foot) is that plane's
/// normal, so the segment runs across the bend, side to side, as a sock's
/// toe is grafted; when that axis is nearly normal to the surface at the
/// crown (its tangent part under 0.3) the lowest score wins outright.
/// The tangent basis at the crown point: t(0) is
/// the world axis least aligned with the vertex normal, projected onto the
/// tangent plane; t(90°) = n x t(0).
///
/// One crown only: when the superlevel set {d >= t} falls into several
/// pieces that each rise at least 2 (s / 2 + w) above t, for a t between
/// half the largest distance and the depth of the cut (two peaks: a mitten
/// with its thumb, a two-toed sock), the surface is refused with the number
/// of crowns and what to do. A lower bump (the back of a sock's heel, a
/// local maximum of d a few mm high) is no crown.

#include <optional>
#include <string>
#include <vector>

#include "knitforge/geometry/tri_mesh.h"

namespace knitforge {

/// Scores (stitches, estimate) within this of the lowest are a tie.
inline constexpr double kDirectionTie = 1.0;

/// Options of cut_crown().
struct CrownOptions {
  double crown_length = 42.0;        ///< mm: the crown ring's length (crown stitches x sw), > 0
  double stitch_width = 3.5;         ///< mm: scores the directions (transfer estimate)
  double min_slit_half_width = 0.0;  ///< mm: w at least this (and at least the mean edge length)
  int directions = 6;                ///< segment directions tried, 1..36
  std::optional<int> crown_vertex;   ///< the crown point; default: the vertex farthest from the rim
  /// rim_distance() of the disk when the caller has it (several crowns cut
  /// from one disk); empty: computed.
  std::vector<double> rim_distance;
};

/// A disk cut open along its crown segment.
struct TubeCrown {
  TriMesh annulus;            ///< the surface without the slit round the segment: two boundary loops
  Vec3 crown = Vec3::Zero();  ///< the crown point (mm)
  int crown_vertex = -1;      ///< its vertex in the disk
  double rim_to_crown = 0;  ///< its geodesic distance from the rim (mm)
  double cap_radius = 0;    ///< w: the slit's geodesic half-width (mm)
  double cap_area = 0;      ///< area cut off (mm^2)
  Vec3 segment_start = Vec3::Zero(),
       segment_end = Vec3::Zero();       ///< ends of the crown segment (on the surface, mm)
  double segment_length = 0;             ///< s (mm, along the surface)
  double ring_length = 0;                ///< the crown ring's length as cut (mm)
  double direction_degrees = 0;          ///< phi of the winner
  std::vector<double> direction_scores;  ///< per direction tried: transfer estimate (stitches)
};

/// Geodesic distance (mm) of every vertex of `disk` from its rim (its first
/// boundary loop), to a thousandth of `stitch_width` (the approximate
/// propagation of geodesic_distance.h).
/// \throw as geodesic_distance().
std::vector<double> rim_distance(const TriMesh& disk, double stitch_width);

/// Cuts `disk` open along its crown segment (see the file comment).
/// \throw InvalidInput when `disk` is not one manifold piece with one
///        boundary loop and genus 0, the options are out of range (names
///        the option), the crown lies too close to the rim for the segment
///        (within s / 2 + 2 w), or the surface has several crowns (the
///        message counts them and says what to do).
TubeCrown cut_crown(const TriMesh& disk, const CrownOptions& options, const std::string& what);

}  // namespace knitforge
