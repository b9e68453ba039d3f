#pragma once
/// \file shape_up.h
/// Shape-Up (Bouaziz et al., "Shape-Up: shaping discrete geometry with
/// projections", SGP 2012; seed §1.3.2 eq. 1.1): move the vertices of a
/// polygon mesh so that every polygon is as close as possible, by a rigid
/// motion, to its target shape:
///
///   E(V) = sum_i w_i min_{R_i, t_i} sum_{j in f_i} |R_i p'_ij + t_i - v_j|^2
///
/// with p'_ij the target corner positions in the polygon's own frame, R_i a
/// proper rotation and w_i a weight (seed: the target area).
///
/// Local step: for each polygon the best rigid fit (Kabsch / orthogonal
/// Procrustes with det R = +1; targets lying in the z = 0 plane of their
/// frame use a closed-form 3x2 polar decomposition, others a 3x3 SVD).
/// Global step: the mean-centred least-squares system
/// sum_i w_i |C_i (v_i - R_i p'_i)|^2 (C_i removes the polygon mean), whose
/// matrix is constant: it is factored once (sparse_solver.h) and each
/// iteration back-substitutes x, y and z together. The translation null space
/// is removed by fixing vertices (by default the first vertex of every
/// connected component, at its start position).
///
/// The local/global iteration converges slowly on large meshes, so it is
/// Anderson-accelerated (Peng et al., "Anderson acceleration for geometry
/// optimization and physics simulation", SIGGRAPH 2018) with an energy
/// safeguard. Energy is non-increasing over the iterations.

#include <vector>

#include "knitforge/geometry/sparse_solver.h"
#include "knitforge/geometry/vec.h"

namespace knitforge {

/// Polygons with target shapes, in compressed form.
struct ShapeUpPolygons {
  std::vector<int> start{0};    ///< polygon f has corners start[f] .. start[f+1]-1
  std::vector<int> vertices;    ///< vertex index of each corner
  std::vector<Vec3> targets;    ///< target position of each corner, polygon frame (mm)
  std::vector<double> weights;  ///< one weight > 0 per polygon

  int num_polygons() const { return static_cast<int>(start.size()) - 1; }
  /// Appends a polygon (corner vertices and their targets, same size >= 2).
  void add(const std::vector<int>& corner_vertices, const std::vector<Vec3>& corner_targets, double weight);
};

struct ShapeUpOptions {
  int max_iterations = 300;  ///< iterations (global steps) at most
  /// Stop when (E_k - E_{k+1}) / E_k <= tolerance, or E_{k+1} <= 1e-24 times
  /// the weighted squared size of the targets.
  double tolerance = 1e-7;
  /// Anderson acceleration depth (previous iterates used); 0 = plain Shape-Up.
  /// Accelerated steps are kept only when they lower the energy, so the
  /// energy stays non-increasing either way.
  int anderson_depth = 5;
};

struct ShapeUpResult {
  std::vector<Vec3> positions;  ///< final vertex positions
  /// energy[0] is the energy of the start positions, energy[k] after k iterations.
  std::vector<double> energy;
  int iterations = 0;           ///< global steps done
  bool converged = false;       ///< tolerance reached before max_iterations
};

/// Shape-Up with a factored global matrix; reusable for many starts.
class ShapeUpSolver {
 public:
  /// Precomputes and factors the global matrix.
  /// `fixed`: vertices held at their start position; empty = the smallest
  /// vertex of every connected component (vertices no polygon uses are fixed
  /// too).
  /// \throw InvalidInput for inconsistent sizes, a vertex index out of
  ///        [0, num_vertices), a repeated vertex in a polygon, a weight that is
  ///        not finite and > 0, a non-finite target, a fixed vertex out of
  ///        range, or a connected component without a fixed vertex;
  ///        SolverError if the factorisation fails.
  ShapeUpSolver(int num_vertices, ShapeUpPolygons polygons, std::vector<int> fixed = {});

  int num_vertices() const { return num_vertices_; }

  /// Runs Shape-Up from `start` (num_vertices positions).
  /// \throw InvalidInput for a wrong size or non-finite start positions;
  ///        SolverError for a non-finite solve.
  ShapeUpResult solve(std::vector<Vec3> start, const ShapeUpOptions& options = {}) const;

  /// The energy E(V) of positions V (best rigid fits).
  double energy(const std::vector<Vec3>& positions) const;

 private:
  double local_step(const std::vector<Vec3>& x, Eigen::MatrixXd* rhs) const;

  int num_vertices_ = 0;
  ShapeUpPolygons poly_;
  std::vector<char> planar_;        ///< per polygon: targets in the z = 0 plane
  std::vector<Vec3> centred_;       ///< targets minus their polygon mean
  std::vector<int> free_index_;     ///< per vertex: unknown index or -1 when fixed
  std::vector<int> fixed_;
  int num_free_ = 0;
  SparseSolver solver_;
};

/// One-shot Shape-Up: ShapeUpSolver(start.size(), polygons).solve(start, options).
ShapeUpResult shape_up(const std::vector<Vec3>& start, const ShapeUpPolygons& polygons,
                       const ShapeUpOptions& options = {});

}  // namespace knitforge
