#pragma once
/// \file geodesic_source.h
/// Sources of the geodesic distance field of the short-row route (seed §3.2.1,
/// §3.A.1): polylines lying ON the surface, made of points given as surface
/// points (face + barycentric coordinates, exactly on an edge or at a vertex
/// when a coordinate is zero). Consecutive points of a polyline share a face;
/// the segment between them is the straight segment inside that face (or along
/// the shared edge). A polyline of one point is a point source.
///
/// Builders: the intersection of the surface with a plane (the symmetry plane
/// of a garment), part of the boundary loop by arc-length fractions or by
/// vertex ids, a single vertex, or a 3D polyline projected onto the surface.
/// A source that cuts the surface into two sides carries a per-vertex side
/// (+1 / -1, 0 on the source) so that geodesic_distance() can sign the field.

#include <string>
#include <vector>

#include "knitforge/geometry/tri_mesh.h"
#include "knitforge/geometry/vec.h"

namespace knitforge {

/// A point on a triangle mesh: barycentric coordinates `bary` (non-negative,
/// summing to 1) with respect to the vertices faces[face][0..2]. A point on
/// an edge has the coordinate of the opposite corner exactly 0; a point at a
/// vertex has that vertex's coordinate exactly 1 and the others 0.
struct SurfacePoint {
  int face = -1;
  Vec3 bary = Vec3(1.0 / 3.0, 1.0 / 3.0, 1.0 / 3.0);
};

/// Position (mm) of a surface point.
/// \pre 0 <= p.face < mesh.num_faces().
Vec3 surface_point_position(const TriMesh& mesh, const SurfacePoint& p);

/// The surface point at vertex v (in the first face that uses it).
/// \throw InvalidInput when v is out of range or used by no face.
SurfacePoint surface_point_at_vertex(const TriMesh& mesh, int v);

/// The surface point on edge (v0, v1) at ratio t: position (1 - t) v0 + t v1.
/// \throw InvalidInput when t is outside [0, 1] or (v0, v1) is not an edge.
SurfacePoint surface_point_on_edge(const TriMesh& mesh, int v0, int v1, double t);

/// The surface point of `mesh` closest to `p` (brute force over the faces,
/// O(#faces)); on an edge or vertex the barycentric zeros are exact.
/// \throw InvalidInput when the mesh has no faces or p is not finite.
SurfacePoint closest_surface_point(const TriMesh& mesh, const Vec3& p);

/// A source of a geodesic distance field: polylines on the surface.
struct GeodesicSource {
  /// Each polyline: points in order; consecutive points must share a face
  /// (checked by geodesic_distance()). A single point is a point source.
  std::vector<std::vector<SurfacePoint>> polylines;
  /// Per-vertex side of the source, used to sign the field: +1 or -1 on the
  /// two sides of a source that cuts the surface in two, 0 on the source.
  /// Empty when the source does not separate the surface (boundary, vertex,
  /// open curve): the field is then unsigned.
  std::vector<signed char> vertex_side;
  /// What the source is, for messages and reports ("plane x = 0", ...).
  std::string description;

  /// Number of source segments (pairs of consecutive points).
  int num_segments() const;
  /// Total length (mm) of the polylines.
  double length(const TriMesh& mesh) const;
};

/// The intersection of the surface with a plane (seed §3.2.1).
///
/// The plane is {x : n̂·x = offset} with n̂ = normal / |normal|, so `offset` is
/// the signed distance of the plane from the origin in mm. Vertices within
/// 1e-9 x (bounding-box diagonal) of the plane are taken as on it. The result
/// may be several polylines (one per connected piece of the intersection);
/// faces lying in the plane contribute their edges. Seed §3.2.1: the
/// symmetry plane of a garment piece.
///
/// Side: vertex_side[v] = sign(n̂·x_v - offset), so the half-space the normal
/// points to is positive. Because the field of geodesic_distance() is
/// piecewise linear and the plane's signed distance is linear on every face,
/// the two sides of the surface are exactly the two half-spaces.
/// \throw InvalidInput when the normal is zero or not finite, the offset is
///        not finite, the mesh has no faces, or the plane misses the surface
///        (the message gives the range of n̂·x over the mesh).
GeodesicSource source_from_plane(const TriMesh& mesh, const Vec3& normal, double offset);

/// The part of a boundary loop from arc-length fraction `begin_fraction` to
/// `end_fraction`, measured from the loop's first vertex (its smallest vertex
/// id, as in Halfedges::boundary_loops()) in the loop's direction (surface on
/// the left). When begin > end the part wraps around through the first
/// vertex; begin == end gives a single point; (0, 1) is the whole loop
/// (closed polyline). Points inside boundary edges are exact edge points.
/// `loop` indexes Halfedges::boundary_loops() (sorted by smallest vertex).
/// Unsigned (the boundary does not separate the surface).
/// \throw InvalidInput when a fraction is outside [0, 1] or not finite, the
///        loop index is out of range (the message gives the number of loops),
///        or the mesh is not a valid surface (TopologyError from
///        build_halfedges()).
GeodesicSource source_from_boundary(const TriMesh& mesh, double begin_fraction, double end_fraction,
                                    int loop = 0);

/// The given boundary vertices and the boundary edges joining two of them
/// (runs of consecutive boundary vertices become polylines along the
/// boundary; isolated ones are point sources). Order and duplicates in `ids`
/// do not matter. Unsigned.
/// \throw InvalidInput when `ids` is empty or an id is out of range or not on
///        the boundary (the message names it).
GeodesicSource source_from_boundary_vertices(const TriMesh& mesh, const std::vector<int>& ids);

/// A single vertex (any vertex; seed §3.2.1 asks for a boundary vertex so that
/// the isocurves are open). Unsigned.
/// \throw InvalidInput when v is out of range or used by no face.
GeodesicSource source_from_vertex(const TriMesh& mesh, int v);

/// Paths of mesh vertices (consecutive vertices joined by a mesh edge; a
/// path of one vertex is a point source), e.g. a source carried over to a
/// surface that was cut open (cut_to_disk.h). Signed when the paths cut
/// the surface into exactly two parts (source_sides()).
/// \throw InvalidInput when a vertex is out of range or used by no face,
///        two consecutive vertices are not joined by an edge, or no path
///        has a vertex; TopologyError from build_halfedges().
GeodesicSource source_from_vertex_paths(const TriMesh& mesh, const std::vector<std::vector<int>>& paths,
                                       const std::string& description);

/// The per-vertex sides of a source (GeodesicSource::vertex_side) when its
/// polylines cut the surface into exactly two parts (the vertices used by
/// faces, minus those on the source, fall into two components across edges
/// the source neither ends on nor crosses); empty otherwise. The part on the
/// left of the first segment of positive length (looking along the face
/// normal) is +1, vertices on the source are 0.
/// \pre the source points are valid for `mesh`.
std::vector<signed char> source_sides(const TriMesh& mesh, const GeodesicSource& source);

/// A 3D polyline projected onto the surface: every point goes to its closest
/// surface point (a barycentric coordinate below 1e-9 is snapped to zero, so
/// a point within rounding of an edge or a vertex lies on it exactly);
/// consecutive projected points are joined along the surface by the
/// intersection of the surface with the plane through both points that
/// contains their mean surface normal (a normal section, which is the
/// straight segment on a flat part), taken as the shortest way along that
/// section between them among the faces near them; where the section does
/// not join them there (it leaves the surface through the boundary, or the
/// normals are parallel to the segment), by the shortest path on the surface
/// (geodesic_path()). Consecutive points should be close compared with the
/// surface's curvature radius (a few stitch widths) for the normal section
/// to be what is meant. Repeated points are dropped. The polyline is closed
/// when its last point equals its first.
///
/// Side: when the projected polyline is closed or starts and ends on the
/// boundary and cuts the surface into exactly two parts, vertex_side is set:
/// positive on the left of the polyline direction (looking along the surface
/// normal, i.e. the side n × t points to, t the tangent); otherwise unsigned.
/// \throw InvalidInput when `points` is empty or has a non-finite point, or
///        two consecutive points lie on different parts of the surface (the
///        message names the pair).
GeodesicSource source_from_polyline(const TriMesh& mesh, const std::vector<Vec3>& points);

}  // namespace knitforge
