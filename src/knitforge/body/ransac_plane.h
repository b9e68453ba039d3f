#pragma once
/// \file ransac_plane.h
/// The dominant plane of a point cloud by RANSAC (Fischler & Bolles 1981),
/// for finding the calibration board in a depth camera's points (seed §5.3.1
/// does not say how the planes are detected).
///
/// 1. Hypotheses: planes through 3 points drawn at random (seeded), up to
///    max_iterations, fewer when the best inlier fraction w found so far
///    makes it `confidence`-sure that an all-inlier sample was drawn:
///    N = log(1 - confidence) / log(1 - w^3).
/// 2. The hypothesis with the most points within inlier_distance_mm wins.
/// 3. Refinement: the least-squares plane of its inliers (centroid and the
///    covariance's smallest eigenvector), then the inliers again, `refinements`
///    times. Exact for noiseless points on a plane.
///
/// The normal is oriented towards the origin (for points in a camera's frame:
/// towards the camera, i.e. out of the surface the camera sees).

#include <span>
#include <vector>

#include "knitforge/geometry/vec.h"

namespace knitforge {

/// Options of ransac_plane().
struct RansacPlaneOptions {
  double inlier_distance_mm = 4.0;   ///< a point this close to the plane is an inlier (4 sigma of 1 mm noise)
  int max_iterations = 2000;         ///< most hypotheses
  double confidence = 0.999;         ///< stop when this sure of an all-inlier sample
  int refinements = 3;               ///< least-squares refits after the best hypothesis
  double min_inlier_fraction = 0.2;  ///< fewer inliers than this fraction of the points: no plane
  int min_inliers = 100;             ///< ... or than this count: no plane
  unsigned seed = 1;                 ///< random draws (deterministic)
};

/// A detected plane n . (x - point) = 0.
struct RansacPlane {
  Vec3 normal = Vec3::UnitZ();  ///< unit, towards the origin
  Vec3 point = Vec3::Zero();    ///< centroid of the inliers (mm)
  std::vector<int> inliers;     ///< indices into the points, ascending
  double rms_mm = 0.0;          ///< rms distance of the inliers to the plane
  double inlier_fraction = 0.0; ///< inliers / points
  int iterations = 0;           ///< hypotheses drawn
};

/// The least-squares plane of `points` (all of them): centroid and unit
/// normal (smallest principal direction, oriented towards the origin).
/// \throw InvalidInput for fewer than 3 points or collinear points.
RansacPlane fit_plane(std::span<const Vec3> points);

/// The dominant plane (file comment).
/// \throw InvalidInput when there are fewer than 3 points or an option is
///        out of range, and "no plane found" (with the best inlier count and
///        what was needed) when the best plane has fewer inliers than
///        min_inliers or min_inlier_fraction of the points.
RansacPlane ransac_plane(std::span<const Vec3> points, const RansacPlaneOptions& options = {});

}  // namespace knitforge
