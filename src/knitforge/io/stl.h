#pragma once
/// \file stl.h
/// STL triangle-mesh reader and writer (see mesh_io.h for the dispatcher and
/// docs/formats.md for the accepted dialect).

#include <string>

#include "knitforge/geometry/tri_mesh.h"
#include "knitforge/io/mesh_io.h"

namespace knitforge {

/// Reads an STL file (ascii or binary, detected from the content) into a
/// triangle mesh. Corners at exactly the same position are welded into one
/// vertex; triangles whose corners coincide after welding are dropped.
/// \throw IOError naming the file and line (or byte offset) on any problem:
///        missing/empty/truncated file, bad counts or indices, non-finite
///        coordinates, no faces, non-manifold or inconsistently oriented mesh.
TriMesh read_stl(const std::string& path);

/// Writes `mesh` as STL (binary unless options.ascii), atomically. STL stores
/// 32-bit floats and no colours.
/// \throw InvalidInput for bad indices, non-finite coordinates, wrong-sized or
///        unsupported colours; IOError when the file cannot be written.
void write_stl(const std::string& path, const TriMesh& mesh, const MeshWriteOptions& options = {});

}  // namespace knitforge
