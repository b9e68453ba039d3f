#include "knitforge/geometry/support_object.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include <fmt/core.h>

#include "knitforge/geometry/halfedges.h"
#include "knitforge/geometry/thicken_surface.h"
#include "knitforge/util/errors.h"
#include "knitforge/util/work_limit.h"

namespace knitforge {

namespace {

double cross2(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }

double signed_area(const std::vector<Vec2>& poly) {
  double s = 0.0;
  for (std::size_t i = 0; i < poly.size(); ++i) s += cross2(poly[i], poly[(i + 1) % poly.size()]);
  return 0.5 * s;
}

bool segments_cross(const Vec2& p1, const Vec2& p2, const Vec2& q1, const Vec2& q2) {
  const double d1 = cross2(p2 - p1, q1 - p1), d2 = cross2(p2 - p1, q2 - p1);
  const double d3 = cross2(q2 - q1, p1 - q1), d4 = cross2(q2 - q1, p2 - q1);
  return ((d1 > 0.0 && d2 < 0.0) || (d1 < 0.0 && d2 > 0.0)) &&
         ((d3 > 0.0 && d4 < 0.0) || (d3 < 0.0 && d4 > 0.0));
}

/// Index of the first pair of non-adjacent polygon edges that cross, or -1.
int first_self_intersection(const std::vector<Vec2>& poly) {
  const int n = static_cast<int>(poly.size());
  for (int i = 0; i < n; ++i) {
    for (int j = i + 2; j < n; ++j) {
      if (i == 0 && j == n - 1) continue;
      if (segments_cross(poly[i], poly[(i + 1) % n], poly[j], poly[(j + 1) % n])) return i;
    }
  }
  return -1;
}

/// Triangulates a simple polygon keeping its winding: triangles of polygon
/// indices. Centre fan when the polygon is star-shaped about its vertex
/// centroid (returns centre = true; index n is the centre), else ear clipping.
std::vector<std::array<int, 3>> cap_polygon(const std::vector<Vec2>& poly, bool& centre) {
  const int n = static_cast<int>(poly.size());
  const double sign = signed_area(poly) >= 0.0 ? 1.0 : -1.0;
  double scale = 0.0;
  Vec2 c = Vec2::Zero();
  for (const Vec2& p : poly) c += p;
  c /= n;
  for (const Vec2& p : poly) scale = std::max(scale, (p - c).squaredNorm());
  const double eps = 1e-10 * scale;
  std::vector<std::array<int, 3>> out;
  bool star = true;
  for (int i = 0; i < n && star; ++i) star = sign * cross2(poly[i] - c, poly[(i + 1) % n] - c) > eps;
  if (star) {
    centre = true;
    for (int i = 0; i < n; ++i) out.push_back({n, i, (i + 1) % n});
    return out;
  }
  centre = false;
  std::vector<int> ring(n);
  for (int i = 0; i < n; ++i) ring[i] = i;
  while (ring.size() > 3) {
    const int r = static_cast<int>(ring.size());
    int ear = -1;
    for (int k = 0; k < r && ear < 0; ++k) {
      const Vec2& a = poly[ring[(k + r - 1) % r]];
      const Vec2& b = poly[ring[k]];
      const Vec2& d = poly[ring[(k + 1) % r]];
      if (sign * cross2(b - a, d - b) <= eps) continue;  // reflex or collinear
      bool empty = true;
      for (int q = 0; q < r && empty; ++q) {
        if (q == k || q == (k + r - 1) % r || q == (k + 1) % r) continue;
        const Vec2& p = poly[ring[q]];
        const double s1 = sign * cross2(b - a, p - a), s2 = sign * cross2(d - b, p - b),
                     s3 = sign * cross2(a - d, p - d);
        if (s1 >= -eps && s2 >= -eps && s3 >= -eps) empty = false;
      }
      if (empty) ear = k;
    }
    if (ear < 0) {
      throw TopologyError(
          "support_object: cannot triangulate the base polygon (it is degenerate); use the rectangle base");
    }
    out.push_back({ring[(ear + r - 1) % r], ring[ear], ring[(ear + 1) % r]});
    ring.erase(ring.begin() + ear);
  }
  out.push_back({ring[0], ring[1], ring[2]});
  return out;
}

}  // namespace

SupportObject support_object(const TriMesh& surface, const SupportOptions& options) {
  auto bad = [](double v) { return !std::isfinite(v); };
  if (bad(options.offset) || options.offset < 0.0) {
    throw InvalidInput(fmt::format("support_object: the offset must be >= 0 mm (got {})", options.offset));
  }
  if (bad(options.base_height) || options.base_height <= 0.0) {
    throw InvalidInput(
        fmt::format("support_object: the base height must be > 0 mm (got {})", options.base_height));
  }
  if (bad(options.base_margin) || options.base_margin < 0.0) {
    throw InvalidInput(
        fmt::format("support_object: the base margin must be >= 0 mm (got {})", options.base_margin));
  }
  if (bad(options.shell_thickness) || options.shell_thickness < 0.0) {
    throw InvalidInput(
        fmt::format("support_object: the shell thickness must be >= 0 mm (got {})", options.shell_thickness));
  }
  if (!options.up.allFinite() || options.up.norm() == 0.0) {
    throw InvalidInput("support_object: the up direction must be a finite non-zero vector");
  }
  if (surface.faces.empty()) throw InvalidInput("support_object: the surface has no faces");
  const Vec3 up = options.up.normalized();

  // Compact to the used vertices; offset_normals() checks finiteness.
  std::vector<int> index(surface.num_vertices(), -1);
  TriMesh top;
  for (const auto& t : surface.faces) {
    for (int v : t) {
      if (v < 0 || v >= surface.num_vertices()) {
        throw InvalidInput(
            fmt::format("support_object: a face uses vertex {}, outside [0, {})", v, surface.num_vertices()));
      }
      index[v] = 0;
    }
  }
  for (int v = 0; v < surface.num_vertices(); ++v) {
    if (index[v] == 0) {
      index[v] = top.num_vertices();
      top.vertices.push_back(surface.vertices[v]);
    }
  }
  for (const auto& t : surface.faces) top.faces.push_back({index[t[0]], index[t[1]], index[t[2]]});

  SupportObject result;
  Vec3 area_sum = Vec3::Zero();
  double area = 0.0;
  for (const auto& t : top.faces) {
    const Vec3 av = (top.vertices[t[1]] - top.vertices[t[0]]).cross(top.vertices[t[2]] - top.vertices[t[0]]);
    area_sum += av;
    area += av.norm();
  }
  Halfedges he = build_halfedges(top.num_vertices(), top.faces);
  auto loops = he.boundary_loops();
  if (options.shell_thickness == 0.0 && loops.size() != 1) {
    throw TopologyError(fmt::format(
        "support_object: the surface has {} boundary loops; a support with a base needs exactly one "
        "(a disk-like surface). Close the other holes, or use a shell support (shell thickness > 0)",
        loops.size()));
  }
  // A closed surface (shell only) keeps its orientation; an open one is
  // oriented so that its normals point away from the base.
  if (!loops.empty()) {
    if (!(std::abs(area_sum.dot(up)) > 1e-3 * area)) {
      throw InvalidInput(
          "support_object: the surface is edge-on when seen along the up direction (its projected area "
          "is zero); rotate it so that the knitted side faces up");
    }
    if (area_sum.dot(up) < 0.0) {
      result.reoriented = true;
      for (auto& t : top.faces) std::swap(t[1], t[2]);
      he = build_halfedges(top.num_vertices(), top.faces);
      loops = he.boundary_loops();
    }
  }
  const TriMesh offset = offset_surface(top, -options.offset, &result.flipped_faces);

  if (options.shell_thickness > 0.0) {
    ThickenResult shell = thicken_surface(offset, {options.shell_thickness, ThickenSide::Inside});
    result.flipped_faces += shell.flipped_faces;
    result.solid = std::move(shell.solid);
    return result;
  }

  // A = the boundary loop reversed (so the band glues to the surface).
  std::vector<int> a_ids(loops[0].rbegin(), loops[0].rend());
  std::vector<Vec3> a;
  for (int v : a_ids) a.push_back(offset.vertices[v]);

  // Plane frame: u x w = up.
  const Vec3 helper = std::abs(up.x()) < 0.9 ? Vec3(1, 0, 0) : Vec3(0, 1, 0);
  const Vec3 u = helper.cross(up).normalized();
  const Vec3 w = up.cross(u);
  double low = std::numeric_limits<double>::infinity();
  for (const Vec3& p : offset.vertices) low = std::min(low, p.dot(up));
  const double base_level = low - options.base_height;
  auto lift = [&](const Vec2& q) -> Vec3 { return q.x() * u + q.y() * w + base_level * up; };
  std::vector<Vec2> a2;
  for (const Vec3& p : a) a2.emplace_back(p.dot(u), p.dot(w));

  std::vector<Vec2> b2;
  if (options.base == SupportBase::Projected) {
    const int cross_at = first_self_intersection(a2);
    if (cross_at >= 0) {
      throw TopologyError(fmt::format(
          "support_object: the boundary of the surface, projected onto the base plane, intersects itself "
          "(at boundary vertex {}); use the rectangle base or reorient the surface",
          a_ids[cross_at]));
    }
    b2 = a2;
  } else {
    Vec2 lo = a2[0], hi = a2[0];
    double perimeter = 0.0;
    for (std::size_t i = 0; i < a2.size(); ++i) {
      lo = lo.cwiseMin(a2[i]);
      hi = hi.cwiseMax(a2[i]);
      perimeter += (a[(i + 1) % a.size()] - a[i]).norm();
    }
    lo -= Vec2::Constant(options.base_margin);
    hi += Vec2::Constant(options.base_margin);
    const double spacing = perimeter / static_cast<double>(a.size());
    // The rectangle's boundary points at the loop's spacing; the band between
    // the loops is triangulated by a dynamic program over both (|a| x |b|).
    const double points = 2.0 * ((hi.x() - lo.x()) + (hi.y() - lo.y())) / spacing;
    check_work({fmt::format("support_object: a base rectangle of {:.4g} x {:.4g} mm", hi.x() - lo.x(), hi.y() - lo.y()),
                points * static_cast<double>(a.size()), "band cells", 5e7, 16.0,
                "use a smaller base margin (--margin) or the projected base"});
    std::vector<Vec2> corners{lo, Vec2(hi.x(), lo.y()), hi, Vec2(lo.x(), hi.y())};
    if (signed_area(a2) < 0.0) std::reverse(corners.begin() + 1, corners.end());
    for (int s = 0; s < 4; ++s) {
      const Vec2 p = corners[s], q = corners[(s + 1) % 4];
      const int k = std::max(1, static_cast<int>(std::lround((q - p).norm() / spacing)));
      for (int i = 0; i < k; ++i) b2.push_back(p + (q - p) * (static_cast<double>(i) / k));
    }
  }
  std::vector<Vec3> b;
  for (const Vec2& q : b2) b.push_back(lift(q));

  LoopTessellationOptions lo;
  lo.cost = options.cost;
  const LoopTessellation band = loop_tessellation(a, b, lo);
  result.band_triangles = static_cast<int>(band.triangles.size());
  result.band_cost = band.cost;

  TriMesh& solid = result.solid;
  solid = offset;
  const int m = static_cast<int>(a.size());
  const int base0 = solid.num_vertices();
  for (const Vec3& p : b) solid.vertices.push_back(p);
  auto band_vertex = [&](int k) { return k < m ? a_ids[k] : base0 + (k - m); };
  for (const auto& t : band.triangles)
    solid.faces.push_back({band_vertex(t[0]), band_vertex(t[1]), band_vertex(t[2])});

  // The band runs along B backwards, so the cap runs along B forwards.
  bool centre = false;
  const auto cap = cap_polygon(b2, centre);
  const int nb = static_cast<int>(b2.size());
  if (centre) {
    Vec2 c = Vec2::Zero();
    for (const Vec2& q : b2) c += q;
    solid.vertices.push_back(lift(c / nb));
  }
  for (const auto& t : cap) solid.faces.push_back({base0 + t[0], base0 + t[1], base0 + t[2]});
  return result;
}

}  // namespace knitforge
