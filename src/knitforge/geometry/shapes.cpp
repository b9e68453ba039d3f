#include "knitforge/geometry/shapes.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <numbers>

#include <fmt/core.h>

#include "knitforge/geometry/isotropic_remesh.h"
#include "knitforge/util/errors.h"

namespace knitforge {

namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kMaxFaces = 2e7;

void check_size(std::string_view shape, std::string_view name, double value) {
  if (!(value > 0.0) || !std::isfinite(value)) {
    throw InvalidInput(fmt::format("{}: {} must be a positive, finite number, got {}", shape, name, value));
  }
}

// Validates the edge length against the smallest dimension and the area.
void check_edge(std::string_view shape, double edge, double smallest_dimension, double area) {
  check_size(shape, "edge length", edge);
  if (edge > 0.25 * smallest_dimension) {
    throw InvalidInput(fmt::format("{}: edge length {} mm is too large for a shape of size {} mm; use at most {} mm",
                                   shape, edge, smallest_dimension, 0.25 * smallest_dimension));
  }
  if (area / (0.433 * edge * edge) > kMaxFaces) {
    throw InvalidInput(fmt::format("{}: edge length {} mm is too small (the mesh would have more than {:.0f} "
                                   "million faces); use a larger edge length",
                                   shape, edge, kMaxFaces / 1e6));
  }
}

// Triangulates the band between two neighbouring rings, marching once
// around both: in(i) / out(j) give
// the vertex of the i-th inner / j-th outer step (indices wrap around, so
// in(n_in) is in(0)). While both rings have vertices left,
// advance_outer(i, j) chooses the next triangle: {in(i), out(j), out(j+1)}
// when true, {in(i), out(j), in(i+1)} when false.
template <class In, class Out, class AdvanceOuter>
void join_rings(TriMesh& m, int n_in, int n_out, In in, Out out, AdvanceOuter advance_outer) {
  int i = 0, j = 0;
  while (i < n_in || j < n_out) {
    if (i == n_in || (j < n_out && advance_outer(i, j))) {
      m.faces.push_back({in(i), out(j), out(j + 1)});
      ++j;
    } else {
      m.faces.push_back({in(i), out(j), in(i + 1)});
      ++i;
    }
  }
}

// A disk-like mesh of concentric rings: ring 0 is a single centre vertex,
// ring k (1..K) has counts[k] vertices at angles 2π(j + offset_k)/counts[k].
// point(k, phi) gives the position. Faces are counter-clockwise when the
// parameter disk (k as radius, phi as angle) is seen from +z.
TriMesh ring_mesh(int rings, const std::function<int(int)>& count,
                  const std::function<Vec3(int, double)>& point) {
  TriMesh m;
  m.vertices.push_back(point(0, 0.0));
  std::vector<int> start{0}, size{1};
  std::vector<double> offset{0.0};
  for (int k = 1; k <= rings; ++k) {
    const int n = std::max(6, count(k));
    start.push_back(m.num_vertices());
    size.push_back(n);
    offset.push_back(k % 2 ? 0.0 : 0.5);
    for (int j = 0; j < n; ++j) m.vertices.push_back(point(k, 2.0 * kPi * (j + offset[k]) / n));
  }
  for (int j = 0; j < size[1]; ++j) m.faces.push_back({0, start[1] + j, start[1] + (j + 1) % size[1]});
  for (int k = 1; k < rings; ++k) {
    const int m_in = size[k], m_out = size[k + 1];
    auto angle_in = [&](int i) { return (i + offset[k]) / m_in; };
    auto angle_out = [&](int j) { return (j + offset[k + 1]) / m_out; };
    // Start both rings at their vertex of smallest angle; march by angle.
    join_rings(
        m, m_in, m_out, [&](int i) { return start[k] + i % m_in; },
        [&](int j) { return start[k + 1] + j % m_out; },
        [&](int i, int j) { return angle_out(j + 1) <= angle_in(i + 1); });
  }
  return m;
}

// A grid of nx x ny cells over [x0, x1] x [y0, y1] (parameters u, v) mapped
// by `point`, with alternating diagonals. Corners are returned in `corners`.
TriMesh grid_mesh(double x0, double x1, double y0, double y1, int nx, int ny,
                  const std::function<Vec3(double, double)>& point, std::vector<int>& corners) {
  TriMesh m;
  for (int j = 0; j <= ny; ++j) {
    for (int i = 0; i <= nx; ++i) {
      const double u = i == nx ? x1 : x0 + (x1 - x0) * i / nx;
      const double v = j == ny ? y1 : y0 + (y1 - y0) * j / ny;
      m.vertices.push_back(point(u, v));
    }
  }
  auto id = [&](int i, int j) { return j * (nx + 1) + i; };
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      const int a = id(i, j), b = id(i + 1, j), c = id(i + 1, j + 1), d = id(i, j + 1);
      if ((i + j) % 2 == 0) {
        m.faces.push_back({a, b, c});
        m.faces.push_back({a, c, d});
      } else {
        m.faces.push_back({a, b, d});
        m.faces.push_back({b, c, d});
      }
    }
  }
  corners = {id(0, 0), id(nx, 0), id(nx, ny), id(0, ny)};
  return m;
}

// Closest point of the boundary of [x0, x1] x [y0, y1] to (u, v).
Vec2 rectangle_boundary_point(double u, double v, double x0, double x1, double y0, double y1) {
  u = std::clamp(u, x0, x1);
  v = std::clamp(v, y0, y1);
  const double d[4] = {u - x0, x1 - u, v - y0, y1 - v};
  const int k = static_cast<int>(std::min_element(d, d + 4) - d);
  if (k == 0) u = x0;
  if (k == 1) u = x1;
  if (k == 2) v = y0;
  if (k == 3) v = y1;
  return {u, v};
}

int cells(double length, double edge) { return std::max(1, static_cast<int>(std::lround(length / edge))); }

// Remeshes the initial mesh of a height field z = height(x, y) over a
// rectangle, with the corners fixed.
TriMesh height_field_rectangle(double x0, double x1, double y0, double y1, double edge, int iterations,
                               const std::function<double(double, double)>& height) {
  std::vector<int> corners;
  TriMesh m = grid_mesh(x0, x1, y0, y1, cells(x1 - x0, edge), cells(y1 - y0, edge),
                        [&](double x, double y) { return Vec3(x, y, height(x, y)); }, corners);
  RemeshOptions o;
  o.target_edge_length = edge;
  o.iterations = iterations;
  o.fixed_vertices = corners;
  o.boundary_corner_angle_deg = 0.0;
  o.project = [=](const Vec3& p) {
    const double x = std::clamp(p.x(), x0, x1), y = std::clamp(p.y(), y0, y1);
    return Vec3(x, y, height(x, y));
  };
  o.project_boundary = [=](const Vec3& p) {
    const Vec2 q = rectangle_boundary_point(p.x(), p.y(), x0, x1, y0, y1);
    return Vec3(q.x(), q.y(), height(q.x(), q.y()));
  };
  return isotropic_remesh(m, o);
}

// Remeshes the initial mesh of a height field z = height(x, y) over the disk
// of radius r.
TriMesh height_field_disk(double r, double edge, int iterations,
                          const std::function<double(double, double)>& height) {
  const int rings = cells(r, edge);
  TriMesh m = ring_mesh(
      rings, [&](int k) { return static_cast<int>(std::lround(2.0 * kPi * r * k / rings / edge)); },
      [&](int k, double phi) {
        const double rho = k == rings ? r : r * k / rings;
        const double x = rho * std::cos(phi), y = rho * std::sin(phi);
        return Vec3(x, y, height(x, y));
      });
  RemeshOptions o;
  o.target_edge_length = edge;
  o.iterations = iterations;
  o.boundary_corner_angle_deg = 0.0;
  o.project = [=](const Vec3& p) {
    double x = p.x(), y = p.y();
    const double rho = std::hypot(x, y);
    if (rho > r) {
      x *= r / rho;
      y *= r / rho;
    }
    return Vec3(x, y, height(x, y));
  };
  o.project_boundary = [=](const Vec3& p) {
    const double rho = std::hypot(p.x(), p.y());
    const double x = rho > 0.0 ? r * p.x() / rho : r, y = rho > 0.0 ? r * p.y() / rho : 0.0;
    return Vec3(x, y, height(x, y));
  };
  return isotropic_remesh(m, o);
}

// The hemisphere of radius r built directly from rings of latitude (see
// hemisphere() in shapes.h): ring k (0..K) at polar angle θ_k = k π/(2K),
// K = round((π r / 2) / (√3/2 l)) so that neighbouring rings are the height
// of an equilateral triangle of side l apart; ring 0 is the pole, ring K the
// equator (z = 0 exactly). Ring k has max(6, round(2π r sin θ_k / l))
// vertices, uniformly spaced in longitude: odd rings have a vertex at
// longitude 90° (on the +y axis), even rings are turned by half of their
// spacing from there, so that rings of equal count are staggered
// (equilateral triangles) and every ring is mirror-symmetric about the plane
// x = 0. Neighbouring rings are joined by the usual ring-marching
// triangulation that always takes the shorter diagonal.
// A surface of revolution about the z axis from rings of latitude: ring 0
// is the pole, ring k (1..rings) the circle of radius profile(k).first at
// height profile(k).second, with max(6, round(2π ρ / l)) vertices placed as
// the hemisphere's (see above); the last ring is the boundary. Faces are
// oriented with normals away from the axis when the pole lies above.
TriMesh revolution_rings(int rings, double edge, const std::function<std::pair<double, double>(int)>& profile) {
  std::vector<int> start(rings + 1), count(rings + 1);
  std::vector<double> phase(rings + 1, 0.0);  // longitude of the ring's vertex 0
  start[0] = 0;
  count[0] = 1;
  long total = 1;
  for (int k = 1; k <= rings; ++k) {
    count[k] = std::max(6, static_cast<int>(std::lround(2.0 * kPi * profile(k).first / edge)));
    start[k] = static_cast<int>(total);
    total += count[k];
    phase[k] = 0.5 * kPi + (k % 2 == 1 ? 0.0 : kPi / count[k]);
  }
  TriMesh m;
  m.vertices.reserve(total);
  m.faces.reserve(2 * total);
  m.vertices.push_back(Vec3(0.0, 0.0, profile(0).second));
  for (int k = 1; k <= rings; ++k) {
    const auto [rho, z] = profile(k);
    // Longitude 90° + a_j, a_j = offset + 2πj/n; the mirror image (x -> -x)
    // of vertex j is vertex n - j (offset 0) or n - 1 - j (offset π/n), and
    // is copied with x negated so that the symmetry is exact.
    const int n = count[k];
    const bool odd = k % 2 == 1;
    for (int j = 0; j < n; ++j) {
      const int mirror = odd ? (n - j) % n : n - 1 - j;
      if (mirror < j) {
        const Vec3 q = m.vertices[start[k] + mirror];
        m.vertices.push_back(Vec3(-q.x(), q.y(), q.z()));
        continue;
      }
      const double a = (odd ? 0.0 : kPi / n) + 2.0 * kPi * j / n;
      m.vertices.push_back(Vec3(mirror == j ? 0.0 : -rho * std::sin(a), rho * std::cos(a), z));
    }
  }
  for (int j = 0; j < count[1]; ++j) m.faces.push_back({0, start[1] + j, start[1] + (j + 1) % count[1]});
  for (int k = 1; k < rings; ++k) {
    // Longitudes in turns after inner vertex 0: inner vertex i at i / nin,
    // the j-th outer vertex from j0 (the first at or after inner vertex 0)
    // at t0 + j / nout. The edge between inner vertex 0 and outer vertex j0
    // opens and closes the strip.
    const int nin = count[k], nout = count[k + 1];
    double t0 = (phase[k + 1] - phase[k]) / (2.0 * kPi);
    t0 -= std::floor(t0);
    int j0 = static_cast<int>(std::ceil(-t0 * nout - 1e-9));
    t0 += static_cast<double>(j0) / nout;
    j0 = ((j0 % nout) + nout) % nout;
    auto in = [&](int i) { return start[k] + i % nin; };
    auto out = [&](int j) { return start[k + 1] + (j0 + j) % nout; };
    join_rings(m, nin, nout, in, out, [&](int i, int j) {
      const double d_out = (m.vertices[in(i)] - m.vertices[out(j + 1)]).squaredNorm();
      const double d_in = (m.vertices[in(i + 1)] - m.vertices[out(j)]).squaredNorm();
      // Equal diagonals (up to rounding): advance the ring whose next vertex
      // comes first in longitude, so that the choice does not depend on the
      // last bits of sin and cos.
      return std::abs(d_out - d_in) <= 1e-9 * (d_out + d_in) ? t0 + (j + 1.0) / nout <= (i + 1.0) / nin
                                                             : d_out < d_in;
    });
  }
  return m;
}

TriMesh hemisphere_rings(double r, double edge) {
  const double spacing = 0.5 * std::sqrt(3.0) * edge;
  const int rings = std::max(2, static_cast<int>(std::lround(0.5 * kPi * r / spacing)));
  const double dtheta = 0.5 * kPi / rings;
  return revolution_rings(rings, edge, [&](int k) {
    if (k == 0) return std::pair<double, double>(0.0, r);
    const bool equator = k == rings;
    const double s = equator ? 1.0 : std::sin(k * dtheta), c = equator ? 0.0 : std::cos(k * dtheta);
    return std::pair<double, double>(r * s, r * c);
  });
}

// The beanie (see beanie() in shapes.h): its meridian, the quarter ellipse
// (R sin φ, band + H cos φ) from the crown, then the band's straight line
// down to z = 0, tabulated by arc length and cut into rings an equilateral
// triangle's height apart.
TriMesh beanie_rings(const BeanieShape& b, double edge) {
  constexpr int kTable = 4096;
  std::vector<double> arc(kTable + 1, 0.0);
  auto dome = [&](int i) {
    const double phi = 0.5 * kPi * i / kTable;
    return std::pair<double, double>(i == kTable ? b.radius : b.radius * std::sin(phi),
                                     b.band_height + (i == kTable ? 0.0 : b.crown_height * std::cos(phi)));
  };
  for (int i = 1; i <= kTable; ++i) {
    const auto [r0, z0] = dome(i - 1);
    const auto [r1, z1] = dome(i);
    arc[i] = arc[i - 1] + std::hypot(r1 - r0, z1 - z0);
  }
  const double dome_len = arc[kTable], total = dome_len + b.band_height;
  const int rings = std::max(2, static_cast<int>(std::lround(total / (0.5 * std::sqrt(3.0) * edge))));
  return revolution_rings(rings, edge, [&](int k) {
    if (k == rings) return std::pair<double, double>(b.radius, 0.0);
    const double s = total * k / rings;
    if (s >= dome_len) return std::pair<double, double>(b.radius, b.band_height - (s - dome_len));
    const auto it = std::upper_bound(arc.begin(), arc.end(), s);
    const int i = std::clamp(static_cast<int>(it - arc.begin()), 1, kTable);
    const double t = (s - arc[i - 1]) / (arc[i] - arc[i - 1]);
    const auto [r0, z0] = dome(i - 1);
    const auto [r1, z1] = dome(i);
    return std::pair<double, double>(r0 + t * (r1 - r0), z0 + t * (z1 - z0));
  });
}

// Ring of n vertices at height z on the circle of radius r: odd rings
// (k % 2 == 1) with a vertex at longitude 90° (the +y axis), even ones turned
// by half a spacing, so that the ring is mirror-symmetric about x = 0 (the
// mirror image of vertex j is vertex n - j, resp. n - 1 - j, copied with x
// negated so that the symmetry is exact).
void add_symmetric_ring(TriMesh& m, int k, int n, double r, double z) {
  const int start = m.num_vertices();
  const bool odd = k % 2 == 1;
  for (int j = 0; j < n; ++j) {
    const int mirror = odd ? (n - j) % n : n - 1 - j;
    if (mirror < j) {
      const Vec3 q = m.vertices[start + mirror];
      m.vertices.push_back(Vec3(-q.x(), q.y(), q.z()));
      continue;
    }
    const double a = (odd ? 0.0 : kPi / n) + 2.0 * kPi * j / n;
    m.vertices.push_back(Vec3(mirror == j ? 0.0 : -r * std::sin(a), r * std::cos(a), z));
  }
}

// The open tube from staggered rings (see open_tube() in shapes.h).
TriMesh tube_rings(double r, double h, double edge) {
  const int n = std::max(6, static_cast<int>(std::lround(2.0 * kPi * r / edge)));
  const int rings = std::max(1, static_cast<int>(std::lround(h / (0.5 * std::sqrt(3.0) * edge))));
  TriMesh m;
  m.vertices.reserve(static_cast<size_t>(n) * (rings + 1));
  m.faces.reserve(2 * static_cast<size_t>(n) * rings);
  for (int k = 0; k <= rings; ++k) add_symmetric_ring(m, k, n, r, k == rings ? h : h * k / rings);
  for (int k = 0; k < rings; ++k) {
    // In spacings from the upper ring's vertex 0, the lower ring's vertices
    // lie at L + 1/2 (upper ring odd) or L - 1/2 (upper ring even); starting
    // at the first one after upper vertex 0 (j0), the j-th is at j + 1/2.
    // The upper ring is the "inner" ring of join_rings(), which makes the
    // normals point outward.
    const int up = (k + 1) * n, low = k * n;
    const int j0 = (k + 1) % 2 == 1 ? 0 : 1;
    join_rings(
        m, n, n, [&](int i) { return up + i % n; }, [&](int j) { return low + (j0 + j) % n; },
        [](int i, int j) { return j + 1.5 <= i + 1; });
  }
  return m;
}

// Unit direction of the centre of the cap's face opening.
Vec3 cap_face_axis(const CapShape& c) {
  const double e = c.face_elevation_deg * kPi / 180.0;
  return Vec3(0.0, -std::cos(e), -std::sin(e));
}

// The closest point of the circle {x on the sphere of radius r : angle(x,
// axis) = a} to p (any point of p's half-plane around the axis).
Vec3 closest_on_rim(const Vec3& p, const Vec3& axis, double a, double r) {
  Vec3 t = p - p.dot(axis) * axis;
  if (t.norm() <= 1e-12 * r) t = axis.unitOrthogonal();
  return r * (std::cos(a) * axis + std::sin(a) * t.normalized());
}

}  // namespace

double triple_peak_height(double x, double y) {
  constexpr double scale = 50.0, w = 1.2, sigma2 = 0.1;
  const double u = x / scale, v = y / scale;
  double f = 0.0;
  for (double cx : {0.0, 1.0, -1.0}) f += std::exp(-((u - cx) * (u - cx) + v * v) / sigma2);
  return scale * w * f;
}

double monkey_saddle_height(double x, double y) {
  constexpr double scale = 50.0;
  const double u = x / scale, v = y / scale;
  return scale * (u * u * u - 3.0 * u * v * v);
}

TriMesh hemisphere(double radius, double edge_length) {
  check_size("hemisphere", "radius", radius);
  check_edge("hemisphere", edge_length, radius, 2.0 * kPi * radius * radius);
  return hemisphere_rings(radius, edge_length);
}

TriMesh beanie(const BeanieShape& shape, double edge_length) {
  check_size("beanie", "radius", shape.radius);
  check_size("beanie", "crown height", shape.crown_height);
  if (!(shape.band_height >= 0.0) || !std::isfinite(shape.band_height))
    throw InvalidInput(fmt::format("beanie: the band height must be 0 or more (mm), got {}", shape.band_height));
  const double a = shape.radius, c = shape.crown_height;
  // Half a spheroid's area (prolate or oblate) plus the band.
  double dome = kPi * a * a;
  if (std::abs(c - a) <= 1e-12 * a) {
    dome = 2.0 * kPi * a * a;
  } else if (c > a) {
    const double e = std::sqrt(1.0 - a * a / (c * c));
    dome += kPi * a * c * std::asin(e) / e;
  } else {
    const double e = std::sqrt(1.0 - c * c / (a * a));
    dome += kPi * c * c / e * std::atanh(e);
  }
  check_edge("beanie", edge_length, std::min(a, c), dome + 2.0 * kPi * a * shape.band_height);
  return beanie_rings(shape, edge_length);
}

TriMesh sock(const SockShape& s, double edge_length) {
  check_size("sock", "radius", s.radius);
  check_size("sock", "foot length", s.foot_length);
  check_size("sock", "heel radius", s.heel_radius);
  check_size("sock", "leg length", s.leg_length);
  if (!(s.radius < s.heel_radius))
    throw InvalidInput(fmt::format("sock: the radius ({} mm) must be below the heel radius ({} mm)", s.radius,
                                   s.heel_radius));
  const double r = s.radius, bend = 0.5 * kPi * s.heel_radius;
  const double cap = 0.5 * kPi * r, total = cap + s.foot_length + bend + s.leg_length;
  check_edge("sock", edge_length, std::min(r, s.foot_length),
             2.0 * kPi * r * r + 2.0 * kPi * r * (s.foot_length + bend + s.leg_length));
  // The straight sock: the toe's quarter circle from the tip (z = r), then
  // the tube down to z = -(axis length); a = -z is the distance along the
  // axis from the toe cap's centre.
  const int rings = std::max(3, static_cast<int>(std::lround(total / (0.5 * std::sqrt(3.0) * edge_length))));
  TriMesh m = revolution_rings(rings, edge_length, [&](int k) {
    const double t = total * k / rings;
    if (k == rings) return std::pair<double, double>(r, cap - total);
    if (t < cap) return std::pair<double, double>(r * std::sin(t / r), r * std::cos(t / r));
    return std::pair<double, double>(r, cap - t);
  });
  // Swept along the bent axis: the section's y toward the bend's centre
  // (n1, in the plane y = 0), its x along +y.
  const double Rb = s.heel_radius, Lf = s.foot_length;
  for (Vec3& p : m.vertices) {
    const double a = -p.z();
    Vec3 c, n1;
    if (a <= Lf) {
      c = Vec3(Lf - a, 0.0, 0.0);
      n1 = Vec3(0.0, 0.0, 1.0);
    } else if (a <= Lf + bend) {
      const double phi = (a - Lf) / Rb;
      c = Vec3(-Rb * std::sin(phi), 0.0, Rb * (1.0 - std::cos(phi)));
      n1 = Vec3(std::sin(phi), 0.0, std::cos(phi));
    } else {
      c = Vec3(-Rb, 0.0, Rb + (a - Lf - bend));
      n1 = Vec3(1.0, 0.0, 0.0);
    }
    p = c + p.y() * n1 + p.x() * Vec3(0.0, 1.0, 0.0);
  }
  return m;
}

TriMesh triple_peak(double edge_length) {
  check_edge("triple-peak", edge_length, 100.0, 150.0 * 100.0 * 1.5);
  return height_field_rectangle(-75.0, 75.0, -50.0, 50.0, edge_length, 10, triple_peak_height);
}

TriMesh monkey_saddle(double edge_length) {
  check_edge("monkey-saddle", edge_length, 100.0, kPi * 50.0 * 50.0 * 2.0);
  return height_field_disk(50.0, edge_length, 10, monkey_saddle_height);
}

TriMesh flat_disk(double radius, double edge_length) {
  check_size("disk", "radius", radius);
  check_edge("disk", edge_length, radius, kPi * radius * radius);
  return height_field_disk(radius, edge_length, 4, [](double, double) { return 0.0; });
}

TriMesh rectangle(double width, double height, double edge_length) {
  check_size("rectangle", "width", width);
  check_size("rectangle", "height", height);
  check_edge("rectangle", edge_length, std::min(width, height), width * height);
  return height_field_rectangle(-0.5 * width, 0.5 * width, -0.5 * height, 0.5 * height, edge_length, 6,
                                [](double, double) { return 0.0; });
}

TriMesh cylinder_patch(double radius, double angle, double height, double edge_length) {
  check_size("cylinder-patch", "radius", radius);
  check_size("cylinder-patch", "angle", angle);
  check_size("cylinder-patch", "height", height);
  const double r = radius, a = angle, h = height;
  const double arc = r * a;
  check_edge("cylinder-patch", edge_length, std::min(arc, h), arc * h);
  if (r * (2.0 * kPi - a) < edge_length) {
    throw InvalidInput(fmt::format(
        "cylinder-patch: angle {} rad leaves a gap of {} mm, less than the edge length {} mm; the patch "
        "must stay open (use a smaller angle)",
        a, r * (2.0 * kPi - a), edge_length));
  }
  // Parameters: u = arc length in [-arc/2, arc/2], v = z in [0, h].
  auto point = [r](double u, double v) { return Vec3(r * std::cos(u / r), r * std::sin(u / r), v); };
  auto params = [r](const Vec3& p) { return Vec2(r * std::atan2(p.y(), p.x()), p.z()); };
  std::vector<int> corners;
  TriMesh m = grid_mesh(-0.5 * arc, 0.5 * arc, 0.0, h, cells(arc, edge_length), cells(h, edge_length), point,
                        corners);
  RemeshOptions o;
  o.target_edge_length = edge_length;
  o.iterations = 6;
  o.fixed_vertices = corners;
  o.boundary_corner_angle_deg = 0.0;
  o.project = [=](const Vec3& p) {
    const Vec2 q = params(p);
    return point(std::clamp(q.x(), -0.5 * arc, 0.5 * arc), std::clamp(q.y(), 0.0, h));
  };
  o.project_boundary = [=](const Vec3& p) {
    const Vec2 q = params(p);
    const Vec2 b = rectangle_boundary_point(q.x(), q.y(), -0.5 * arc, 0.5 * arc, 0.0, h);
    return point(b.x(), b.y());
  };
  return isotropic_remesh(m, o);
}

TriMesh open_tube(double radius, double height, double edge_length) {
  check_size("tube", "radius", radius);
  check_size("tube", "height", height);
  check_edge("tube", edge_length, std::min(2.0 * kPi * radius / 6.0, height), 2.0 * kPi * radius * height);
  return tube_rings(radius, height, edge_length);
}

TriMesh sleeve(const SleeveShape& s, double edge_length) {
  check_size("sleeve", "start radius", s.start_radius);
  check_size("sleeve", "end radius", s.end_radius);
  check_size("sleeve", "bend radius", s.bend_radius);
  if (!(s.bend_deg > 0.0 && s.bend_deg <= 180.0))
    throw InvalidInput(fmt::format("sleeve: the bend angle must be in (0, 180] degrees, got {}", s.bend_deg));
  if (!(std::max(s.start_radius, s.end_radius) < s.bend_radius))
    throw InvalidInput(fmt::format("sleeve: the radii ({} and {} mm) must be below the bend radius ({} mm)",
                                   s.start_radius, s.end_radius, s.bend_radius));
  const double theta = s.bend_deg * kPi / 180.0, length = s.bend_radius * theta;
  const double mean = 0.5 * (s.start_radius + s.end_radius);
  check_edge("sleeve", edge_length, std::min(0.5 * kPi * std::min(s.start_radius, s.end_radius), length),
             2.0 * kPi * mean * length);
  // The straight tube of the mean radius (its ring vertex count),
  // mapped onto the sweep (ring k at arc fraction k / K).
  TriMesh m = tube_rings(mean, length, edge_length);
  for (Vec3& p : m.vertices) {
    const double t = std::clamp(p.z() / length, 0.0, 1.0), phi = theta * t;
    const double r = s.start_radius + (s.end_radius - s.start_radius) * t;
    const double a = std::atan2(p.y(), p.x());
    const Vec3 centre(s.bend_radius * (1.0 - std::cos(phi)), 0.0, s.bend_radius * std::sin(phi));
    const Vec3 inward(std::cos(phi), 0.0, -std::sin(phi));  // toward the bend centre; inward x y = the axis
    p = centre + r * (std::cos(a) * inward + std::sin(a) * Vec3(0.0, 1.0, 0.0));
  }
  return m;
}

TriMesh cap(const CapShape& c, double edge_length) {
  check_size("cap", "radius", c.radius);
  for (const auto& [name, a] : {std::pair<const char*, double>{"face angle", c.face_angle_deg},
                                {"neck angle", c.neck_angle_deg}}) {
    if (!(a >= 5.0 && a <= 85.0)) {
      throw InvalidInput(fmt::format("cap: the {} must be between 5 and 85 degrees, got {}", name, a));
    }
  }
  if (!std::isfinite(c.face_elevation_deg) || std::abs(c.face_elevation_deg) > 85.0) {
    throw InvalidInput(fmt::format("cap: the face elevation must be within ±85 degrees, got {}",
                                   c.face_elevation_deg));
  }
  const double r = c.radius, deg = kPi / 180.0;
  const double face = c.face_angle_deg * deg, neck = c.neck_angle_deg * deg;
  const Vec3 face_axis = cap_face_axis(c), neck_axis(0.0, 0.0, -1.0);
  // Angle between the two opening centres minus both openings: the gap.
  const double gap = std::acos(std::clamp(face_axis.dot(neck_axis), -1.0, 1.0)) - face - neck;
  if (!(gap * r >= 2.0 * edge_length)) {
    throw InvalidInput(fmt::format(
        "cap: the face and neck openings are {:.3g} mm apart, less than two edge lengths ({} mm); make "
        "them smaller or the edge length shorter",
        gap * r, 2.0 * edge_length));
  }
  const double area = 2.0 * kPi * r * r * (std::cos(face) + std::cos(neck));
  check_edge("cap", edge_length, std::min(gap * r * 4.0, r * std::sin(face)), area);

  // Rings of latitude from the crown to the neck rim, the faces of the face
  // opening removed (by their centroids), then remeshed with the rims held
  // on their circles.
  const double polar_end = kPi - neck;
  const int rings = std::max(2, static_cast<int>(std::lround(polar_end * r / (0.5 * std::sqrt(3.0) * edge_length))));
  const TriMesh full = ring_mesh(
      rings,
      [&](int k) { return static_cast<int>(std::lround(2.0 * kPi * r * std::sin(polar_end * k / rings) / edge_length)); },
      [&](int k, double phi) {
        const double theta = polar_end * k / rings;
        return Vec3(r * std::sin(theta) * std::cos(phi), r * std::sin(theta) * std::sin(phi), r * std::cos(theta));
      });
  TriMesh m;
  m.vertices = full.vertices;
  const double cos_face = std::cos(face);
  for (const auto& t : full.faces) {
    const Vec3 centroid = (full.vertices[t[0]] + full.vertices[t[1]] + full.vertices[t[2]]) / 3.0;
    if (centroid.normalized().dot(face_axis) < cos_face) m.faces.push_back(t);
  }
  // Drop the vertices inside the opening; boundary vertices go to their rim.
  {
    std::vector<int> index(m.num_vertices(), -1);
    for (const auto& t : m.faces)
      for (int v : t) index[v] = 0;
    std::vector<Vec3> kept;
    for (int v = 0; v < m.num_vertices(); ++v) {
      if (index[v] < 0) continue;
      index[v] = static_cast<int>(kept.size());
      kept.push_back(m.vertices[v]);
    }
    for (auto& t : m.faces)
      for (int& v : t) v = index[v];
    m.vertices = std::move(kept);
  }
  auto on_sphere = [r](const Vec3& p) {
    const double n = p.norm();
    return n > 0.0 ? Vec3(p * (r / n)) : Vec3(0.0, 0.0, r);
  };
  auto on_rims = [=](const Vec3& p) {
    // The nearer rim: compare the angular distances to the two circles.
    const Vec3 u = p.normalized();
    const double to_face = std::abs(std::acos(std::clamp(u.dot(face_axis), -1.0, 1.0)) - face);
    const double to_neck = std::abs(std::acos(std::clamp(u.dot(neck_axis), -1.0, 1.0)) - neck);
    return to_face <= to_neck ? closest_on_rim(p, face_axis, face, r) : closest_on_rim(p, neck_axis, neck, r);
  };
  RemeshOptions o;
  o.target_edge_length = edge_length;
  o.iterations = 8;
  o.boundary_corner_angle_deg = 0.0;
  o.project = on_sphere;
  o.project_boundary = on_rims;
  return isotropic_remesh(m, o);
}

std::vector<std::string> shape_names() {
  return {"hemisphere", "triple-peak", "monkey-saddle", "disk", "rectangle", "cylinder-patch", "cap", "tube", "sleeve", "beanie", "sock"};
}

TriMesh make_shape(std::string_view name, double edge_length) {
  if (name == "hemisphere") return hemisphere(75.0, edge_length);
  if (name == "triple-peak") return triple_peak(edge_length);
  if (name == "monkey-saddle") return monkey_saddle(edge_length);
  if (name == "disk") return flat_disk(50.0, edge_length);
  if (name == "rectangle") return rectangle(150.0, 100.0, edge_length);
  if (name == "cylinder-patch") return cylinder_patch(50.0, kPi, 100.0, edge_length);
  if (name == "cap") return cap(CapShape{}, edge_length);
  if (name == "tube") return open_tube(40.0, 100.0, edge_length);
  if (name == "sleeve") return sleeve(SleeveShape{}, edge_length);
  if (name == "beanie") return beanie(BeanieShape{}, edge_length);
  if (name == "sock") return sock(SockShape{}, edge_length);
  std::string names;
  for (const auto& n : shape_names()) names += (names.empty() ? "" : ", ") + n;
  throw InvalidInput(fmt::format("unknown shape '{}'; the built-in shapes are: {}", name, names));
}

}  // namespace knitforge
