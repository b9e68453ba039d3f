#pragma once
/// \file ply.h
/// PLY triangle-mesh reader and writer (see mesh_io.h for the dispatcher and
/// docs/formats.md for the accepted dialect).

#include <string>

#include "knitforge/geometry/tri_mesh.h"
#include "knitforge/io/mesh_io.h"

namespace knitforge {

/// Reads a PLY file into a triangle mesh (polygons fan-triangulated).
/// \throw IOError naming the file and line (or byte offset) on any problem:
///        missing/empty/truncated file, bad counts or indices, non-finite
///        coordinates, no faces, non-manifold or inconsistently oriented mesh.
TriMesh read_ply(const std::string& path);

/// Writes `mesh` as PLY, atomically.
/// \throw InvalidInput for bad indices, non-finite coordinates, wrong-sized or
///        unsupported colours; IOError when the file cannot be written.
void write_ply(const std::string& path, const TriMesh& mesh, const MeshWriteOptions& options = {});

}  // namespace knitforge
