#pragma once
/// \file marching_tetrahedra.h
/// Polygonisation of an implicit surface {f = 0} (f < 0 inside) on a regular
/// grid by marching tetrahedra: every grid cube is split into the six
/// tetrahedra around its main diagonal (Kuhn's subdivision, consistent
/// across neighbouring cubes), and in each tetrahedron the zero set of the
/// linear interpolant of f is one triangle or one quad (two triangles,
/// split along the shorter diagonal). Crossing points are shared through
/// their grid edge, so the result is the piecewise-linear isosurface of the
/// interpolant: closed, 2-manifold and consistently oriented (normals
/// towards increasing f), possibly several components. Grid values exactly
/// 0 count as outside, so no vertex sits on a grid node.
///
/// Used to mesh the generated body (body/generated_body.h) before isotropic
/// remeshing. Cost: one f evaluation per grid node (nx ny nz) plus
/// O(crossing cells).

#include <functional>

#include "knitforge/geometry/mesh_measures.h"
#include "knitforge/geometry/tri_mesh.h"

namespace knitforge {

/// A scalar field on R^3 (mm -> field units; negative inside).
using ImplicitFunction = std::function<double(const Vec3&)>;

/// Polygonises {f = 0} inside `box` with cubes of edge `cell` (mm). The
/// caller makes f positive on the box boundary if the surface is to be
/// closed there.
/// \throw InvalidInput when cell is not positive and finite, the box is
///        empty, the grid would have more than 50 million nodes, or f
///        returns a non-finite value (naming the point).
TriMesh marching_tetrahedra(const ImplicitFunction& f, const BoundingBox& box, double cell);

/// The faces of the largest connected component (by face count; faces
/// joined through shared vertices) with its vertices renumbered in order of
/// first use.
TriMesh largest_component(const TriMesh& mesh);

}  // namespace knitforge
