#pragma once
/// \file kinematic_body.h
/// A kinematic body the fabric rests on or is worn over: a triangle mesh
/// whose vertices move as prescribed (a mesh per frame, same faces), with a
/// bounding-volume hierarchy for distance queries. The tree is built once and
/// refit when the body moves (geometry/aabb_tree.h). The mesh need not be
/// closed: distances are unsigned, and the contact barrier with
/// collision-free steps keeps every fabric vertex on the side it starts on.
///
/// **Parts.** The body is made of parts (the two capsules of the built-in
/// arm; a torso and upper arms; ...), one label per face: given by whoever
/// made the mesh, or by default its connected components (faces sharing a
/// vertex), so a plain OBJ of one closed surface is one part. Contact is per
/// part (contact_candidates.h): a fabric vertex within d̂ of two parts (the
/// crook of an elbow, an armpit) is pushed away from both, not only from
/// the closer one.

#include <optional>
#include <vector>

#include "knitforge/geometry/aabb_tree.h"
#include "knitforge/geometry/mesh_measures.h"
#include "knitforge/geometry/tri_mesh.h"

namespace knitforge {

/// The closest point of the body to a query point.
struct BodyPoint {
  int face = -1;
  int part = 0;               ///< the face's part
  TrianglePoint where;        ///< closest point, barycentrics, region
  double distance2 = 0.0;     ///< squared distance to the query (mm²)
};

/// The orthonormal frame of triangle `face` of `mesh` with its vertices at
/// `positions` (the mesh's own, or a pose of it): columns the first edge's
/// direction, normal x edge, and the unit normal (not finite when the
/// triangle is degenerate). A rigid motion of the triangle moves its frame
/// with it.
Mat3 face_frame(const TriMesh& mesh, const std::vector<Vec3>& positions, int face);

class KinematicBody {
 public:
  KinematicBody() = default;
  /// `face_parts`: empty (the parts are the mesh's connected components,
  /// numbered in the order of their smallest face), or one part label per
  /// face in 0..P-1, each label used.
  /// \throw InvalidInput for a mesh without faces, bad indices or non-finite
  ///        vertices, a wrong number of labels or a label out of range or
  ///        unused (naming them).
  explicit KinematicBody(TriMesh mesh, std::vector<int> face_parts = {});

  /// Moves the body's vertices (same count) and refits the tree.
  /// \throw InvalidInput for a wrong count or non-finite positions.
  void move_to(const std::vector<Vec3>& vertices);

  const TriMesh& mesh() const { return mesh_; }
  bool empty() const { return mesh_.faces.empty(); }
  const AabbTree& tree() const { return tree_; }

  /// Number of parts (>= 1), and the part of each face.
  int num_parts() const { return num_parts_; }
  int face_part(int face) const { return face_parts_[face]; }
  const std::vector<int>& face_parts() const { return face_parts_; }

  /// The closest body point to p if it is within max_distance (mm); on equal
  /// distances the lowest face.
  std::optional<BodyPoint> closest_point_within(const Vec3& p, double max_distance) const;
  /// The closest point of each part that comes within max_distance of p
  /// (mm), in part order: one entry per such part (ties as above). For a
  /// one-part body, closest_point_within() as a list.
  std::vector<BodyPoint> closest_points_per_part_within(const Vec3& p, double max_distance) const;
  /// The closest point of part `part` to p if it is within max_distance
  /// (part -1: of any part, as closest_point_within()).
  std::optional<BodyPoint> closest_point_of_part_within(const Vec3& p, int part, double max_distance) const;
  /// The point of `face` with barycentrics `bary` (mm).
  Vec3 point(int face, const Vec3& bary) const;
  /// Unit normal of `face` (zero when degenerate).
  Vec3 face_normal(int face) const;

 private:
  TriMesh mesh_;
  AabbTree tree_;
  std::vector<int> face_parts_;
  int num_parts_ = 1;
};

/// Part labels of the connected components of a mesh (faces sharing a
/// vertex), numbered in the order of each component's smallest face; writes
/// the count to *count when given.
std::vector<int> mesh_component_parts(const TriMesh& mesh, int* count = nullptr);

/// The face boxes of a mesh at positions `vertices` (merged with those at
/// `vertices_end` when given: swept boxes of a moving mesh).
std::vector<Aabb> face_boxes(const TriMesh& mesh, const std::vector<Vec3>* vertices_end = nullptr);

}  // namespace knitforge
