#pragma once
/// \file mesh_measures.h
/// Small geometric measures of a TriMesh: face normals and areas, vertex
/// normals, bounding box, edge-length statistics, closest points on
/// triangles. All lengths are millimetres, areas mm².
///
/// These functions assume valid vertex indices (see validate_surface() in
/// surface_checks.h); they do not build connectivity. A degenerate face has a
/// zero normal and zero area.

#include <vector>

#include <Eigen/Geometry>  // cross()

#include "knitforge/geometry/tri_mesh.h"
#include "knitforge/geometry/vec.h"

namespace knitforge {

/// (b - a) x (c - a): twice the area times the unit normal of triangle abc
/// (counter-clockwise orientation).
Vec3 triangle_area_vector(const Vec3& a, const Vec3& b, const Vec3& c);

/// Area of triangle abc (mm²).
double triangle_area(const Vec3& a, const Vec3& b, const Vec3& c);

/// Unit normal of face f (right-hand rule on its vertex order); zero for a
/// degenerate face.
Vec3 face_normal(const TriMesh& mesh, int f);

/// Unit normal per face (see face_normal()).
std::vector<Vec3> face_normals(const TriMesh& mesh);

/// Area per face (mm²).
std::vector<double> face_areas(const TriMesh& mesh);

/// Sum of the face areas (mm²).
double total_area(const TriMesh& mesh);

/// Area-weighted vertex normals (sum of the incident faces' area vectors,
/// normalised); zero for isolated vertices.
std::vector<Vec3> vertex_normals(const TriMesh& mesh);

/// Axis-aligned bounding box.
struct BoundingBox {
  Vec3 min = Vec3::Zero();
  Vec3 max = Vec3::Zero();
  Vec3 size() const { return max - min; }
  Vec3 center() const { return 0.5 * (min + max); }
  double diagonal() const { return (max - min).norm(); }
};

/// Bounding box of the vertices (all of them, used or not).
/// \throw InvalidInput when the mesh has no vertices.
BoundingBox bounding_box(const TriMesh& mesh);

/// Length of every undirected edge, each counted once (edges are ordered by
/// their (smaller, larger) vertex pair, so the result is deterministic).
std::vector<double> edge_lengths(const TriMesh& mesh);

/// Statistics of the undirected edge lengths (mm); all zero for a mesh
/// without faces.
struct EdgeLengthStats {
  int count = 0;
  double min = 0.0;
  double mean = 0.0;
  double max = 0.0;
};
EdgeLengthStats edge_length_stats(const TriMesh& mesh);

/// The point of segment ab closest to p.
Vec3 closest_point_on_segment(const Vec3& p, const Vec3& a, const Vec3& b);

/// The point of the (solid) triangle abc closest to p; correct also for
/// degenerate triangles.
Vec3 closest_point_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c);

/// The closest point of triangle abc to p with where it lies: in the
/// interior (Face), on an edge (Edge, `feature` 0 = ab, 1 = bc, 2 = ca) or at
/// a corner (Vertex, `feature` 0 = a, 1 = b, 2 = c), and its barycentric
/// coordinates (point = bary[0] a + bary[1] b + bary[2] c). A degenerate
/// triangle (zero area) reports the closest of its three edges.
struct TrianglePoint {
  enum class Region { Face, Edge, Vertex };
  Vec3 point = Vec3::Zero();
  Vec3 bary = Vec3::Zero();
  Region region = Region::Face;
  int feature = 0;
};
TrianglePoint closest_triangle_point(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c);

/// Euclidean distance from p to triangle abc.
double point_triangle_distance(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c);

}  // namespace knitforge
