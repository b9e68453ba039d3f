#pragma once
/// \file stitch_distortion.h
/// Per-stitch distortion of a stitch mesh (seed §2.A.2): how far each stitch
/// is from the ideal shape of its type (ideal_stitch_shape() in
/// convert/relax_stitch_mesh.h), independent of rotation and translation.
///
/// For a stitch with ideal corners p_i (in the plane z = 0 of the stitch
/// frame) and actual corners q_i (3D), i = 1..n:
///  1. rigid fit (seed eq. 2.3-2.4): the rotation R and translation t
///     minimising sum |R p_i + t - q_i|^2 (rigid_align()); its RMS residual
///     is reported as `rigid_rms`;
///  2. linear map: the 3x2 matrix A minimising sum |A (p_i - p̄) - (q_i - q̄)|^2,
///     i.e. the affine map of the triangle for a triangular stitch (exact)
///     and the least-squares affine fit of all four corners for a quad (not
///     an average over its two triangles). Expressed in the aligned frame
///     (R^T A restricted to the plane) this is the 2x2 map T of §2.A.1; its
///     singular values σ1 >= σ2 >= 0 are those of A and do not depend on R;
///  3. scalar distortion d = max(|σ1 - 1|, |σ2 - 1|): the largest relative
///     stretch or compression in any direction (0 for an ideal stitch, k - 1
///     for a stitch scaled by k, 1 for a stitch collapsed to a segment).
///
/// A quad's non-affine deviation (a trapezoid, a twist out of its plane) is
/// not in σ; it shows in `rigid_rms` and, relative to the stitch size, in
/// `rigid_rms / sqrt(w h)`.

#include <span>
#include <vector>

#include "knitforge/core/knit_params.h"
#include "knitforge/core/stitch_mesh.h"
#include "knitforge/geometry/vec.h"

namespace knitforge {

/// Distortion of one stitch.
struct StitchDistortion {
  double sigma1 = 1.0;      ///< larger singular value of the linear map (stretch factor)
  double sigma2 = 1.0;      ///< smaller singular value
  double distortion = 0.0;  ///< max(|σ1 - 1|, |σ2 - 1|)
  double rigid_rms = 0.0;   ///< RMS corner residual of the best rigid fit (mm)
};

/// Distortion of the polygon `actual` against the planar polygon `ideal`
/// (corresponding corners; ideal z coordinates are ignored).
/// \throw InvalidInput for mismatched sizes, fewer than 3 corners, non-finite
///        coordinates, or an ideal polygon whose corners are collinear.
StitchDistortion polygon_distortion(std::span<const Vec3> ideal, std::span<const Vec3> actual);

/// Distortion of every stitch of `mesh` against the ideal shape of its type.
/// \throw InvalidInput for bad params or non-finite vertices; TopologyError
///        for a corner index out of range (naming the stitch).
std::vector<StitchDistortion> stitch_distortion(const StitchMesh& mesh, const KnitParams& params);

/// The `distortion` member of each entry (for scalar_stats() / colouring).
std::vector<double> distortion_values(std::span<const StitchDistortion> d);

}  // namespace knitforge
