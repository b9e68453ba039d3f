#pragma once
/// \file dart.h
/// Darts (seed §2.2): cuts that let a non-developable surface flatten with
/// less distortion, and the constraints that make them knittable.
///
/// - By shape: a one-end dart runs from the boundary (its two notches, which
///   are the two copies of the boundary point after cutting) to an interior
///   tip (domes: the stretched boundary shrinks); a two-end dart is a slit
///   with both ends inside (saddles: the stretched centre opens).
/// - By knitting method: a horizontal dart is closed by short rows; its
///   notches must get the same x in the pattern. A vertical dart is closed
///   by short columns; its notches must get the same y. For a two-end dart
///   the "notches" are the two copies of the path's middle point (by length).
///
/// A dart is given as waypoints on the input surface; consecutive waypoints
/// are joined by shortest (geodesic) paths on the surface, computed on the
/// mesh as already cut by the darts before it (so darts do not cross).
#include <string>
#include <string_view>
#include <vector>
#include "knitforge/geometry/mesh_point.h"
#include "knitforge/geometry/tri_mesh.h"
#include "knitforge/geometry/vec.h"

namespace knitforge {

enum class DartType { OneEnd, TwoEnd };
enum class DartOrientation { Horizontal, Vertical };

/// "one-end" / "two-end" (inline: the darts JSON reader needs no geometry).
inline std::string_view to_string(DartType t) { return t == DartType::OneEnd ? "one-end" : "two-end"; }
/// "horizontal" / "vertical".
inline std::string_view to_string(DartOrientation o) {
  return o == DartOrientation::Horizontal ? "horizontal" : "vertical";
}

/// A point of a dart path on the input surface: a vertex, or a face with
/// barycentric coordinates, or a 3D position (mm) snapped to the closest
/// surface point.
struct DartWaypoint {
  int vertex = -1;                                    ///< >= 0: this vertex of the input mesh
  int face = -1;                                      ///< >= 0 (and vertex < 0): a point in this face ...
  Vec3 bary = Vec3(1.0 / 3.0, 1.0 / 3.0, 1.0 / 3.0);  ///< ... at these barycentric coordinates
  bool has_position = false;  ///< true (vertex, face < 0): the surface point closest to `position`
  Vec3 position = Vec3::Zero();
  static DartWaypoint at_vertex(int v) {
    DartWaypoint w;
    w.vertex = v;
    return w;
  }
  static DartWaypoint in_face(int f, const Vec3& b) {
    DartWaypoint w;
    w.face = f;
    w.bary = b;
    return w;
  }
  static DartWaypoint at_position(const Vec3& p) {
    DartWaypoint w;
    w.has_position = true;
    w.position = p;
    return w;
  }
};

/// A dart as the user (or dart_hints.h) specifies it.
struct DartSpec {
  DartType type = DartType::OneEnd;
  DartOrientation orientation = DartOrientation::Horizontal;
  /// Waypoints, at least 2 (1 with to_boundary). A one-end dart must start
  /// or end on the boundary (the path is turned so that it starts there).
  std::vector<DartWaypoint> points;
  /// One-end only: prepend the shortest path from points[0] to the boundary
  /// (then points[0] is the tip side and may be the only point).
  bool to_boundary = false;
};

/// A dart after cutting and flattening.
struct DartResult {
  DartType type = DartType::OneEnd;
  DartOrientation orientation = DartOrientation::Horizontal;
  /// The cut path as vertices of the cut mesh (left-side copies), from the
  /// boundary end (one-end) or the first waypoint (two-end).
  std::vector<int> path;
  int notch_a = -1;              ///< left copy of the notch point (vertex of the cut mesh)
  int notch_b = -1;              ///< right copy
  std::vector<int> tips;         ///< tip vertices: 1 (one-end) or 2 (two-end)
  double length = 0.0;           ///< 3D length of the path (mm)
  double angle_deg = 0.0;        ///< largest angle between the legs at a tip in the pattern
  double angle_limit_deg = 0.0;  ///< the knittability limit for this orientation (dart_angle_limit())
  bool angle_ok = true;          ///< angle_deg <= angle_limit_deg
  double alignment_error = 0.0;  ///< |Δx| (horizontal) or |Δy| (vertical) of the notches (mm)
};

/// The mesh with all darts cut, and the darts in its indices.
struct CutDarts {
  TriMesh mesh;
  std::vector<DartResult> darts;  ///< geometry fields (angles) not yet set
  /// For every vertex of `mesh`, the vertex of the surface with every dart
  /// closed again (the input as split along the darts) it is a copy of:
  /// the two copies of a cut vertex share it. Empty before the first dart
  /// (identity); numbered 0..K-1.
  std::vector<int> vertex_class;
};

/// The surface with every dart of `cut` closed again: one vertex per class
/// of cut.vertex_class (at the position of its copies), the faces of
/// cut.mesh with their vertices replaced by their classes.
TriMesh closed_darts_mesh(const CutDarts& cut);

/// Splits and cuts `mesh` along every dart in order (split_mesh_along_path()
/// then cut_mesh_along_path(), seed §2.B).
/// \pre mesh is a valid disk (require_disk()).
/// \throw InvalidInput naming the dart index (and waypoint index / field)
///        when a waypoint is not on the surface (vertex or face out of range,
///        barycentric coordinates negative or not summing to 1, non-finite
///        position), a dart has too few points, a one-end dart does not
///        reach the boundary or has both ends on it, a two-end dart touches
///        the boundary, or cutting would split the piece in two.
CutDarts cut_darts(const TriMesh& mesh, const std::vector<DartSpec>& darts);

/// Cuts one more dart into `cut` (the input `mesh` as cut by the darts
/// already in `cut`); the dart's index in messages is cut.darts.size().
/// \throw as cut_darts().
void append_dart(CutDarts& cut, const TriMesh& mesh, const DartSpec& spec);

/// The largest knittable angle between the legs of a dart (degrees), from
/// the stitch size w x h (seed §2.2.2, angle constraint), as the rasteriser
/// (rasterize_pattern.h) knits darts:
/// - horizontal: every turn is a pair of short rows (height 2h), and a wale
///   may hold only one turn pair (no four stacked short-row ends), so the
///   turns of the two legs take every other column: each leg rises at most
///   2h per 2w, angle 2 atan(h / w) (77° for 3.5 x 2.8 mm);
/// - vertical: a course may not hold two neighbouring decreases (or
///   increases), so a gap widens on one side per row: each leg moves at most
///   w per 2h, angle 2 atan(w / (2h)) (64° for 3.5 x 2.8 mm).
/// The exact knittability is decided on the final map (check_knittability()).
/// \throw InvalidInput when w or h is not positive.
double dart_angle_limit(DartOrientation orientation, double stitch_width, double stitch_height);

}  // namespace knitforge
