#include "knitforge/design/tube/tube_crown.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include <fmt/format.h>
#include <Eigen/Eigenvalues>

#include "knitforge/design/shortcolumn/divergence_metric.h"
#include "knitforge/design/tube/tube_field.h"
#include "knitforge/geometry/clip_mesh_by_field.h"
#include "knitforge/geometry/geodesic_distance.h"
#include "knitforge/geometry/geodesic_source.h"
#include "knitforge/geometry/halfedges.h"
#include "knitforge/geometry/mesh_measures.h"
#include "knitforge/geometry/surface_checks.h"
#include "knitforge/util/errors.h"

namespace knitforge {

namespace {

// Pieces of {v : d[v] >= t}, vertices joined by mesh edges, that rise to
// at least t + prominence.
int superlevel_pieces(const Halfedges& he, const std::vector<double>& d, double t, double prominence) {
  const int n = static_cast<int>(d.size());
  std::vector<char> seen(static_cast<size_t>(n), 0);
  int pieces = 0;
  std::vector<int> stack;
  for (int v = 0; v < n; ++v) {
    if (seen[static_cast<size_t>(v)] || !(d[static_cast<size_t>(v)] >= t)) continue;
    double top = d[static_cast<size_t>(v)];
    seen[static_cast<size_t>(v)] = 1;
    stack.assign(1, v);
    while (!stack.empty()) {
      const int u = stack.back();
      stack.pop_back();
      top = std::max(top, d[static_cast<size_t>(u)]);
      for (int w : he.vertex_neighbors(u))
        if (!seen[static_cast<size_t>(w)] && d[static_cast<size_t>(w)] >= t) {
          seen[static_cast<size_t>(w)] = 1;
          stack.push_back(w);
        }
    }
    if (top >= t + prominence) ++pieces;
  }
  return pieces;
}

double mean_edge_length(const TriMesh& m) {
  double sum = 0.0;
  for (const auto& f : m.faces)
    for (int k = 0; k < 3; ++k)
      sum += (m.vertices[static_cast<size_t>(f[k])] - m.vertices[static_cast<size_t>(f[(k + 1) % 3])]).norm();
  return m.faces.empty() ? 0.0 : sum / (3.0 * static_cast<double>(m.faces.size()));
}

// Length of the shortest boundary loop (the crown ring of the annulus).
double shortest_loop_length(const TriMesh& m) {
  const Halfedges he = build_halfedges(m.num_vertices(), m.faces);
  double best = 1e300;
  for (const auto& loop : he.boundary_loops()) {
    double len = 0.0;
    for (size_t i = 0; i < loop.size(); ++i)
      len += (m.vertices[static_cast<size_t>(loop[(i + 1) % loop.size()])] -
              m.vertices[static_cast<size_t>(loop[i])])
                 .norm();
    best = std::min(best, len);
  }
  return best;
}

// Euclidean distance from p to the polyline (a single point: to it).
double distance_to_polyline(const Vec3& p, const std::vector<Vec3>& line) {
  double best = (p - line.front()).norm();
  for (size_t i = 0; i + 1 < line.size(); ++i) {
    const Vec3 e = line[i + 1] - line[i];
    const double len2 = e.squaredNorm();
    const double t = len2 > 0.0 ? std::clamp((p - line[i]).dot(e) / len2, 0.0, 1.0) : 0.0;
    best = std::min(best, (p - line[i] - t * e).norm());
  }
  return best;
}

// The axis along which the surface is thinnest: the eigenvector of the
// smallest eigenvalue of the area-weighted covariance of its face centroids.
Vec3 thinnest_axis(const TriMesh& m) {
  const std::vector<double> area = face_areas(m);
  double total = 0.0;
  Vec3 mean = Vec3::Zero();
  std::vector<Vec3> c(m.faces.size());
  for (size_t f = 0; f < m.faces.size(); ++f) {
    c[f] = (m.vertices[static_cast<size_t>(m.faces[f][0])] + m.vertices[static_cast<size_t>(m.faces[f][1])] +
            m.vertices[static_cast<size_t>(m.faces[f][2])]) /
           3.0;
    mean += area[f] * c[f];
    total += area[f];
  }
  mean /= total;
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for (size_t f = 0; f < c.size(); ++f) cov += area[f] * (c[f] - mean) * (c[f] - mean).transpose();
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(cov);
  return es.eigenvectors().col(0);
}

}  // namespace

std::vector<double> rim_distance(const TriMesh& disk, double stitch_width) {
  const Halfedges he = build_halfedges(disk.num_vertices(), disk.faces);
  const auto loops = he.boundary_loops();
  if (loops.empty()) throw InvalidInput("rim distance: the surface has no boundary");
  GeodesicOptions go;
  go.signed_field = false;
  (void)stitch_width;
  return geodesic_distance(disk, source_from_boundary_vertices(disk, loops.front()), go).distance;
}

TubeCrown cut_crown(const TriMesh& disk, const CrownOptions& o, const std::string& what) {
  if (!(o.crown_length > 0.0) || !std::isfinite(o.crown_length))
    throw InvalidInput(
        fmt::format("{}: the crown round's length must be positive, got {} mm", what, o.crown_length));
  if (o.directions < 1 || o.directions > 36)
    throw InvalidInput(
        fmt::format("{}: the crown segment's directions tried must be 1..36, got {}", what, o.directions));
  if (!(o.stitch_width > 0.0))
    throw InvalidInput(fmt::format("{}: the stitch width must be positive, got {} mm", what, o.stitch_width));
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
  if (!o.rim_distance.empty() && o.rim_distance.size() != static_cast<size_t>(disk.num_vertices()))
    throw InvalidInput(fmt::format("{}: {} rim distances for {} vertices", what, o.rim_distance.size(),
                                   disk.num_vertices()));
  const std::vector<double> d = o.rim_distance.empty() ? rim_distance(disk, o.stitch_width) : o.rim_distance;
  int top = 0;
  if (o.crown_vertex) {
    top = *o.crown_vertex;
    if (top < 0 || top >= disk.num_vertices() || !std::isfinite(d[static_cast<size_t>(top)]))
      throw InvalidInput(fmt::format("{}: crown vertex {} is not a vertex of the surface", what, top));
  } else {
    for (int v = 0; v < disk.num_vertices(); ++v)
      if (std::isfinite(d[static_cast<size_t>(v)]) && d[static_cast<size_t>(v)] > d[static_cast<size_t>(top)])
        top = v;
  }
  TubeCrown c;
  c.crown_vertex = top;
  c.crown = disk.vertices[static_cast<size_t>(top)];
  c.rim_to_crown = d[static_cast<size_t>(top)];
  c.cap_radius = std::max(o.min_slit_half_width, mean_edge_length(disk));
  // 2 s + 2 pi w = crown_length; a ring too short for a segment is a circle round the point.
  const double s = std::max(0.0, (o.crown_length - 2.0 * std::numbers::pi * c.cap_radius) / 2.0);
  if (s <= 0.0) c.cap_radius = o.crown_length / (2.0 * std::numbers::pi);
  const double reach = s / 2.0 + c.cap_radius;
  if (!(c.rim_to_crown > 2.0 * reach)) {
    throw InvalidInput(fmt::format(
        "{}: the crown lies {:.1f} mm from the rim, too close for a closed tube whose last round is {:.1f} "
        "mm "
        "round (the rounds need at least {:.1f} mm); fewer crown stitches or a smaller stitch, or design it "
        "without --tube",
        what, c.rim_to_crown, o.crown_length, 2.0 * reach));
  }
  int crowns = 1;
  constexpr int kLevels = 16;
  double dmax = 0.0;
  for (double x : d)
    if (std::isfinite(x)) dmax = std::max(dmax, x);
  const double cut = dmax - reach;
  for (int k = 0; k <= kLevels; ++k) {
    const double t = 0.5 * dmax + (cut - 0.5 * dmax) * k / kLevels;
    crowns = std::max(crowns, superlevel_pieces(he, d, t, 2.0 * reach));
  }
  if (crowns > 1) {
    throw InvalidInput(fmt::format(
        "{}: the distance from the rim has {} separate maxima (crowns) above half its largest value; a closed "
        "tube is knitted from its rim to ONE crown, so cut the surface into pieces with one crown each (e.g. a "
        "thumb off a mitten) or design it without --tube",
        what, crowns));
  }

  // Tangent basis at the crown point.
  const Vec3 n = vertex_normals(disk)[static_cast<size_t>(top)];
  Vec3 axis = Vec3::UnitX();
  if (std::abs(n.y()) < std::abs(axis.dot(n))) axis = Vec3::UnitY();
  if (std::abs(n.z()) < std::abs(axis.dot(n))) axis = Vec3::UnitZ();
  const Vec3 t0 = (axis - axis.dot(n) * n).normalized(), t1 = n.cross(t0);

  DivergenceOptions dv;
  dv.along_gradient = true;
  std::string why;
  struct Tried {
    TriMesh annulus;
    Vec3 a, b, t;
    double score, length;
    int j;
  };
  std::vector<Tried> tried;
  for (int j = 0; j < (s > 0.0 ? o.directions : 1); ++j) {
    const double phi = std::numbers::pi * j / o.directions;
    const Vec3 t = std::cos(phi) * t0 + std::sin(phi) * t1;
    // The tangent segment's ends are pulled in by the projection onto a
    // curved surface: stretch them until the section is s long (1 %).
    std::vector<Vec3> line{c.crown};
    double reach_out = s;
    for (int it = 0; s > 0.0 && it < 6; ++it) {
      line.clear();
      const Vec3 half = 0.5 * reach_out * t;
      for (const auto& pl : source_from_polyline(disk, {c.crown - half, c.crown, c.crown + half}).polylines)
        for (const SurfacePoint& p : pl) line.push_back(surface_point_position(disk, p));
      double along = 0.0;
      for (size_t i = 0; i + 1 < line.size(); ++i) along += (line[i + 1] - line[i]).norm();
      if (!(along > 0.0) || std::abs(along - s) <= 0.01 * s) break;
      reach_out = std::min(4.0 * s, reach_out * s / along);
    }
    std::vector<double> keep(static_cast<size_t>(disk.num_vertices()));
    for (size_t v = 0; v < keep.size(); ++v)
      keep[v] = distance_to_polyline(disk.vertices[v], line) - c.cap_radius;
    TriMesh annulus = clip_mesh_by_field(disk, keep).mesh;
    double score = 0.0;
    try {
      const TubeField f = tube_field(annulus, what);
      score = divergence_metric(annulus, f.value, dv).transfer_estimate(o.stitch_width);
    } catch (const InvalidInput& e) {
      why = e.what();
      c.direction_scores.push_back(std::numeric_limits<double>::quiet_NaN());
      continue;
    }
    c.direction_scores.push_back(score);
    double along = 0.0;
    for (size_t i = 0; i + 1 < line.size(); ++i) along += (line[i + 1] - line[i]).norm();
    tried.push_back({std::move(annulus), line.front(), line.back(), t, score, along, j});
  }
  if (tried.empty())
    throw InvalidInput(fmt::format("{}: cutting the crown segment open leaves no tube ({})", what, why));
  double best = tried.front().score;
  for (const Tried& x : tried) best = std::min(best, x.score);
  // Ties (within kDirectionTie): across the surface's thinnest axis.
  Vec3 thin = thinnest_axis(disk);
  thin -= thin.dot(n) * n;
  const auto key = [&](const Tried& y) { return thin.norm() > 0.3 ? std::abs(y.t.dot(thin)) : -y.score; };
  Tried* win = nullptr;
  for (Tried& x : tried) {
    if (x.score > best + kDirectionTie) continue;
    if (!win || key(x) > key(*win) + 1e-12) win = &x;
  }
  c.annulus = std::move(win->annulus);
  c.direction_degrees = 180.0 * win->j / o.directions;
  c.segment_start = win->a;
  c.segment_end = win->b;
  c.segment_length = win->length;
  c.ring_length = shortest_loop_length(c.annulus);
  c.cap_area = total_area(disk) - total_area(c.annulus);
  return c;
}

}  // namespace knitforge
