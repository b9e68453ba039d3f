#pragma once
/// \file tessellate_wales.h
/// The stitch mesh between all wale curves (seed §3.2.2-3.2.3): every strip
/// between the wales of neighbouring levels is tessellated by
/// tessellate_strip(), level by level from the lowest field value up, with
/// the apexes placed so far feeding the apex-diffusion term of the next
/// strips.
///
/// Strips. When both levels have one wale, the strip is the pair of whole
/// wales. When a level has several pieces (the isocurve split around a peak
/// or a notch of the boundary), the even samples of every piece are given to
/// the nearest piece of the other level (3D distance between even samples),
/// counting only samples where the two wales run the same way (wale
/// directions, as chords over two segments each way, with a positive dot
/// product): next to a cut made to open a closed isocurve, the wales on its
/// two sides run in opposite directions a fraction of a millimetre apart,
/// and pairing across it would fold a strip over the cut. A pair of pieces
/// forms a strip over the longest run of consecutive even samples each gives
/// the other (at least two segments on each side), so strips never share a
/// wale segment on the same side. Pieces that pair with nothing are
/// reported; samples outside every run stay uncovered (a notch in the
/// fabric where the isocurve splits).
///
/// Overhangs. Where one wale of a strip runs on beyond the end of the other
/// (near the boundary the wales end at different heights), the strip covers
/// only the half of the overhang next to the shorter wale's end: the fan of
/// short-row ends tessellate_strip() puts there has its apex on the boundary
/// and becomes a column of full stitches in the post-processing
/// (boundary_apex_quads.h), and half the overhang's length of full stitches
/// has the area of the triangle of surface the overhang spans. Covering the
/// whole overhang would add about one stitch per two boundary samples beyond
/// the surface. Only whole pairs of segments can be removed, so where half
/// the overhang is an odd number of segments one end keeps a segment more
/// than half and the next such end one fewer (a running balance over the
/// whole tessellation); always keeping the extra segment added about 3 % to
/// the monkey saddle's stitch count. The trimming looks for the nearest samples running the same
/// way, like the pairing. When the strip nevertheless ends in a fan whose
/// apex is a trimmed end (e.g. the tiny opened loop at the top of a peak,
/// whose last samples pair with nothing), that apex would lie in the middle
/// of its wale, on the edge of the fabric, and the post-processing would
/// turn the fan into a column of stitches detached from the stitches across
/// the wale (a second last course): the trimmed samples at that end are
/// given back two at a time, and the strip tessellated again, until no fan
/// sits on a trimmed end.
///
/// Vertices. Every wale sample is one vertex of the mesh (wale by wale, in
/// level order); faces of neighbouring strips therefore share the samples of
/// their common wale, and two stitches of neighbouring strips that share a
/// wale segment belong to the same course (§3.2.4).
///
/// Directions. tessellate_strip() numbers courses inside a strip from 0 at
/// the bottom with even courses knitted left to right; because every strip
/// starts at an even sample of both wales and every operator adds an even
/// number of faces, the course parity of a face equals the parity of the
/// index of its wale segments, so neighbouring strips always agree on the
/// knitting direction of a shared course.

#include <optional>
#include <vector>

#include "knitforge/core/knit_params.h"
#include "knitforge/core/stitch_mesh.h"
#include "knitforge/design/shortrow/wale_curves.h"

namespace knitforge {

/// Options of tessellate_wales(); lengths in mm.
struct TessellateWalesOptions {
  std::optional<double> lambda;            ///< initial bridge limit; default sw + 2 sh
  std::optional<double> mu;                ///< apex diffusion weight; default 100 sw; 0 = off
  std::optional<double> diffusion_length;  ///< D unit; default sw
};

/// Result of tessellate_wales().
struct WaleTessellation {
  /// Stitches with type, corners (canonical order), direction, and wale =
  /// the level of the strip's lower wale (the map column: strips of one
  /// level that lie one above the other share it); course is -1 (set by
  /// the course ordering).
  StitchMesh mesh;
  /// Per vertex: the wale (flat index over WaleCurves::wales, level by level)
  /// and the sample index along it.
  std::vector<int> vertex_wale;
  std::vector<int> vertex_sample;
  /// Per stitch: the strip it belongs to and its level (the lower wale's).
  std::vector<int> stitch_strip;
  std::vector<int> stitch_level;
  /// Apexes of short-row-end pairs (mm), in placement order, and whether the
  /// apex is a wale end (those become quads in the post-processing).
  std::vector<Vec3> apexes;
  std::vector<char> apex_on_wale_end;
  int num_strips = 0;
  int unpaired_pieces = 0;  ///< wale pieces that share a strip with no other piece
  int lambda_growths = 0;   ///< total growths of lambda over all strips
  double max_lambda = 0.0;  ///< largest final lambda of a strip (mm)
  double cost = 0.0;        ///< total path cost over all strips (mm)
};

/// Tessellates all strips between the wales of `wales`.
/// \throw InvalidInput for bad options or fewer than two non-empty levels
///        (the message says to use a smaller stitch width);
///        SolverError from tessellate_strip() naming the strip.
WaleTessellation tessellate_wales(const WaleCurves& wales, const KnitParams& params,
                                  const TessellateWalesOptions& options = {});

}  // namespace knitforge
