#pragma once
/// \file isocurves.h
/// Robust isocurve (level-set) extraction of a piecewise-linear scalar field
/// on a triangle mesh (seed §3.A.2, Fig. 3.23), used for the wale curves of
/// the short-row route (seed §3.2.1: isocurves of the geodesic field every
/// stitch width) and as input of mesh splitting (seed §2.B).
///
/// Algorithm (three rounds, as in the seed):
///  1. vertex round: a vertex whose value is within the tolerance of the level
///     is "on the level" (sign 0) and becomes an isocurve point itself;
///  2. edge round: an edge whose end values are strictly on opposite sides
///     (signs + and -) gets one crossing point at the linear interpolation;
///  3. face round: per face, by its sign triplet (Fig. 3.23):
///     (-,-,+)/(-,+,+): a segment between two edge crossings;
///     (0,-,+): a segment from the vertex to the crossing on the opposite edge;
///     (0,-,-)/(0,+,+): nothing (the level only touches the vertex);
///     (0,0,±): the edge between the two on-level vertices;
///     (0,0,0): a flat region; only the edges on the border of the flat region
///     (shared with a face that is not flat) are isocurve segments, so a flat
///     region is outlined by its border, never filled with edges.
///  An on-level edge is emitted exactly once however many faces see it; an
///  on-level edge on the mesh boundary is emitted unless its face is flat.
///  Vertices on the level whose neighbours are all on one side (touching
///  points) produce no isocurve.
///
/// Points are identified by mesh vertex or mesh edge, so neighbouring faces
/// share their isocurve points and no duplicates arise. Segments are joined
/// into maximal manifold chains: a point where more than two segments meet
/// (a saddle of the field exactly on the level, or a flat region touching
/// the curve) is a *junction*; chains end there and are flagged
/// (`starts_at_junction` / `ends_at_junction`). A chain whose two ends are the
/// same point without a junction is closed.
///
/// Orientation: every chain runs along n x grad F (n the face normal, from
/// the counter-clockwise vertex order), i.e. seen from the front (normal)
/// side, the field INCREASES TO THE RIGHT of the walking direction and
/// decreases to the left. This is the wale direction of seed §3.2.1. Chains
/// along on-level edges whose two sides lie on the same side of the level
/// (touching) have no preferred direction; they take the majority direction
/// of the chain they belong to, or a deterministic one.
///
/// All outputs are deterministic (independent of hash order).

#include <vector>

#include "knitforge/geometry/mesh_point.h"
#include "knitforge/geometry/tri_mesh.h"
#include "knitforge/geometry/vec.h"

namespace knitforge {

/// Options of isocurve extraction.
struct IsocurveOptions {
  /// Absolute snapping tolerance (field units): a vertex with
  /// |F(v) - level| <= tolerance is on the level. The effective tolerance is
  /// max(tolerance, relative_tolerance * (max F - min F)).
  double tolerance = 0.0;
  /// Tolerance relative to the range of the field (see `tolerance`).
  double relative_tolerance = 1e-10;
};

/// One maximal manifold isocurve chain.
struct Isocurve {
  double value = 0.0;                ///< the level
  bool closed = false;               ///< true: points.back() connects to points.front()
  std::vector<MeshPoint> points;  ///< vertex points or edge points (ratio in (0, 1))
  std::vector<Vec3> positions;       ///< 3D positions of `points` (mm)
  /// faces[i] is a face containing the segment points[i] -> points[i+1]
  /// (points[n-1] -> points[0] for i = n-1 of a closed curve); size n-1 (open)
  /// or n (closed). For a segment along a mesh edge it is the face on the
  /// side where the field is larger (right of the walking direction) when
  /// that face exists, otherwise the other face.
  std::vector<int> faces;
  bool starts_at_junction = false;  ///< points.front() is a non-manifold junction
  bool ends_at_junction = false;    ///< points.back() is a non-manifold junction

  int num_points() const { return static_cast<int>(points.size()); }
  /// Length of the polyline (closing segment included when closed), mm.
  double length() const;
};

/// Extracts the isocurve F = value of the piecewise-linear field F (one value
/// per vertex) as maximal manifold chains, in a deterministic order (open
/// chains first, from their lowest end node; then closed chains).
/// \pre mesh is edge-manifold and consistently oriented.
/// \throw InvalidInput when field.size() != mesh.num_vertices(), a field value
///        or `value` is not finite, or a tolerance is negative / not finite.
/// \throw TopologyError from build_halfedges() for non-manifold meshes.
std::vector<Isocurve> extract_isocurve(const TriMesh& mesh, const std::vector<double>& field,
                                       double value, const IsocurveOptions& options = {});

/// Extracts the isocurves of many levels in one pass over the faces: per face
/// only the levels within its value range are visited (binary search in the
/// sorted levels), so the cost is O(faces log levels + output). Result[i]
/// holds the chains of values[i], exactly as extract_isocurve() would return
/// them. The tolerance is computed once from the field.
/// \throw InvalidInput as extract_isocurve(), also for a non-finite level.
std::vector<std::vector<Isocurve>> extract_isocurves(const TriMesh& mesh,
                                                     const std::vector<double>& field,
                                                     const std::vector<double>& values,
                                                     const IsocurveOptions& options = {});

/// Levels every `spacing` field units: first + k spacing for k = 0, 1, ...
/// while <= last (with a relative slack of 1e-9 spacing).
/// \throw InvalidInput when spacing <= 0 or a value is not finite.
std::vector<double> isocurve_levels(double first, double last, double spacing);

/// Gradient of the piecewise-linear field on every face (field units per mm,
/// a vector in the plane of the face); zero for a degenerate face.
/// \throw InvalidInput when field.size() != mesh.num_vertices().
std::vector<Vec3> field_face_gradients(const TriMesh& mesh, const std::vector<double>& field);

/// Unit wale direction n x grad F / |grad F| per face (seed §3.2.1): the
/// walking direction of the isocurves of extract_isocurve(). Zero where the
/// gradient or the face vanishes.
/// \throw InvalidInput when field.size() != mesh.num_vertices().
std::vector<Vec3> wale_directions(const TriMesh& mesh, const std::vector<double>& field);

}  // namespace knitforge
