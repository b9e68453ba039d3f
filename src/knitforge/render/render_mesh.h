#pragma once
/// \file render_mesh.h
/// The plain data the render module works on: a coloured triangle mesh
/// (RenderMesh), an 8-bit colour and an RGB image. The render module sits
/// below io, so it has its own colour type; io/colours.h's palette is mapped
/// to it by the caller (the CLI).

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "knitforge/geometry/tri_mesh.h"

namespace knitforge {

/// An 8-bit sRGB colour {r, g, b}.
using RenderColour = std::array<uint8_t, 3>;

/// A triangle mesh with optional shading normals, colours and feature lines.
/// Colour precedence: face_colours, else vertex_colours, else `colour`.
struct RenderMesh {
  std::string name;                          ///< shown in glTF / SVG ids ("yarn 0")
  TriMesh mesh;                              ///< positions (mm), CCW triangles
  std::vector<Vec3> normals;                 ///< empty, or one unit normal per vertex
  std::vector<RenderColour> vertex_colours;  ///< empty, or one colour per vertex
  std::vector<RenderColour> face_colours;    ///< empty, or one colour per face
  RenderColour colour{200, 200, 200};        ///< colour when neither array is given
  /// Feature lines (vertex index pairs) drawn by the raster preview when edge
  /// lines are requested, e.g. the stitch outlines of a triangulated stitch
  /// mesh. Empty = every triangle edge.
  std::vector<std::array<int, 2>> lines;
};

/// An 8-bit RGB image, rows from top to bottom, 3 bytes per pixel:
/// pixel (x, y) is at pixels[3 * (y * width + x)].
struct RgbImage {
  int width = 0;
  int height = 0;
  std::vector<uint8_t> pixels;

  RenderColour at(int x, int y) const {
    const size_t i = 3 * (static_cast<size_t>(y) * static_cast<size_t>(width) + static_cast<size_t>(x));
    return {pixels[i], pixels[i + 1], pixels[i + 2]};
  }
};

/// Checks a RenderMesh's array sizes and indices.
/// \throw InvalidInput naming the mesh and the offending face, vertex or
///        array (face index out of range, non-finite coordinate, normals /
///        vertex_colours / face_colours of the wrong size, bad line index).
void validate_render_mesh(const RenderMesh& mesh);

}  // namespace knitforge
