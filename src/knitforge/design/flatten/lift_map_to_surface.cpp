#include "knitforge/design/flatten/lift_map_to_surface.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "knitforge/convert/map_to_stitch_mesh.h"
#include "knitforge/geometry/mesh_measures.h"
#include "knitforge/util/errors.h"

namespace knitforge {

namespace {

// Barycentric coordinates of p in the 2D triangle abc (area2 = twice its signed area).
Vec3 barycentric(const Vec2& p, const Vec2& a, const Vec2& b, const Vec2& c, double area2) {
  auto cross = [](const Vec2& u, const Vec2& v) { return u.x() * v.y() - u.y() * v.x(); };
  const double w0 = cross(b - p, c - p) / area2;
  const double w1 = cross(c - p, a - p) / area2;
  return Vec3(w0, w1, 1.0 - w0 - w1);
}

}  // namespace

std::vector<Vec3> pattern_points_to_surface(const TriMesh& mesh, const std::vector<Vec2>& uv,
                                            const std::vector<Vec2>& points, OutsidePattern outside) {
  if (static_cast<int>(uv.size()) != mesh.num_vertices()) {
    throw InvalidInput("pattern_points_to_surface: one 2D position per vertex needed");
  }
  std::vector<int> faces;
  Vec2 lo(1e300, 1e300);
  Vec2 hi(-1e300, -1e300);
  double edge_sum = 0.0;
  for (int f = 0; f < mesh.num_faces(); ++f) {
    const auto& t = mesh.faces[f];
    const Vec2 e1 = uv[t[1]] - uv[t[0]];
    const Vec2 e2 = uv[t[2]] - uv[t[0]];
    if (!(std::abs(e1.x() * e2.y() - e1.y() * e2.x()) > 0.0)) continue;
    faces.push_back(f);
    for (int v : t) {
      lo = lo.cwiseMin(uv[v]);
      hi = hi.cwiseMax(uv[v]);
    }
    edge_sum += e1.norm();
  }
  if (faces.empty()) throw InvalidInput("pattern_points_to_surface: the pattern has no triangle");
  const double cell = std::max(edge_sum / faces.size(), 1e-9 * std::max(1.0, (hi - lo).norm()));
  const int nx = std::max(1, std::min(4096, static_cast<int>((hi.x() - lo.x()) / cell) + 1));
  const int ny = std::max(1, std::min(4096, static_cast<int>((hi.y() - lo.y()) / cell) + 1));
  const double cx = (hi.x() - lo.x()) / nx + 1e-300;
  const double cy = (hi.y() - lo.y()) / ny + 1e-300;
  std::vector<std::vector<int>> bucket(static_cast<size_t>(nx) * ny);
  auto ix = [&](double x) { return std::clamp(static_cast<int>(std::floor((x - lo.x()) / cx)), 0, nx - 1); };
  auto iy = [&](double y) { return std::clamp(static_cast<int>(std::floor((y - lo.y()) / cy)), 0, ny - 1); };
  for (int f : faces) {
    const auto& t = mesh.faces[f];
    const double x0 = std::min({uv[t[0]].x(), uv[t[1]].x(), uv[t[2]].x()});
    const double x1 = std::max({uv[t[0]].x(), uv[t[1]].x(), uv[t[2]].x()});
    const double y0 = std::min({uv[t[0]].y(), uv[t[1]].y(), uv[t[2]].y()});
    const double y1 = std::max({uv[t[0]].y(), uv[t[1]].y(), uv[t[2]].y()});
    for (int j = iy(y0); j <= iy(y1); ++j) {
      for (int i = ix(x0); i <= ix(x1); ++i) bucket[static_cast<size_t>(j) * nx + i].push_back(f);
    }
  }
  std::vector<Vec3> out(points.size());
  for (size_t k = 0; k < points.size(); ++k) {
    const Vec2& p = points[k];
    if (!p.allFinite())
      throw InvalidInput(fmt::format("pattern_points_to_surface: point {} is not finite", k));
    const int pi = ix(p.x());
    const int pj = iy(p.y());
    double best = std::numeric_limits<double>::infinity();
    int best_face = -1;
    Vec3 best_bary = Vec3::Zero();
    const int max_ring = std::max(nx, ny);
    for (int ring = 0; ring <= max_ring; ++ring) {
      // Every point of a cell at ring distance >= ring is at least (ring - 1) cells away.
      if (best_face >= 0 && (ring - 1) * std::min(cx, cy) > std::sqrt(best)) break;
      for (int j = pj - ring; j <= pj + ring; ++j) {
        if (j < 0 || j >= ny) continue;
        for (int i = pi - ring; i <= pi + ring; ++i) {
          if (i < 0 || i >= nx) continue;
          if (std::max(std::abs(i - pi), std::abs(j - pj)) != ring) continue;
          for (int f : bucket[static_cast<size_t>(j) * nx + i]) {
            const auto& t = mesh.faces[f];
            const Vec3 a(uv[t[0]].x(), uv[t[0]].y(), 0.0);
            const Vec3 b(uv[t[1]].x(), uv[t[1]].y(), 0.0);
            const Vec3 c(uv[t[2]].x(), uv[t[2]].y(), 0.0);
            const Vec3 q = closest_point_on_triangle(Vec3(p.x(), p.y(), 0.0), a, b, c);
            const double d = (q.head<2>() - p).squaredNorm();
            if (d < best) {
              best = d;
              best_face = f;
              const Vec2 e1 = uv[t[1]] - uv[t[0]];
              const Vec2 e2 = uv[t[2]] - uv[t[0]];
              const Vec2 at = outside == OutsidePattern::Closest ? Vec2(q.head<2>()) : p;
              best_bary = barycentric(at, uv[t[0]], uv[t[1]], uv[t[2]], e1.x() * e2.y() - e1.y() * e2.x());
            }
          }
        }
      }
    }
    const auto& t = mesh.faces[best_face];
    out[k] = best_bary.x() * mesh.vertices[t[0]] + best_bary.y() * mesh.vertices[t[1]] +
             best_bary.z() * mesh.vertices[t[2]];
  }
  return out;
}

std::vector<std::array<Vec2, 4>> stitch_corner_pattern_points(const RasterizedPattern& raster,
                                                               const StitchMesh& sm, const KnitParams& params) {
  const KnittingMap& map = raster.map;
  const bool banded = raster.cell_pattern_row.size() == map.cells.size();
  std::vector<std::array<Vec2, 4>> out(sm.stitches.size());
  for (size_t k = 0; k < sm.stitches.size(); ++k) {
    const Stitch& s = sm.stitches[k];
    const int r = s.course;
    const int c = s.wale;
    if (r < 0 || r >= map.rows || c < 0 || c >= map.cols)
      throw InvalidInput(fmt::format("stitch_corner_pattern_points: stitch {} lies outside the map", k));
    const int row = banded ? raster.cell_pattern_row[static_cast<size_t>(r) * map.cols + c] : r;
    auto corner = [&](int dx, int dy) -> Vec2 {
      return Vec2(raster.origin.x() + (c + dx) * params.stitch_width,
                  raster.origin.y() + (row + dy) * params.stitch_height);
    };
    const Vec2 bl = corner(0, 0);
    const Vec2 br = corner(1, 0);
    const Vec2 tr = corner(1, 1);
    const Vec2 tl = corner(0, 1);
    // Corners in the order of core/stitch.h; an apex stands for the two
    // grid corners it merges.
    std::array<Vec2, 4> p = {bl, br, tr, tl};
    switch (s.type) {
      case StitchType::Knit:
        break;
      case StitchType::ShortRowLeft:
        p = {0.5 * (bl + tl), br, tr, Vec2::Zero()};
        break;
      case StitchType::ShortRowRight:
        p = {bl, 0.5 * (br + tr), tl, Vec2::Zero()};
        break;
      case StitchType::Increase:
        p = {0.5 * (bl + br), tr, tl, Vec2::Zero()};
        break;
      case StitchType::Decrease:
        p = {bl, br, 0.5 * (tr + tl), Vec2::Zero()};
        break;
    }
    out[k] = p;
  }
  return out;
}

StitchMesh lift_map_to_surface(const RasterizedPattern& raster, const TriMesh& mesh,
                               const std::vector<Vec2>& uv, const KnitParams& params) {
  StitchMesh sm = map_to_stitch_mesh_topology(raster.map, params);
  const std::vector<std::array<Vec2, 4>> corners = stitch_corner_pattern_points(raster, sm, params);
  std::vector<Vec2> pts;
  pts.reserve(4 * corners.size());
  for (size_t k = 0; k < corners.size(); ++k) {
    for (int q = 0; q < sm.stitches[k].corners(); ++q) pts.push_back(corners[k][q]);
  }
  const std::vector<Vec3> lifted = pattern_points_to_surface(mesh, uv, pts, OutsidePattern::Extend);
  // Each vertex at the mean of its stitch corners' 3D points: a vertex that
  // closes a dart (its corners on the dart's two legs, the wedge between them
  // Collapsed) lands on the dart's seam, where both legs meet on the
  // surface, not at the lifted middle of the wedge.
  std::vector<Vec3> sum(sm.vertices.size(), Vec3::Zero());
  std::vector<int> count(sm.vertices.size(), 0);
  size_t next = 0;
  for (const Stitch& s : sm.stitches) {
    for (int q = 0; q < s.corners(); ++q) {
      sum[s.v[q]] += lifted[next++];
      ++count[s.v[q]];
    }
  }
  // Every vertex is a corner of some stitch (map_to_stitch_mesh_topology()
  // numbers them by first use).
  for (size_t v = 0; v < sm.vertices.size(); ++v) sm.vertices[v] = sum[v] / static_cast<double>(count[v]);
  return sm;
}

}  // namespace knitforge
