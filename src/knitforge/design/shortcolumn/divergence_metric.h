#pragma once
/// \file divergence_metric.h
/// The divergence-based metric of seed §3.3.2 (L1236-1300): how many
/// transfer stitches (short-column starts and ends) a stitch mesh whose wales
/// follow the isocurves of f will need.
///
/// g = grad f per face (constant on each triangle, the face-based
/// representation [38]); v = J g^ = n x g / |g| is the unit tangent of the
/// isocurves (the wale direction, isocurves.h). Per interior vertex i
/// (eq. 3.5):
///
///     [div v]_i = sum_{ijk in N(i)} <v_ijk, J e_kj> / sum_{ijk in N(i)} A_ijk
///
/// with e_kj = x_j - x_k the edge of face ijk opposite i, oriented so that
/// J e_kj = n_ijk x e_kj points out of the 1-ring (its length is the edge
/// length, so the numerator is the flux of v out of the 1-ring, eq. 3.2).
/// div v > 0: isocurves spread (a short column starts); < 0: they converge
/// (one ends). The metric (eq. 3.6) is
///
///     I(f) = sum_{i interior} A_i |[div v]_i|        (mm)
///
/// with A_i the mixed Voronoi area (cotan_laplacian.h).
///
/// Consistency: eq. 3.5 evaluates v at the face centroids, two thirds of the
/// way from i to the outer edges of its 1-ring, so for a smooth field it
/// converges to 2/3 div v, not div v (for a linear v exactly: the flux of
/// v(i) + 2/3 grad v (x - x_i) through the closed ring is 2/3 tr(grad v) x
/// ring area). We keep the seed's formula, so I(f) is the seed's metric, about
/// 2/3 of the integral of eq. 3.1 (the tests measure the factor on a field of
/// known divergence).
///
/// Transfer estimate: |div v| is the rate at which wales sw apart must be
/// added or removed per unit length along them (a fan of angle a between
/// radii r0 and r1 needs (r1 - r0) a / sw extra wales, and the integral of
/// |div v| over it is (r1 - r0) a), so 3/2 I(f) / sw estimates the number of
/// transfer stitches; DivergenceMetric::transfer_estimate() is that
/// ESTIMATE, labelled as such (docs/shortcolumn.md compares it with the
/// counts). A geodesic distance field has div J g^ = 0 (eq. 3.4): no short
/// columns.
///
/// Tubes (DivergenceOptions::along_gradient, seed §3.3.8): v = g^, the wale
/// direction of a tube whose rounds are the isocurves; on a cone of radius
/// r(s) along the axis, div g^ = r'/r, its integral 2π |Δr|, and the
/// estimate 2π |Δr| / sw the change of the round's stitch count: the
/// increases plus decreases.
///
/// Vanishing gradients: where |g| <= gradient_epsilon x (range of f) /
/// (bounding-box diagonal), v is undefined; such faces contribute 0 and are
/// counted (DivergenceMetric::flat_faces).

#include <array>
#include <vector>

#include "knitforge/geometry/tri_mesh.h"
#include "knitforge/geometry/vec.h"

namespace knitforge {

/// Options of the divergence metric.
struct DivergenceOptions {
  /// A face is "flat" (no direction) when |grad f| <= gradient_epsilon x
  /// (max f - min f) / (bounding-box diagonal) (see the file comment).
  double gradient_epsilon = 1e-9;
  /// Measure v = g^ itself instead of J g^: the tube route's courses follow
  /// the isocurves and its wales the gradient, so the divergence of the
  /// normalised gradient estimates its increases and decreases (seed §3.3.8,
  /// L1550; docs/tubes.md "Transfer estimate").
  bool along_gradient = false;
};

/// The metric of one field.
struct DivergenceMetric {
  std::vector<double> divergence;    ///< [div v]_i per vertex (1/mm); 0 on boundary and unused vertices
  std::vector<double> contribution;  ///< A_i |[div v]_i| per vertex (mm^2 / mm = mm)
  std::vector<char> interior;        ///< 1 for the vertices eq. 3.6 sums over
  double total = 0.0;                ///< I(f) of eq. 3.6 (mm)
  double area = 0.0;                 ///< surface area (mm^2)
  double positive = 0.0;             ///< sum of A_i [div v]_i over div > 0 (mm; spreading, short-column starts)
  double negative = 0.0;             ///< sum of A_i |[div v]_i| over div < 0 (mm; converging, ends)
  int flat_faces = 0;                ///< faces with a vanishing gradient

  /// I(f) / area (1/mm): the resolution-independent value of Fig. 3.17.
  double normalised() const { return area > 0.0 ? total / area : 0.0; }
  /// 3/2 I(f) / sw: an ESTIMATE of the number of transfer stitches (see the
  /// file comment), not a count.
  double transfer_estimate(double stitch_width) const { return 1.5 * total / stitch_width; }
};

/// Precomputed geometry (face gradient bases, outward edge normals, 1-ring
/// and Voronoi areas) for evaluating the metric of many fields on one mesh.
class DivergenceOperator {
 public:
  /// \throw InvalidInput for an empty mesh, indices out of range or
  ///        non-finite coordinates; TopologyError for a non-manifold mesh.
  explicit DivergenceOperator(const TriMesh& mesh, const DivergenceOptions& options = {});
  /// \throw InvalidInput when field.size() != num_vertices() or a value is
  ///        not finite.
  DivergenceMetric evaluate(const std::vector<double>& field) const;
  /// Only I(f) (no per-vertex arrays): the optimiser's objective.
  double total(const std::vector<double>& field) const;
  int num_vertices() const { return static_cast<int>(vertex_area_.size()); }

 private:
  void face_directions(const std::vector<double>& field, std::vector<Vec3>& v, int& flat) const;
  DivergenceOptions options_;
  std::vector<std::array<int, 3>> faces_;
  std::vector<std::array<Vec3, 3>> grad_basis_;  ///< per face, grad of each hat function (1/mm)
  std::vector<Vec3> normal_;                     ///< per face unit normal
  std::vector<std::array<Vec3, 3>> out_edge_;    ///< per face corner k: J e of the edge opposite k (mm)
  std::vector<double> ring_area_;                ///< per vertex, sum of the areas of its faces
  std::vector<double> vertex_area_;              ///< mixed Voronoi area
  std::vector<char> interior_;
  double diagonal_ = 0.0, area_ = 0.0;
};

/// One-shot metric of `field` on `mesh`.
/// \throw as DivergenceOperator.
DivergenceMetric divergence_metric(const TriMesh& mesh, const std::vector<double>& field,
                                   const DivergenceOptions& options = {});

}  // namespace knitforge
