#pragma once
/// \file kinematic_body.h
/// A kinematic body the fabric rests on or is worn over: a triangle mesh
/// whose vertices move as prescribed (a mesh per frame, same faces), with a
/// bounding-volume hierarchy for distance queries. The tree is built once and
/// refit when the body moves (geometry/aabb_tree.h). The mesh need not be
/// closed: distances are unsigned, and the contact barrier with
/// collision-free steps keeps every fabric vertex on the side it starts on.

#include <optional>
#include <vector>

#include "knitforge/geometry/aabb_tree.h"
#include "knitforge/geometry/mesh_measures.h"
#include "knitforge/geometry/tri_mesh.h"

namespace knitforge {

/// The closest point of the body to a query point.
struct BodyPoint {
  int face = -1;
  TrianglePoint where;        ///< closest point, barycentrics, region
  double distance2 = 0.0;     ///< squared distance to the query (mm²)
};

class KinematicBody {
 public:
  KinematicBody() = default;
  /// \throw InvalidInput for a mesh without faces, bad indices or non-finite
  ///        vertices (naming them).
  explicit KinematicBody(TriMesh mesh);

  /// Moves the body's vertices (same count) and refits the tree.
  /// \throw InvalidInput for a wrong count or non-finite positions.
  void move_to(const std::vector<Vec3>& vertices);

  const TriMesh& mesh() const { return mesh_; }
  bool empty() const { return mesh_.faces.empty(); }
  const AabbTree& tree() const { return tree_; }

  /// The closest body point to p if it is within max_distance (mm).
  std::optional<BodyPoint> closest_point_within(const Vec3& p, double max_distance) const;
  /// The point of `face` with barycentrics `bary` (mm).
  Vec3 point(int face, const Vec3& bary) const;
  /// Unit normal of `face` (zero when degenerate).
  Vec3 face_normal(int face) const;

 private:
  TriMesh mesh_;
  AabbTree tree_;
};

/// The face boxes of a mesh at positions `vertices` (merged with those at
/// `vertices_end` when given: swept boxes of a moving mesh).
std::vector<Aabb> face_boxes(const TriMesh& mesh, const std::vector<Vec3>* vertices_end = nullptr);

}  // namespace knitforge
