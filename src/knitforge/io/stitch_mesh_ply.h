#pragma once
/// \file stitch_mesh_ply.h
/// The stitch mesh file (`stitch_mesh.ply`): a StitchMesh as a PLY polygon
/// mesh with per-face stitch attributes, readable by any PLY viewer (faces are
/// coloured by stitch type) and read back exactly.
///
/// Elements and properties (docs/formats.md):
///   element vertex: double x, y, z (mm)
///   element face:   list uchar int vertex_indices (counter-clockwise, starting
///                   at the canonical corner of core/stitch.h; 4 for Knit,
///                   3 for shaping stitches), uchar type (StitchType value),
///                   char direction (+1/-1), int course, int wale, int yarn,
///                   uchar roles (BoundaryRole flags), uchar red, green, blue
///                   (stitch_type_colour(), for viewers; ignored on reading).

#include <string>
#include <vector>

#include "knitforge/core/stitch_mesh.h"

namespace knitforge {

/// A named per-stitch value written as an extra face property (float),
/// e.g. "shape_error" or "distortion"; viewers (report.html) colour by it.
/// The reader ignores such properties.
struct StitchScalar {
  std::string name;            ///< property name: letters, digits, '_'
  std::vector<double> values;  ///< one per stitch
};

struct StitchMeshPlyOptions {
  /// Text PLY instead of binary little endian. Both are lossless (ascii
  /// writes the shortest decimal that reads back to the same double).
  bool ascii = false;
  /// Extra per-stitch properties, written after the standard ones.
  std::vector<StitchScalar> scalars;
};

/// Writes `mesh` to `path` (atomically).
/// \throw InvalidInput when a coordinate is not finite, a stitch has an
///        unknown type, a direction other than +1/-1, or corner indices that
///        do not match its type or are out of range; when a scalar has a bad
///        name, a standard property's name, or not one value per stitch.
/// \throw IOError when the file cannot be written.
void write_stitch_mesh_ply(const std::string& path, const StitchMesh& mesh,
                           const StitchMeshPlyOptions& options = {});

/// Reads a stitch mesh written by write_stitch_mesh_ply() (ascii, binary
/// little or big endian; properties in any order and of any numeric type).
/// Required: vertex x, y, z; face vertex_indices (or vertex_index), type,
/// direction. Optional: course, wale (default -1), yarn, roles (default 0).
/// Doubles are restored bit for bit.
/// \throw IOError naming the file and line (ascii) or byte offset (binary)
///        for malformed files, an unknown type, a direction other than ±1, a
///        corner count that does not match the type, an index out of range,
///        non-finite coordinates, or a non-manifold / inconsistently oriented
///        polygon mesh.
StitchMesh read_stitch_mesh_ply(const std::string& path);

}  // namespace knitforge
