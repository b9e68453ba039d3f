#pragma once
/// \file resample_polyline.h
/// Resampling of an open 3D polyline (a wale curve) into an EVEN number of
/// segments of a target length (the stitch height), seed §3.2.1: "an even
/// number of segments is required for each wale. To achieve this, a wale
/// curve's two ends are slightly extended when odd segments are obtained."
///
/// Rule: L = arc length, n = round(L / target) (at least 1).
///  - n even: n segments of equal arc length L / n along the curve (no
///    extension; |L/n - target| <= target / (2n)).
///  - n odd (and extend_ends): n + 1 segments of exactly `target`; the curve
///    is extended at both ends by the same length e = ((n+1) target - L) / 2,
///    which lies in (target/4, 3 target/4]. The extension is a straight
///    continuation along the end tangent, estimated robustly as the chord
///    from the end to the curve point one target length (or the whole
///    curve, if shorter) away — so tiny or noisy last segments do not tilt
///    it. The extended points leave the surface by O(e² curvature); callers
///    that need them on the surface project them (the mesh is not known
///    here).
///  - n odd and !extend_ends: the nearest even count (n + 1 when
///    L / target >= n, else n - 1, at least 2) of equal segments L / count.
/// A curve shorter than target / 2 gets two segments (extended to length
/// 2 target, or L / 2 each without extension).
///
/// Arc-length positions are measured along the input from its first point:
/// negative on the start extension, above L on the end extension.
/// Zero-length input segments (repeated points) are ignored.

#include <vector>

#include "knitforge/geometry/vec.h"

namespace knitforge {

/// Options of resample_polyline().
struct ResampleOptions {
  /// true: extend both ends when the natural count is odd (seed §3.2.1);
  /// false: use the nearest even count of equal segments instead.
  bool extend_ends = true;
};

/// The resampled polyline.
struct ResampledPolyline {
  std::vector<Vec3> points;        ///< num_segments + 1 points (mm)
  std::vector<double> arc_length;  ///< per point, arc length along the input from its start (mm)
  /// Per point, the input segment it lies on (index i for the segment from
  /// input point i to i + 1); -1 on the start extension, -2 on the end one.
  std::vector<int> segment;
  int num_segments = 0;       ///< always even and >= 2
  double segment_length = 0;  ///< length of every segment along the (extended) curve (mm)
  double extension = 0;       ///< length added at EACH end (mm), 0 when not extended
  double input_length = 0;    ///< arc length of the input (mm)
};

/// Resamples `polyline` into an even number of segments of about
/// `target_length` (see the file comment for the exact rule).
/// \throw InvalidInput when target_length is not positive and finite, the
///        polyline has fewer than 2 points, a coordinate is not finite, its
///        length is below 1e-9 x target_length (no direction to extend
///        along), or more than 1e8 segments would result.
ResampledPolyline resample_polyline(const std::vector<Vec3>& polyline, double target_length,
                                    const ResampleOptions& options = {});

}  // namespace knitforge
