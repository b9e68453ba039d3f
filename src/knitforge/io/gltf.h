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

#include "knitforge/core/knit_params.h"
#include "knitforge/core/yarn_model.h"
#include "knitforge/render/render_mesh.h"
#include "knitforge/render/yarn_tubes.h"

namespace knitforge {

/// Writes `meshes` to `path` as one .glb (see the file comment), atomically.
/// \throw InvalidInput for an invalid mesh (validate_render_mesh, naming it)
///        or a file that would exceed the 4 GiB GLB limit, or when no mesh
///        has a triangle; IOError when the
///        file cannot be written.
void write_glb(const std::string& path, std::span<const RenderMesh> meshes);

/// Writes the tubes of every yarn (the geometry of yarn_tubes(yarn, params,
/// options, colours), rounded to float32) to `path` as one .glb, atomically,
/// straight from the tube rings without building RenderMeshes: the fast path
/// for large models. The file takes about 36 bytes per tube vertex; memory
/// holds only the yarns' smoothed centre lines and one primitive at a time
/// (the JSON is written first with fixed-width slots for the position
/// bounds, which are filled in once the vertices are made). A 100k-stitch
/// model at the preview detail (vertices_per_ply 1, ring_spacing 1 mm,
/// uncapped: 11M vertices, 400 MB) takes about 0.6 s on one core.
/// Layout: one mesh, node and material per yarn with at least 2 distinct
/// points (named "yarn <id>", base colour = the yarn's colour, no COLOR_0);
/// the tube's side is split into primitives of at most 65535 vertices that
/// share their boundary ring, each with float32 POSITION (accessor min/max),
/// float32 unit NORMAL and unsigned-short indices (unsigned int when a ring
/// alone has more than 32767 vertices); capped tubes get one more primitive
/// with both caps. Every bufferView is 4-byte aligned.
/// \throw InvalidInput for bad options or yarn points (naming the yarn), no
///        yarn with a tube, or more than the 4 GiB a GLB holds; IOError when
///        the file cannot be written.
/// \return the number of meshes written and the tubes' vertices and
///         triangles as yarn_tubes() would make them (the file repeats one
///         ring per primitive boundary).
struct YarnGlbSummary {
  size_t meshes = 0;
  size_t vertices = 0;
  size_t triangles = 0;
};
YarnGlbSummary write_yarn_glb(const std::string& path, const YarnModel& yarn, const KnitParams& params,
                              const TubeOptions& options = {}, std::span<const RenderColour> colours = {});

/// A triangle mesh whose vertices move: the same faces in every frame.
struct AnimatedMesh {
  std::string name;
  RenderColour colour{200, 200, 200};  ///< sRGB base colour
  std::vector<std::array<int, 3>> faces;
  std::vector<std::vector<Vec3>> frames;  ///< vertex positions per frame (mm)
};

/// Writes `meshes`, animated over the frame times `times_s` (one per frame,
/// increasing), as one .glb, atomically. Per mesh: one node and a
/// double-sided material; POSITION = frame 0 (float32, min/max), uint32
/// indices, and one morph target per later frame k (POSITION = frame k -
/// frame 0, with min/max as the specification requires). One animation
/// "motion" drives every mesh's morph weights with LINEAR interpolation:
/// at time t_k the weights are the unit vector of target k (all 0 at t_0),
/// so between two frames the positions interpolate linearly. No normals
/// (viewers shade flat). With one frame the meshes are static (no targets,
/// no animation). The file is about 12 bytes per vertex and frame plus 4
/// bytes per frame squared per mesh (the weights).
/// \throw InvalidInput for no frame times, times not increasing, a frame
///        count or vertex count that differs, a bad index, a coordinate
///        that overflows float32, or more than the 4 GiB a GLB holds;
///        IOError when the file cannot be written.
void write_animation_glb(const std::string& path, std::span<const AnimatedMesh> meshes,
                         std::span<const double> times_s);

/// sRGB 8-bit -> linear 8-bit (rounded), as written to COLOR_0.
uint8_t srgb_to_linear_byte(uint8_t c);

}  // namespace knitforge
