#pragma once
/// \file mesh_io.h
/// Reading and writing triangle meshes (the input surfaces of every design
/// route), dispatched by file extension: .obj, .ply, .off, .stl (case
/// insensitive). Polygons are fan-triangulated on reading. Every reader checks
/// the content and the connectivity (build_halfedges): a malformed file gives
/// an IOError naming the file and the line (text) or byte offset (binary),
/// never a partial mesh. The accepted dialects are listed in docs/formats.md.

#include <string>
#include <vector>

#include "knitforge/geometry/tri_mesh.h"
#include "knitforge/io/colours.h"

namespace knitforge {

/// Options of the mesh writers.
struct MeshWriteOptions {
  /// PLY and STL: text instead of binary (little endian). OBJ and OFF are
  /// always text. Default: binary.
  bool ascii = false;
  /// Empty, or one colour per vertex. PLY: red/green/blue vertex properties;
  /// OBJ: the common "v x y z r g b" extension (r, g, b in [0, 1]); OFF:
  /// written as COFF. Not supported by STL.
  std::vector<Rgb> vertex_colours;
  /// Empty, or one colour per face. PLY: red/green/blue face properties; OFF:
  /// "r g b" after the indices. Not supported by OBJ and STL.
  std::vector<Rgb> face_colours;
};

/// Reads a triangle mesh, choosing the format by the extension of `path`.
/// Vertices are in the file's units; unused vertices are kept.
/// \throw IOError (with file and line or byte offset) when the file is
///        missing, empty, truncated, malformed, has no faces, bad indices,
///        non-finite coordinates, or is not an oriented edge-manifold mesh;
///        also for an unknown extension.
TriMesh read_mesh(const std::string& path);

/// Writes a triangle mesh, choosing the format by the extension of `path`
/// (.obj, .ply, .off, .stl). The file is written atomically. Coordinates are
/// written losslessly (shortest exact decimal or binary double), except STL
/// which stores 32-bit floats.
/// \throw InvalidInput when a face index is out of range, a coordinate is not
///        finite, a colour array has the wrong size, the format cannot store
///        the requested colours, or the extension is unknown.
/// \throw IOError when the file cannot be written.
void write_mesh(const std::string& path, const TriMesh& mesh, const MeshWriteOptions& options = {});

}  // namespace knitforge
