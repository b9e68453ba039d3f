#pragma once
/// \file vector_drawing.h
/// 3D meshes -> 2D vector drawing in the style of a technical drawing
/// (seed §1.A.2, Algorithm 1.2, Fig. 1.12).
///
/// 1. NDC transformation (camera.h): every vertex to normalised device
///    coordinates, where the projection is orthographic.
/// 2. Back-face removal: a triangle is kept (front-facing) when its
///    projection is counter-clockwise with non-zero area. Triangles with a
///    vertex behind the perspective near plane are dropped (counted in
///    VectorDrawing::clipped_faces).
/// 3. Contours: the boundary edges of the front-facing part M_f of each mesh
///    (edges with exactly one front-facing triangle): original mesh
///    boundaries and occluding contours (silhouettes).
/// 4. The 2D arrangement of the projected contour segments (CGAL
///    Arrangement_2, segment traits over the exact-constructions kernel), so
///    every arrangement edge is a piece of contour between two crossings.
/// 5. Visibility: an arrangement edge is visible when the ray through its
///    midpoint hits no front-facing triangle nearer than the contour point
///    itself (relative depth tolerance 1e-6 of the scene's depth range);
///    invisible edges are removed, which merges the faces on their sides.
/// 6. Colouring: each bounded face of the reduced arrangement gets the
///    colour of the triangle the ray through one of its interior points hits
///    first (face colour, else the mean of the vertex colours, else the mesh
///    colour); a face the ray misses (a hole in the scene) is left unfilled.
///
/// The meshes should be oriented, manifold and intersection-free after
/// back-face removal, as the seed requires; otherwise the drawing is still
/// produced but may show contours where surfaces cross.
/// Cost: O(F log F) for the triangles plus the arrangement,
/// O((S + I) log S) for S contour segments with I crossings (exact
/// arithmetic: meant for figures, not for 100k-stitch yarn models).

#include <span>
#include <string>
#include <vector>

#include "knitforge/render/camera.h"
#include "knitforge/render/render_mesh.h"

namespace knitforge {

/// A visible piece of contour, in NDC (x, y in [-1, 1] over the image).
struct DrawingEdge {
  Vec2 a = Vec2::Zero(), b = Vec2::Zero();
  int mesh = -1;          ///< index of the mesh whose contour it is
  bool boundary = false;  ///< true: a boundary edge of the mesh; false: an occluding contour
};

/// A filled region: the outer boundary then any holes, each a closed
/// polygon (counter-clockwise outer, clockwise holes), in NDC.
struct DrawingRegion {
  std::vector<std::vector<Vec2>> rings;
  RenderColour colour{0, 0, 0};
  int mesh = -1;  ///< mesh seen in this region
};

struct VectorDrawing {
  std::vector<DrawingRegion> regions;  ///< filled faces of the reduced arrangement
  std::vector<DrawingEdge> edges;      ///< visible contour pieces
  double aspect = 1.0;                 ///< image width / height (from the camera)
  int front_faces = 0;                 ///< front-facing triangles kept
  int clipped_faces = 0;               ///< triangles dropped at the near plane
  int contour_segments = 0;            ///< projected contour segments put in the arrangement
  int arrangement_edges = 0;           ///< edges of the full arrangement
  int hidden_edges = 0;                ///< arrangement edges removed as invisible
};

/// Algorithm 1.2 for `meshes` seen by `camera` (see the file comment).
/// \throw InvalidInput for an invalid camera (view_transform()) or mesh
///        (validate_render_mesh(), naming the mesh).
VectorDrawing vector_drawing(std::span<const RenderMesh> meshes, const Camera& camera);

struct SvgOptions {
  int width = 800;               ///< picture width (px); the height follows the aspect
  double stroke_width = 1.0;     ///< contour line width (px)
  RenderColour stroke{0, 0, 0};  ///< contour colour
  bool fill = true;              ///< draw the filled regions
  bool background = false;       ///< white background rectangle
};

/// The drawing as an SVG document: regions first (evenodd fill, no
/// stroke), then the visible edges as one stroked path per mesh.
/// Coordinates are written with 3 decimals.
/// \throw InvalidInput when width < 1 or the stroke width is negative.
std::string vector_drawing_svg(const VectorDrawing& drawing, const SvgOptions& options = {});

}  // namespace knitforge
