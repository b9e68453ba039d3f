#include "knitforge/design/tube/tube_crown.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <fmt/format.h>

#include "knitforge/geometry/clip_mesh_by_field.h"
#include "knitforge/geometry/geodesic_distance.h"
#include "knitforge/geometry/geodesic_source.h"
#include "knitforge/geometry/halfedges.h"
#include "knitforge/geometry/mesh_measures.h"
#include "knitforge/geometry/surface_checks.h"
#include "knitforge/util/errors.h"

namespace knitforge {

namespace {

// Pieces of {v : d[v] >= t}, vertices joined by mesh edges.
int superlevel_pieces(const Halfedges& he, const std::vector<double>& d, double t) {
  const int n = static_cast<int>(d.size());
  std::vector<char> seen(static_cast<size_t>(n), 0);
  int pieces = 0;
  std::vector<int> stack;
  for (int v = 0; v < n; ++v) {
    if (seen[static_cast<size_t>(v)] || !(d[static_cast<size_t>(v)] >= t)) continue;
    ++pieces;
    seen[static_cast<size_t>(v)] = 1;
    stack.assign(1, v);
    while (!stack.empty()) {
      const int u = stack.back();
      stack.pop_back();
      for (int w : he.vertex_neighbors(u))
        if (!seen[static_cast<size_t>(w)] && d[static_cast<size_t>(w)] >= t) {
          seen[static_cast<size_t>(w)] = 1;
          stack.push_back(w);
        }
    }
  }
  return pieces;
}

}  // namespace

TubeCrown cut_crown(const TriMesh& disk, double crown_length, const std::string& what) {
  if (!(crown_length > 0.0) || !std::isfinite(crown_length))
    throw InvalidInput(fmt::format("{}: the crown round's length must be positive, got {} mm", what, crown_length));
  const SurfaceReport rep = validate_surface(disk);
  if (!rep.manifold || rep.num_components != 1 || rep.num_boundary_loops != 1 || rep.genus != 0) {
    throw InvalidInput(fmt::format(
        "{}: a closed tube (--tube on a surface with one boundary loop) needs one piece of manifold surface "
        "with one rim and no handle; this one has {} piece(s), {} boundary loop(s), genus {}{}; repair it or "
        "design it without --tube",
        what, rep.num_components, rep.num_boundary_loops, rep.genus, rep.manifold ? "" : ", not manifold"));
  }
  const Halfedges he = build_halfedges(disk.num_vertices(), disk.faces);
  const std::vector<int> rim = he.boundary_loops().front();
  const std::vector<double> d = geodesic_distance(disk, source_from_boundary_vertices(disk, rim)).distance;
  int top = 0;
  for (int v = 0; v < disk.num_vertices(); ++v)
    if (std::isfinite(d[static_cast<size_t>(v)]) && d[static_cast<size_t>(v)] > d[static_cast<size_t>(top)]) top = v;
  TubeCrown c;
  c.crown = disk.vertices[static_cast<size_t>(top)];
  c.rim_to_crown = d[static_cast<size_t>(top)];
  c.cap_radius = crown_length / (2.0 * std::numbers::pi);
  const double cut = c.rim_to_crown - c.cap_radius;
  if (!(cut > c.cap_radius)) {
    throw InvalidInput(fmt::format(
        "{}: the crown lies {:.1f} mm from the rim, too close for a closed tube whose last round is {:.1f} mm "
        "round (the rounds need at least twice its radius, {:.1f} mm); fewer crown stitches or a smaller "
        "stitch, or design it without --tube",
        what, c.rim_to_crown, crown_length, 2.0 * c.cap_radius));
  }
  int crowns = 1;
  constexpr int kLevels = 16;
  for (int k = 0; k <= kLevels; ++k) {
    const double t = 0.5 * c.rim_to_crown + (cut - 0.5 * c.rim_to_crown) * k / kLevels;
    crowns = std::max(crowns, superlevel_pieces(he, d, t));
  }
  if (crowns > 1) {
    throw InvalidInput(fmt::format(
        "{}: the distance from the rim has {} separate maxima (crowns) above half its largest value; a closed "
        "tube is knitted from its rim to ONE crown, so cut the surface into pieces with one crown each (e.g. a "
        "thumb off a mitten) or design it without --tube",
        what, crowns));
  }
  std::vector<double> keep(d.size());
  for (size_t v = 0; v < d.size(); ++v) keep[v] = cut - d[v];
  c.annulus = clip_mesh_by_field(disk, keep).mesh;
  c.cap_area = total_area(disk) - total_area(c.annulus);
  return c;
}

}  // namespace knitforge
