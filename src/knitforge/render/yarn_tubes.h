#pragma once
/// \file yarn_tubes.h
/// Yarn model -> tube meshes with ply detail (seed §1.A.1, Fig. 1.11).
///
/// Each yarn polyline is turned into a smooth curve (centripetal Catmull-Rom
/// through every polyline vertex, sampled about every `ring_spacing` mm),
/// rotation-minimising frames are carried along it by parallel transport
/// (the double-reflection method of Wang et al. 2008), and a twisted
/// n-gonal prism (n = plies, seed: 6) is swept along the frames. Where the
/// seed uses a displacement texture for the plies, the ply detail here is
/// real geometry: the cross-section has `vertices_per_ply` vertices per ply
/// and their radius follows the outer envelope of n touching ply circles
/// (crest on a ply's centre line, valley where two plies touch), blended with
/// a plain circle by `ply_depth`. The cross-section rotates by
/// `twist_per_mm` turns per millimetre of yarn, so the plies spiral; each
/// cross-section vertex is joined to the vertex of the next ring that lies
/// on the same ply nearest in angle, so the side triangles follow the plies.
///
/// Output: one RenderMesh per yarn (triangles CCW seen from outside, unit
/// vertex normals, RenderMesh::colour = the yarn's colour; no per-vertex
/// colours). tube_rings(), tube_section() and tube_ring_vertices() give the
/// same geometry ring by ring in float32 for writers that stream it
/// (write_yarn_glb()) without building the double-precision mesh. A side vertex's
/// normal is the outward perpendicular, in its cross-section's plane, of the
/// chord between its two cross-section neighbours (radial for a round
/// section); cap vertices have the axial normal. Vertices are
/// stored ring by ring along the yarn (ring i, vertex k at index i*K + k,
/// K = plies * vertices_per_ply), then the cap vertices (K ring copies and a
/// centre per end, with the end's axial normal). Cost is linear in the number
/// of rings times K.

#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include "knitforge/core/knit_params.h"
#include "knitforge/core/yarn_model.h"
#include "knitforge/render/render_mesh.h"

namespace knitforge {

struct TubeOptions {
  /// Tube radius (mm); 0 = 0.12 * KnitParams::stitch_width, the yarn radius
  /// stitch_mesh_to_yarn() assumes by default (0.42 mm for 3.5 mm stitches).
  double radius = 0.0;
  int plies = 6;             ///< plies (sides of the twisted prism), >= 1 (1 = round yarn)
  int vertices_per_ply = 2;  ///< cross-section vertices per ply, >= 1 (1 = plain prism)
  /// How much of the ply envelope's relief is applied, in [0, 1]: 0 = round
  /// cross-section, 1 = the full scalloped outline of touching ply circles.
  double ply_depth = 0.3;
  /// Turns of the ply pattern per mm of yarn (sign = twist direction). The
  /// default gives the plies a helix angle of about 22 degrees at the default
  /// radius (tan = 2 pi r twist).
  double twist_per_mm = 0.15;
  /// Distance between consecutive cross-sections along the yarn (mm);
  /// 0 = the radius. Every polyline vertex is on the curve whatever the
  /// spacing; each polyline segment gets at least one ring.
  double ring_spacing = 0.0;
  bool capped = true;  ///< close both ends with a flat cap
};

/// The centripetal Catmull-Rom curve through `points`, sampled so that
/// consecutive samples along each polyline segment are at most about
/// `spacing` apart (each segment of length L gets ceil(L / spacing)
/// intervals). Every input point is a sample; consecutive duplicate points
/// (closer than 1e-9 mm) are dropped first.
/// \throw InvalidInput when a point is not finite or spacing <= 0.
std::vector<Vec3> smooth_polyline(std::span<const Vec3> points, double spacing);

/// Rotation-minimising frames along a sampled curve.
struct CurveFrames {
  std::vector<Vec3> tangents;      ///< unit tangent per sample
  std::vector<Vec3> normals;       ///< unit normal per sample, orthogonal to the tangent
  std::vector<double> arc_length;  ///< polyline arc length from the first sample (mm)
};

/// Parallel-transport frames of a curve (double reflection): the normal
/// turns only as much as the tangent forces it to (no twist about the
/// tangent). The first normal is the unit vector orthogonal to the first
/// tangent nearest to the axis the tangent is least aligned with.
/// \pre at least 2 samples, consecutive samples distinct.
/// \throw InvalidInput when fewer than 2 samples or two consecutive samples coincide.
CurveFrames parallel_transport_frames(std::span<const Vec3> curve);

/// The cross-section of a tube: K = plies * vertices_per_ply vertices at
/// offsets (x[k], y[k]) mm in a ring's (u, w) axes, with shading normal
/// directions (nx[k], ny[k]) (unit) in the same axes.
struct TubeSection {
  int plies = 0;
  int vertices_per_ply = 0;
  std::vector<double> x, y, nx, ny;
  int size() const { return plies * vertices_per_ply; }
};

/// The cross-section of `options` at `radius` (see the file comment).
/// \throw InvalidInput for options out of range (as yarn_tube()).
TubeSection tube_section(const TubeOptions& options, double radius);

/// One cross-section ring of a tube: its centre on the smoothed curve and
/// its axes u, w (the parallel-transport normal and binormal rotated by the
/// twist phase; unit, orthogonal, u x w = the curve tangent). Vertex k of
/// the ring is centre + x[k] u + y[k] w. `shift` joins ring i to ring i+1:
/// vertex k of ring i is connected to vertex (k + shift) mod K of ring i+1.
struct TubeRing {
  Vec3 centre;
  Vec3 u, w;
  int shift = 0;
};

/// The distance between a tube's rings: options.ring_spacing, or `radius`
/// when it is 0.
double tube_ring_spacing(const TubeOptions& options, double radius);

/// Calls ring(i, r) for ring i = 0, 1, ... of the tube along `curve` (a
/// smooth_polyline() output, one ring per sample) in order, without storing
/// the rings: the streaming form of tube_rings().
/// \throw InvalidInput when the curve has fewer than 2 samples or two
///        consecutive samples coincide; whatever `ring` throws.
void for_each_tube_ring(std::span<const Vec3> curve, const TubeOptions& options,
                        const std::function<void(size_t, const TubeRing&)>& ring);

/// The rings of the tube of `polyline` (smooth_polyline() at the ring
/// spacing, parallel-transport frames, twist): everything yarn_tube() needs
/// except the cross-section. Empty when the polyline has fewer than 2
/// distinct points. Linear in the number of rings.
/// \throw InvalidInput for a non-finite point or options out of range.
std::vector<TubeRing> tube_rings(std::span<const Vec3> polyline, const TubeOptions& options, double radius);

/// Float32 vertices of consecutive rings: ring j, vertex k goes to
/// positions[3 (j K + k) + 0..2] and its unit normal to normals[...] (the
/// same values as yarn_tube()'s, rounded to float).
/// \throw InvalidInput unless positions.size() == normals.size() == 3 K rings.size().
void tube_ring_vertices(const TubeSection& section, std::span<const TubeRing> rings,
                        std::span<float> positions, std::span<float> normals);

/// The 2 K (rings.size() - 1) side triangles between consecutive `rings`
/// (CCW seen from outside, yarn_tube()'s order), vertex j K + k = ring j,
/// vertex k, written as 3 indices each to `indices`, plus `base` added.
/// \throw InvalidInput unless indices.size() == 6 K (rings.size() - 1) and
///        the largest index fits the index type.
void tube_side_indices(std::span<const TubeRing> rings, int k_ring, uint32_t base,
                       std::span<uint32_t> indices);
void tube_side_indices(std::span<const TubeRing> rings, int k_ring, uint32_t base,
                       std::span<uint16_t> indices);

/// The tube mesh of one polyline (see the file comment), in one colour.
/// A polyline with fewer than 2 distinct points gives an empty mesh.
/// \throw InvalidInput for a non-finite point or options out of range
///        (radius <= 0 after the default, plies < 1, vertices_per_ply < 1,
///        more than 2^20 vertices per ring,
///        ply_depth outside [0, 1], non-finite twist, ring_spacing < 0, or
///        more than 2^31 vertices).
RenderMesh yarn_tube(std::span<const Vec3> polyline, const TubeOptions& options, double radius,
                     const RenderColour& colour);

/// The tube radius yarn_tubes() uses: options.radius, or 0.12 *
/// params.stitch_width when it is 0.
/// \throw InvalidInput for a non-positive stitch width when the radius is defaulted.
double tube_radius(const TubeOptions& options, const KnitParams& params);

/// Tubes of every yarn of `yarn`, named "yarn <id>". Yarn i (position in
/// yarn.yarns) gets colours[i % colours.size()] (grey when colours is empty).
/// \throw InvalidInput as yarn_tube(), naming the yarn; also for
///        non-positive stitch sizes when the radius is defaulted.
std::vector<RenderMesh> yarn_tubes(const YarnModel& yarn, const KnitParams& params,
                                   const TubeOptions& options = {},
                                   std::span<const RenderColour> colours = {});

}  // namespace knitforge
