#pragma once
/// \file polyline_obj.h
/// Polylines as Wavefront OBJ line elements: the yarn model (one object
/// `yarn_<id>` per yarn) and any other curve set (wale curves, isocurves).
/// Each polyline is written as `o <name>`, its `v` lines and one
/// `l i1 i2 ... in` element (a single point as `p i`); coordinates are
/// written losslessly. Any OBJ viewer (MeshLab, Blender) shows them.

#include <string>
#include <vector>

#include "knitforge/core/yarn_model.h"
#include "knitforge/geometry/vec.h"

namespace knitforge {

/// A polyline read from an OBJ file with the name of its object/group.
struct NamedPolyline {
  std::string name;          ///< the current `o` (or `g`) name, "" when none
  std::vector<Vec3> points;  ///< in the order of the element's indices
};

/// Writes one object `yarn_<id>` per yarn with its polyline in knitting
/// order. The per-point stitch tags are not stored (geometry only).
/// \throw InvalidInput for a non-finite point or a point/stitch size mismatch.
/// \throw IOError when the file cannot be written.
void write_yarn_obj(const std::string& path, const YarnModel& yarns);

/// Writes each polyline as an object named names[i] ("polyline_<i>" when
/// `names` is empty or names[i] is empty). An empty polyline is written as
/// its `o` line only (read_polylines_obj() does not return it).
/// \throw InvalidInput when names.size() is neither 0 nor polylines.size(), a
///        name contains a line break or '#', or a point is not finite.
/// \throw IOError when the file cannot be written.
void write_polylines_obj(const std::string& path, const std::vector<std::vector<Vec3>>& polylines,
                         const std::vector<std::string>& names = {});

/// Reads every `l` element (and every point of a `p` element, as a
/// one-point polyline) of an OBJ file, in file order, named by the object
/// or group it belongs to. Faces and other statements are ignored. Index forms
/// v, v/vt, v/vt/vn and negative (relative) indices are accepted.
/// \throw IOError with file and line for a missing or empty file, a bad or
///        out-of-range index, a line element with fewer than 2 vertices, or a
///        non-finite coordinate.
std::vector<NamedPolyline> read_polylines_obj(const std::string& path);

}  // namespace knitforge
