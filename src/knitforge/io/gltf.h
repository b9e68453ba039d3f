#pragma once
/// \file gltf.h
/// glTF 2.0 binary (.glb) writer for coloured triangle meshes (yarn tubes,
/// stitch meshes), viewable in any glTF viewer, Blender and three.js.
///
/// Layout (glTF 2.0 specification, "GLB File Format Specification"):
/// a 12-byte header (magic "glTF", version 2, total length), a JSON chunk
/// (padded with spaces to 4 bytes) and one BIN chunk (padded with zeros).
/// Per mesh, the BIN chunk holds, each 4-byte aligned and in its own
/// bufferView with a target: POSITION (float32 VEC3, accessor min/max),
/// NORMAL (float32 VEC3, unit length) when the mesh has normals, COLOR_0
/// (normalised unsigned byte VEC4, alpha 255) when it has vertex or face
/// colours, and the indices (uint32 SCALAR, ELEMENT_ARRAY_BUFFER). Colours
/// are converted from sRGB to the linear values glTF requires. A mesh with
/// face colours is written unindexed in effect (three vertices per triangle,
/// each with its face's colour). Every mesh has a material (metallic 0,
/// roughness 0.8; base colour = RenderMesh::colour when it has no colours,
/// else white) and one node in the default scene. Meshes without triangles
/// are skipped (at least one mesh must have a triangle). The BIN chunk is streamed from the meshes, so memory
/// stays at the size of the input.

#include <span>
#include <string>

#include "knitforge/render/render_mesh.h"

namespace knitforge {

/// Writes `meshes` to `path` as one .glb (see the file comment), atomically.
/// \throw InvalidInput for an invalid mesh (validate_render_mesh, naming it)
///        or a file that would exceed the 4 GiB GLB limit, or when no mesh
///        has a triangle; IOError when the
///        file cannot be written.
void write_glb(const std::string& path, std::span<const RenderMesh> meshes);

/// sRGB 8-bit -> linear 8-bit (rounded), as written to COLOR_0.
uint8_t srgb_to_linear_byte(uint8_t c);

}  // namespace knitforge
