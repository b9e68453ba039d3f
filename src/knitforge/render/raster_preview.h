#pragma once
/// \file raster_preview.h
/// Software z-buffer preview of triangle meshes (no GPU, no browser): for
/// quick pictures of stitch meshes and yarn tubes in the CLI, docs and
/// reports (seed §1.A; the seed renders with Blender, this is a preview).
///
/// Triangles are projected with the camera (camera.h; the camera's aspect is
/// replaced by width / height), scan-converted at pixel centres, depth-tested
/// on the NDC depth (which is affine across a projected triangle, so the
/// z-buffer is exact per pixel centre) and shaded
///   colour * (ambient + (1 - ambient) * max(0, n . l))
/// with n the interpolated vertex normal (or the face normal) and l the light
/// direction in view space. Colours per face or per vertex (RenderMesh
/// precedence). Optional edge lines are drawn after the triangles with the
/// same depth test and a small bias, so hidden lines stay hidden.
/// Deterministic; cost O(pixels + triangles + covered pixels).

#include <span>

#include "knitforge/core/stitch_mesh.h"
#include "knitforge/render/camera.h"
#include "knitforge/render/render_mesh.h"

namespace knitforge {

struct RasterOptions {
  int width = 800;   ///< image width (px), 1..16384
  int height = 600;  ///< image height (px), 1..16384
  RenderColour background{255, 255, 255};
  bool shading = true;   ///< Lambert shading; false = flat, unshaded colours
  double ambient = 0.3;  ///< ambient fraction in [0, 1]
  /// Light direction in view space (x right, y up, z towards the viewer);
  /// normalised internally. Default: from the upper left, behind the viewer.
  Vec3 light{-0.35, 0.5, 1.0};
  bool cull_back_faces = true;  ///< skip triangles whose projection is clockwise
  bool edges = false;           ///< draw edge lines (RenderMesh::lines, else triangle edges)
  RenderColour edge_colour{40, 40, 40};
};

/// Renders `meshes` as seen by `camera`. Triangles with a vertex behind the
/// perspective near plane are skipped. Without culling, back faces are lit
/// from their visible side.
/// \throw InvalidInput for an invalid camera, mesh (validate_render_mesh) or
///        option (size out of range, ambient outside [0, 1], zero light).
RgbImage rasterize(std::span<const RenderMesh> meshes, const Camera& camera,
                   const RasterOptions& options = {});

/// Colours of a stitch mesh picture.
struct StitchColourOptions {
  /// Knit stitches: course_colours[course % size] (course < 0 uses entry 0).
  std::vector<RenderColour> course_colours{{166, 206, 227}, {120, 170, 205}};
  /// Shaping stitches (non-Knit) by type, so they stand out from the courses
  /// (the Knit entry is unused). Defaults match io/colours.h.
  std::array<RenderColour, kNumStitchTypes> type_colours{
      {{166, 206, 227}, {255, 127, 0}, {227, 26, 28}, {51, 160, 44}, {106, 61, 154}}};
};

/// A stitch mesh as a RenderMesh: quads split along their shorter diagonal,
/// triangles as they are; face colours by course with shaping stitches
/// marked (StitchColourOptions); smooth vertex normals; lines = the stitch
/// outlines (each mesh edge once), for RasterOptions::edges.
/// \throw InvalidInput when a stitch has corner indices out of range or
///        course_colours is empty (naming the stitch).
RenderMesh stitch_mesh_render_mesh(const StitchMesh& mesh, const StitchColourOptions& options = {});

}  // namespace knitforge
