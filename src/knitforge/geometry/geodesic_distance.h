#pragma once
/// \file geodesic_distance.h
/// The governing field of the short-row route (seed §3.2.1, §3.A.1): the
/// exact polyhedral geodesic distance on a triangle mesh from a source on the
/// surface (a plane section, part of the boundary, a vertex, a polyline),
/// signed when the source cuts the surface in two.
///
/// Method and why. We propagate exact windows ourselves (see
/// geodesic_propagation.h: Xin & Wang's improved Chen-Han algorithm, with
/// segment windows for the interior of source segments, as in the
/// polyline-sourced MMP of [16], plus merging of touching windows that carry
/// the same distance function and shadow-cone-only pseudo-source windows at
/// saddle vertices). The distance from points inside source segments is
/// exact, not approximated by subdividing the source: the reference (seed
/// §3.A.1) subdivides the source edges and runs Kirsanov's MMP, whose error
/// is bounded by the subdivision step (1 % of a 3 mm stitch needs a 0.03 mm
/// step: thousands of point sources), and CGAL's Surface_mesh_shortest_path
/// is point-sourced (and, in CGAL 5.5, unreliable for sources on edges). A
/// segment window costs the same as a point window, so a polyline field costs
/// about as much as one vertex-sourced exact run.
///
/// Accuracy: exact up to rounding (absolute tolerance 1e-11 x bounding-box
/// diagonal). Tests: closed forms on flat, L-shaped and developable cylinder
/// meshes (1e-9 relative), CGAL's exact single-source distances on the
/// triple-peak (1e-9), and the subdivided-source band on the triple-peak
/// (within 0.025 mm of CGAL's distance to the 0.05 mm-subdivided source).
///
/// Cost: like every exact window method the number of windows grows about
/// as n^1.5 on curved meshes (each vertex splits the wavefront into pieces
/// with different unfoldings). Measured (2-core machine under load, CPU
/// time, plane x = 0 source): built-in hemisphere (r 75, 13.5k faces) 0.25-
/// 0.31 s, triple_peak.obj (10k faces) 0.13-0.18 s, mannequin_front (26.6k
/// faces, a noisy scan with many saddle vertices) 0.5-0.58 s; about 0.45 µs
/// per window. See docs/geometry.md for the profile.
///
/// Two sides (GeodesicOptions::split_sides, on by default). For a signed
/// source (vertex_side present: source_from_plane(), a cutting
/// source_from_polyline()) the shortest path from a point to the source ends
/// at its first contact with the source curve, so it never crosses it: the
/// two sides are propagated separately, concurrently in two threads, each
/// dropping every window (and edge relaxation) on an edge whose two ends are
/// both on the other side, outside the faces that contain source points. A
/// vertex takes the value of its own side (side 0: the smaller one). This is
/// exact only when the sides match the curve, which is certified first
/// (cheap, conservative; docs/geometry.md "Two sides"): a side-0 vertex lies
/// on the source; a face without source points has three corners of one
/// non-zero side; inside a face with source points, corners of different
/// sides are separated by one connected piece of the source; no piece of an
/// edge lies between two source points without being covered by the source.
/// Otherwise (sides edited by hand, a truncated source whose sides connect
/// around its free end, a side with no vertex) or when a vertex stays
/// unreached on its own side, the single propagation runs instead
/// (GeodesicField::split_sides tells which). Measured: same field as the
/// single propagation (bit for bit on mannequin_front and triple_peak.obj,
/// within 1e-9 x mesh size asserted in the tests), the same windows in total
/// (+0.15 %), about half on each side for the plane x = 0; wall time on the
/// shared 2-core machine at load 2.4-2.9: mannequin_front 451 -> 373 ms
/// exact, 654 -> 341 ms at tolerance 1e-3; hemisphere 230 -> 156 ms. The
/// gain depends on the second core being free (at load 3.3-4.4 it shrank to
/// 10-25 %, none at tolerance 1e-3); the CPU time is unchanged.
///
/// GeodesicSolver builds the connectivity and the unfolded face frames once;
/// each distance() call is then one propagation (or two). The geometry is
/// only read, so one solver may serve concurrent distance() calls. The
/// one-shot geodesic_distance() does both.

#include <memory>
#include <vector>

#include "knitforge/geometry/geodesic_source.h"
#include "knitforge/geometry/tri_mesh.h"

namespace knitforge {

namespace detail {
struct GeodesicGeometry;
}

/// Options of geodesic_distance().
struct GeodesicOptions {
  /// Sign the field when the source carries sides (GeodesicSource::vertex_side,
  /// e.g. a plane source): distances on the -1 side become negative.
  bool signed_field = true;
  /// Approximation tolerance (mm, absolute); 0 (default) = exact, the
  /// same field bit for bit as before the option existed. > 0: windows are
  /// trimmed exactly against the other windows of their edge (MMP-style) and
  /// touching parallel-ray windows (from source segments) are merged into one
  /// family fitted through their outer end values when it deviates from each
  /// by at most tolerance / 10 on its part (Surazhsky et al. 2005's merging);
  /// point windows are never merged. Deviations add up along the wavefront:
  /// measured max |field - exact| over all vertices, plane x = 0 source,
  /// tolerance 1e-3: hemisphere (r 75) 6.0e-4 (windows 0.60 M -> 0.12 M,
  /// field 189 -> 100 ms), mannequin_front 7.3e-4 (1.20 M -> 0.65 M, no
  /// faster: 541 -> 577 ms), triple_peak.obj 1.4e-4 (0.45 M -> 0.23 M,
  /// ~same time); tolerance 3e-3: errors 2.8e-3 / 2.3e-3 / 4.8e-4. The
  /// error is one-sided (measured: the field is at most the exact distance,
  /// never above it). This is a measured, not a proven, bound. Paths
  /// (geodesic_path.h) always use the exact propagation.
  /// The tolerance is an allowance: the approximation pays only where the
  /// wavefront comes mostly from source segments. On meshes where more than
  /// `max_saddle_fraction` of the interior vertices are saddles (their
  /// pseudo-source windows are never merged, and trimming them against the
  /// per-edge index costs more than it saves: mannequin_front 62 % saddles,
  /// triple_peak.obj 76 %, the built-in hemisphere 0 %) the exact field is
  /// computed instead, which is then also faster; GeodesicField::approximate
  /// says which was used.
  /// \throw InvalidInput (from distance()) when negative or not finite.
  double tolerance = 0.0;
  /// See `tolerance`; 1 = approximate whenever tolerance > 0.
  double max_saddle_fraction = 0.25;
  /// Two sides (signed sources, see geodesic_distance()): propagate the two
  /// sides of the source separately and concurrently (two threads) when the
  /// source's vertex_side is certified consistent with the source curve.
  /// Same field up to rounding (1e-9 x mesh size in the tests); false forces
  /// the single propagation.
  bool split_sides = true;
};

/// A per-vertex geodesic distance field.
struct GeodesicField {
  /// Distance (mm) per vertex of the mesh; negative on the -1 side of the
  /// source when `is_signed`. Vertices used by no face get +infinity.
  std::vector<double> distance;
  bool is_signed = false;
  /// Work statistics: windows created by the propagation (the sum of both
  /// side propagations when `split_sides`).
  size_t num_windows = 0;
  /// True when the field came from the two side propagations (see
  /// GeodesicOptions::split_sides), false for the single propagation.
  bool split_sides = false;
  /// True when the approximate propagation was used (GeodesicOptions::tolerance).
  bool approximate = false;
  /// Largest absolute distance over the vertices used by faces (mm).
  double max_abs_distance = 0.0;
};

/// Reusable precomputation for many fields on one mesh (connectivity, edge
/// lengths, unfolded face frames, which vertices can bend geodesics), in the
/// pattern of geometry-central's HeatMethodDistanceSolver.
class GeodesicSolver {
 public:
  /// \throw InvalidInput for an empty mesh or non-finite coordinates;
  ///        TopologyError from build_halfedges() for a non-manifold or
  ///        inconsistently oriented mesh.
  explicit GeodesicSolver(const TriMesh& mesh);
  ~GeodesicSolver();
  GeodesicSolver(GeodesicSolver&&) noexcept;
  GeodesicSolver& operator=(GeodesicSolver&&) noexcept;
  GeodesicSolver(const GeodesicSolver&) = delete;
  GeodesicSolver& operator=(const GeodesicSolver&) = delete;

  /// The field of `source` (see geodesic_distance()). The mesh given to the
  /// constructor must still be alive and unchanged.
  GeodesicField distance(const GeodesicSource& source, const GeodesicOptions& options = {}) const;

  const TriMesh& mesh() const;

 private:
  std::unique_ptr<detail::GeodesicGeometry> geometry_;
};

/// The exact geodesic distance field (mm) from `source`, per vertex.
///
/// Sign: when `options.signed_field` and the source has a vertex_side
/// (source_from_plane(): the side the plane normal points to is positive;
/// source_from_polyline(): the left of the polyline), vertices on the -1 side
/// get the negated distance; otherwise all distances are >= 0.
/// \throw InvalidInput when the source is empty, a source point is invalid
///        (face out of range, bad barycentric coordinates), two consecutive
///        source points share no face, or vertex_side has the wrong size;
///        TopologyError when a vertex used by a face is not reachable from
///        the source (the mesh has a component without source) or the mesh
///        is not manifold; InvalidInput for non-finite coordinates.
GeodesicField geodesic_distance(const TriMesh& mesh, const GeodesicSource& source,
                                const GeodesicOptions& options = {});

}  // namespace knitforge
