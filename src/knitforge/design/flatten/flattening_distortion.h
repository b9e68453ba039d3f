#pragma once
/// \file flattening_distortion.h
/// Distortion of a flattening (seed §2.A.1, as in [172]): per triangle the
/// linear map T from the 3D triangle (in an isometric 2D frame) to its 2D
/// image, T = U Σ Vᵀ; σ1 >= σ2 are the scale factors along two orthogonal
/// directions in the pattern (the columns of U). σ < 1 is compression, σ > 1
/// stretching; an isometric flattening has σ1 = σ2 = 1.
///
/// Statistics are area-weighted (3D areas) over the natural logarithms of
/// both singular values of every face, so compression and stretching by the
/// same factor count the same.
#include <algorithm>
#include <array>
#include <string>
#include <vector>
#include "knitforge/evaluate/scalar_colours.h"
#include "knitforge/geometry/tri_mesh.h"
#include "knitforge/geometry/vec.h"

namespace knitforge {

/// Distortion of one face.
struct FaceDistortion {
  double sigma1 = 1.0;         ///< larger singular value
  double sigma2 = 1.0;         ///< smaller singular value
  Vec2 dir1 = Vec2(1.0, 0.0);  ///< pattern direction scaled by sigma1 (unit)
  Vec2 dir2 = Vec2(0.0, 1.0);  ///< pattern direction scaled by sigma2 (unit, ⟂ dir1)
  bool flipped = false;        ///< det T <= 0 (the 2D triangle is flipped or degenerate)
  /// The log singular value of larger magnitude (signed): < 0 compression
  /// dominates, > 0 stretching dominates. The face colour.
  double dominant_log() const;
};

/// Area-weighted statistics of the log singular values.
struct DistortionStats {
  double min_log_sigma = 0.0;   ///< smallest log σ2
  double max_log_sigma = 0.0;   ///< largest log σ1
  double mean_log_sigma = 0.0;  ///< Σ a (log σ1 + log σ2) / (2 Σ a): log of the mean scale
  double rms_log_sigma = 0.0;   ///< sqrt(Σ a (log² σ1 + log² σ2) / (2 Σ a)): the distortion energy
  double area_3d = 0.0;         ///< mm²
  double area_2d = 0.0;         ///< mm² (signed areas summed)
  int flipped_faces = 0;
  /// The largest |log σ| of any face: the worst stretch or compression.
  double max_abs_log_sigma() const { return std::max(max_log_sigma, -min_log_sigma); }
};

/// Per-face distortion of the flattening uv of mesh.
/// \throw InvalidInput when uv.size() != mesh.num_vertices() or a face uses
///        an index out of range.
std::vector<FaceDistortion> flattening_distortion(const TriMesh& mesh, const std::vector<Vec2>& uv);

/// The 2x2 map T of eq. 2.2 from the 3D triangle (p0, p1, p2) to the 2D
/// triangle (q0, q1, q2), expressed in the isometric frame of the 3D
/// triangle (its edge p0p1 along +x); T is the zero matrix for a degenerate
/// 3D triangle.
Mat2 triangle_map(const Vec3& p0, const Vec3& p1, const Vec3& p2, const Vec2& q0, const Vec2& q1,
                  const Vec2& q2);

/// Singular values and pattern directions of T (see FaceDistortion).
FaceDistortion decompose_map(const Mat2& T);

/// Statistics over the faces (weights: 3D face areas of mesh).
/// \throw InvalidInput when the sizes disagree.
DistortionStats distortion_stats(const TriMesh& mesh, const std::vector<Vec2>& uv,
                                 const std::vector<FaceDistortion>& faces);

/// Per-face colour: white at σ = 1, towards blue for compression and red
/// for stretching (dominant_log()), saturated at |log σ| >= saturation.
/// \throw InvalidInput when saturation <= 0.
std::vector<Rgb8> distortion_colours(const std::vector<FaceDistortion>& faces, double saturation = 0.3);

/// Per-vertex distortion energy: area-weighted mean over the incident faces
/// of log² σ1 + log² σ2 (0 for unused vertices). Used to find where darts
/// help (dart_hints.h).
std::vector<double> vertex_distortion_energy(const TriMesh& mesh, const std::vector<FaceDistortion>& faces);

/// The largest distortion at the scale of a stitch: for every face, the
/// area-weighted means of log σ1 and log σ2 over the faces whose centroids
/// lie within `radius` (mm, 3D) of its centroid, reached through faces
/// sharing a vertex; the largest |mean| over all faces. A sliver or a dart
/// tip's few faces cannot dominate it, as they do the per-face maximum
/// (which grows without bound at a dart tip as the mesh is refined).
/// \throw InvalidInput when the sizes disagree or radius is negative or not finite.
double patch_max_abs_log_sigma(const TriMesh& mesh, const std::vector<FaceDistortion>& faces, double radius);

/// An SVG drawing of the 2D pattern (mm, y up): faces coloured as
/// distortion_colours(), the boundary outlined, direction glyphs (two
/// segments along dir1 / dir2, lengths proportional to σ) on a subsample of
/// at most `max_glyphs` faces, and `marks` (e.g. dart notches) as dots.
/// Deterministic text.
std::string pattern_svg(const TriMesh& mesh, const std::vector<Vec2>& uv,
                        const std::vector<FaceDistortion>& faces, const std::vector<Vec2>& marks = {},
                        int max_glyphs = 600);

}  // namespace knitforge
