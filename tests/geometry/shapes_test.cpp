#include "knitforge/geometry/shapes.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <numbers>
#include <set>
#include <utility>

#include <gtest/gtest.h>

#include "knitforge/geometry/halfedges.h"
#include "knitforge/geometry/mesh_measures.h"
#include "knitforge/geometry/surface_checks.h"
#include "knitforge/util/errors.h"

namespace knitforge {
namespace {

constexpr double kPi = std::numbers::pi;

struct ShapeSpec {
  std::function<bool(const Vec3&)> on_surface;
  std::function<bool(const Vec3&)> on_boundary;
  std::function<bool(const Vec3& centroid, const Vec3& normal)> oriented;
};

// Properties every built-in shape has (shapes.h).
void check_shape(const TriMesh& m, double edge, const ShapeSpec& spec) {
  const SurfaceReport r = validate_surface(m);
  EXPECT_TRUE(r.is_disk) << r.summary();
  EXPECT_TRUE(r.issues.empty()) << r.summary();
  int off_surface = 0, off_boundary = 0, flipped = 0;
  for (const Vec3& p : m.vertices) off_surface += !spec.on_surface(p);
  const Halfedges he = build_halfedges(m.num_vertices(), m.faces);
  for (int v = 0; v < m.num_vertices(); ++v) {
    if (he.is_boundary_vertex(v)) off_boundary += !spec.on_boundary(m.vertices[v]);
  }
  for (int f = 0; f < m.num_faces(); ++f) {
    const auto& t = m.faces[f];
    const Vec3 c = (m.vertices[t[0]] + m.vertices[t[1]] + m.vertices[t[2]]) / 3.0;
    flipped += !spec.oriented(c, face_normal(m, f));
  }
  EXPECT_EQ(off_surface, 0);
  EXPECT_EQ(off_boundary, 0);
  EXPECT_EQ(flipped, 0);
  const std::vector<double> lengths = edge_lengths(m);
  int in_range = 0;
  double sum = 0.0;
  for (double l : lengths) {
    in_range += l >= 0.6 * edge && l <= 1.5 * edge;
    sum += l;
  }
  EXPECT_GE(static_cast<double>(in_range) / lengths.size(), 0.97);
  const double mean = sum / lengths.size();
  EXPECT_GT(mean, 0.8 * edge);
  EXPECT_LT(mean, 1.2 * edge);
}

bool near(double a, double b) { return std::abs(a - b) <= 1e-9; }

bool on_rectangle_boundary(double x, double y, double x0, double x1, double y0, double y1) {
  const bool inside = x >= x0 - 1e-9 && x <= x1 + 1e-9 && y >= y0 - 1e-9 && y <= y1 + 1e-9;
  return inside && (near(x, x0) || near(x, x1) || near(y, y0) || near(y, y1));
}

// Total length of the boundary loops (mm).
double boundary_length(const TriMesh& m, const Halfedges& he) {
  double total = 0.0;
  for (const auto& loop : he.boundary_loops())
    for (size_t i = 0; i < loop.size(); ++i) total += (m.vertices[loop[(i + 1) % loop.size()]] - m.vertices[loop[i]]).norm();
  return total;
}

bool has_vertex(const TriMesh& m, const Vec3& p) {
  return std::any_of(m.vertices.begin(), m.vertices.end(), [&](const Vec3& q) { return (q - p).norm() < 1e-12; });
}

TEST(Shapes, Hemisphere) {
  const double r = 75.0, edge = 5.0;
  const TriMesh m = hemisphere(r, edge);
  check_shape(m, edge,
              {[&](const Vec3& p) { return near(p.norm(), r) && p.z() >= 0.0; },
               [&](const Vec3& p) { return near(std::hypot(p.x(), p.y()), r) && p.z() == 0.0; },
               [](const Vec3& c, const Vec3& n) { return n.dot(c) > 0.0; }});
  EXPECT_NEAR(total_area(m), 2.0 * kPi * r * r, 0.005 * 2.0 * kPi * r * r);
  const BoundingBox box = bounding_box(m);
  EXPECT_NEAR(box.max.z(), r, 0.01 * r);
  EXPECT_EQ(box.min.z(), 0.0);
}

// Smallest and largest interior angle (degrees) over all triangles.
std::pair<double, double> angle_range(const TriMesh& m) {
  double lo = 180.0, hi = 0.0;
  for (const auto& t : m.faces) {
    for (int k = 0; k < 3; ++k) {
      const Vec3 a = m.vertices[t[k]], b = m.vertices[t[(k + 1) % 3]], c = m.vertices[t[(k + 2) % 3]];
      const double cosine = std::clamp((b - a).normalized().dot((c - a).normalized()), -1.0, 1.0);
      const double angle = std::acos(cosine) * 180.0 / kPi;
      lo = std::min(lo, angle);
      hi = std::max(hi, angle);
    }
  }
  return {lo, hi};
}

// The hemisphere is built from rings of latitude (shapes.h): every edge in
// [0.8 l, 1.4 l] and every angle in [38°, 94°] at any resolution r/l >= 4,
// the pole a vertex, the boundary round(2πr/l) vertices on the circle.
TEST(Shapes, HemisphereRingMeshQualityAtEveryResolution) {
  for (const double r : {10.0, 75.0}) {
    for (const double ratio : {4.0, 4.4, 5.1, 6.0, 7.3, 8.8, 10.5, 13.0, 16.2, 21.0, 27.5, 30.0}) {
      const double edge = r / ratio;
      const TriMesh m = hemisphere(r, edge);
      SCOPED_TRACE(::testing::Message() << "r " << r << ", r/l " << ratio);
      ASSERT_TRUE(validate_surface(m).is_disk);
      const std::vector<double> lengths = edge_lengths(m);
      const auto [shortest, longest] = std::minmax_element(lengths.begin(), lengths.end());
      EXPECT_GE(*shortest, 0.8 * edge);
      EXPECT_LE(*longest, 1.4 * edge);
      const auto [lo, hi] = angle_range(m);
      EXPECT_GE(lo, 38.0);
      EXPECT_LE(hi, 94.0);
      EXPECT_TRUE(has_vertex(m, Vec3(0.0, 0.0, r)));
      const Halfedges he = build_halfedges(m.num_vertices(), m.faces);
      const auto loops = he.boundary_loops();
      ASSERT_EQ(loops.size(), 1u);
      EXPECT_EQ(static_cast<long>(loops[0].size()), std::lround(2.0 * kPi * r / edge));
      for (const Vec3& p : m.vertices) ASSERT_NEAR(p.norm(), r, 1e-12 * r);
      for (int f = 0; f < m.num_faces(); ++f) {
        const auto& t = m.faces[f];
        ASSERT_GT(face_normal(m, f).dot(m.vertices[t[0]] + m.vertices[t[1]] + m.vertices[t[2]]), 0.0);
      }
    }
  }
  // The issue's hemisphere: r 75, l 2.5 (the CLI default). The vertex density
  // is that of equilateral triangles of side l: 2πr² / (√3/2 l²) vertices.
  const double r = 75.0, edge = 2.5;
  const TriMesh m = hemisphere(r, edge);
  EXPECT_NEAR(m.num_vertices(), 2.0 * kPi * r * r / (0.5 * std::sqrt(3.0) * edge * edge),
              0.02 * m.num_vertices());
  const std::vector<double> lengths = edge_lengths(m);
  double sum = 0.0;
  for (double l : lengths) sum += l;
  EXPECT_NEAR(sum / lengths.size(), edge, 0.05 * edge);
  EXPECT_NEAR(total_area(m), 2.0 * kPi * r * r, 0.002 * 2.0 * kPi * r * r);
  // Exactly mirror-symmetric about x = 0 (the usual source plane of short
  // rows): the mirror image of every vertex is a vertex, bit for bit.
  std::set<std::array<double, 3>> points;
  for (const Vec3& p : m.vertices) points.insert({p.x(), p.y(), p.z()});
  int unmatched = 0;
  for (const Vec3& p : m.vertices) unmatched += !points.count({-p.x(), p.y(), p.z()});
  EXPECT_EQ(unmatched, 0);
  const BoundingBox box = bounding_box(m);
  EXPECT_EQ(box.min.x(), -box.max.x());
}

TEST(Shapes, FlatDisk) {
  const double r = 40.0, edge = 4.0;
  const TriMesh m = flat_disk(r, edge);
  check_shape(m, edge,
              {[&](const Vec3& p) { return p.z() == 0.0 && std::hypot(p.x(), p.y()) <= r + 1e-9; },
               [&](const Vec3& p) { return near(std::hypot(p.x(), p.y()), r); },
               [](const Vec3&, const Vec3& n) { return n.z() > 0.99; }});
  // Inscribed polygon: area slightly below πr², within 0.5%.
  EXPECT_NEAR(total_area(m), kPi * r * r, 0.005 * kPi * r * r);
  EXPECT_LT(total_area(m), kPi * r * r);
}

TEST(Shapes, RectangleIsExactWithCorners) {
  const double w = 60.0, h = 40.0, edge = 4.0;
  const TriMesh m = rectangle(w, h, edge);
  check_shape(m, edge,
              {[&](const Vec3& p) { return p.z() == 0.0 && std::abs(p.x()) <= w / 2 && std::abs(p.y()) <= h / 2; },
               [&](const Vec3& p) { return on_rectangle_boundary(p.x(), p.y(), -w / 2, w / 2, -h / 2, h / 2); },
               [](const Vec3&, const Vec3& n) { return n.z() > 0.99; }});
  EXPECT_NEAR(total_area(m), w * h, 1e-9 * w * h);
  for (double sx : {-1.0, 1.0})
    for (double sy : {-1.0, 1.0}) EXPECT_TRUE(has_vertex(m, Vec3(sx * w / 2, sy * h / 2, 0.0)));
}

// Midpoint-rule area of z = triple_peak_height over [-75, 75] x [-50, 50],
// with the analytic gradient of eq. 2.5.
double triple_peak_area_numeric() {
  const int nx = 900, ny = 600;
  const double hx = 150.0 / nx, hy = 100.0 / ny;
  double area = 0.0;
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      const double u = (-75.0 + (i + 0.5) * hx) / 50.0, v = (-50.0 + (j + 0.5) * hy) / 50.0;
      double fu = 0.0, fv = 0.0;
      for (double c : {0.0, 1.0, -1.0}) {
        const double e = 1.2 * std::exp(-((u - c) * (u - c) + v * v) / 0.1);
        fu += -2.0 * (u - c) / 0.1 * e;
        fv += -2.0 * v / 0.1 * e;
      }
      area += std::sqrt(1.0 + fu * fu + fv * fv) * hx * hy;
    }
  }
  return area;
}

TEST(Shapes, TriplePeak) {
  EXPECT_NEAR(triple_peak_height(0.0, 0.0), 50.0 * 1.2 * (1.0 + 2.0 * std::exp(-10.0)), 1e-12);
  EXPECT_NEAR(triple_peak_height(50.0, 0.0), 50.0 * 1.2 * (1.0 + std::exp(-10.0) + std::exp(-40.0)), 1e-12);
  const double edge = 5.0;
  const TriMesh m = triple_peak(edge);
  check_shape(m, edge,
              {[](const Vec3& p) {
                 return p.z() == triple_peak_height(p.x(), p.y()) && std::abs(p.x()) <= 75.0 &&
                        std::abs(p.y()) <= 50.0;
               },
               [](const Vec3& p) { return on_rectangle_boundary(p.x(), p.y(), -75, 75, -50, 50); },
               [](const Vec3&, const Vec3& n) { return n.z() > 0.0; }});
  const double exact = triple_peak_area_numeric();
  EXPECT_NEAR(total_area(m), exact, 0.01 * exact);
  const BoundingBox box = bounding_box(m);
  EXPECT_EQ(box.size().x(), 150.0);
  EXPECT_EQ(box.size().y(), 100.0);
  EXPECT_TRUE(has_vertex(m, Vec3(75.0, 50.0, triple_peak_height(75.0, 50.0))));
}

TEST(Shapes, MonkeySaddle) {
  EXPECT_DOUBLE_EQ(monkey_saddle_height(50.0, 0.0), 50.0);
  EXPECT_DOUBLE_EQ(monkey_saddle_height(-50.0, 0.0), -50.0);
  EXPECT_DOUBLE_EQ(monkey_saddle_height(0.0, 50.0), 0.0);
  const double edge = 2.5;
  const TriMesh m = monkey_saddle(edge);
  check_shape(m, edge,
              {[](const Vec3& p) {
                 return p.z() == monkey_saddle_height(p.x(), p.y()) && std::hypot(p.x(), p.y()) <= 50.0 + 1e-9;
               },
               [](const Vec3& p) { return near(std::hypot(p.x(), p.y()), 50.0); },
               [](const Vec3&, const Vec3& n) { return n.z() > 0.0; }});
  // Area of z = r³cos3φ over the unit disk, |grad| = 3r²: 2π (3√10 + asinh 3)/12, scaled by 50².
  const double exact = 2500.0 * 2.0 * kPi * (3.0 * std::sqrt(10.0) + std::asinh(3.0)) / 12.0;
  EXPECT_NEAR(total_area(m), exact, 0.01 * exact);
  const BoundingBox box = bounding_box(m);
  EXPECT_NEAR(box.size().x(), 100.0, 0.5);
  EXPECT_NEAR(box.size().y(), 100.0, 0.5);
  EXPECT_NEAR(box.size().z(), 100.0, 0.5);
}

TEST(Shapes, CylinderPatch) {
  const double r = 30.0, a = 0.75 * kPi, h = 40.0, edge = 3.0;
  const TriMesh m = cylinder_patch(r, a, h, edge);
  check_shape(m, edge,
              {[&](const Vec3& p) {
                 return near(std::hypot(p.x(), p.y()), r) && std::abs(std::atan2(p.y(), p.x())) <= a / 2 + 1e-12 &&
                        p.z() >= 0.0 && p.z() <= h;
               },
               [&](const Vec3& p) {
                 const double u = std::atan2(p.y(), p.x());
                 return near(p.z(), 0.0) || near(p.z(), h) || near(std::abs(u) * r, a / 2 * r);
               },
               [](const Vec3& c, const Vec3& n) { return n.dot(Vec3(c.x(), c.y(), 0.0)) > 0.0; }});
  EXPECT_NEAR(total_area(m), r * a * h, 0.005 * r * a * h);
  EXPECT_TRUE(has_vertex(m, Vec3(r * std::cos(a / 2), r * std::sin(a / 2), h)));
}

// The open tube: staggered rings, every vertex on the cylinder, the rims
// exact circles at z = 0 and z = h, outward normals, exactly mirror-
// symmetric about x = 0, two boundary loops.
TEST(Shapes, TubeIsAnOpenCylinder) {
  const double r = 40.0, h = 100.0, edge = 4.0;
  const TriMesh m = open_tube(r, h, edge);
  const SurfaceReport rep = validate_surface(m);
  EXPECT_TRUE(rep.issues.empty()) << rep.summary();
  EXPECT_EQ(rep.num_boundary_loops, 2);
  EXPECT_EQ(rep.genus, 0);
  EXPECT_EQ(rep.num_components, 1);
  const Halfedges he = build_halfedges(m.num_vertices(), m.faces);
  for (int v = 0; v < m.num_vertices(); ++v) {
    const Vec3& p = m.vertices[v];
    EXPECT_TRUE(near(std::hypot(p.x(), p.y()), r)) << v;
    if (he.is_boundary_vertex(v)) {
      EXPECT_TRUE(p.z() == 0.0 || p.z() == h) << v;
    }
    EXPECT_TRUE(has_vertex(m, Vec3(-p.x(), p.y(), p.z()))) << v;
  }
  for (int f = 0; f < m.num_faces(); ++f) {
    const auto& t = m.faces[f];
    const Vec3 c = (m.vertices[t[0]] + m.vertices[t[1]] + m.vertices[t[2]]) / 3.0;
    EXPECT_GT(face_normal(m, f).dot(Vec3(c.x(), c.y(), 0.0)), 0.0);
  }
  const std::vector<double> lengths = edge_lengths(m);
  const auto [lo, hi] = std::minmax_element(lengths.begin(), lengths.end());
  EXPECT_GT(*lo, 0.8 * edge);
  EXPECT_LT(*hi, 1.3 * edge);
  EXPECT_NEAR(total_area(m), 2 * kPi * r * h, 0.005 * 2 * kPi * r * h);
  EXPECT_THROW(open_tube(40.0, 100.0, 0.0), InvalidInput);
  EXPECT_THROW(open_tube(-1.0, 100.0, 4.0), InvalidInput);
}

// The beanie: one boundary loop (the rim, z = 0, 560 mm round), on the band
// cylinder or the spheroid, outward normals, the spheroid-plus-band area,
// mirror-symmetric about x = 0, the crown at the top.
TEST(Shapes, BeanieIsADomeOnABandClosedAtTheTop) {
  const BeanieShape b;
  const double edge = 4.0;
  const TriMesh m = beanie(b, edge);
  const SurfaceReport rep = validate_surface(m);
  EXPECT_TRUE(rep.issues.empty()) << rep.summary();
  EXPECT_EQ(rep.num_boundary_loops, 1);
  EXPECT_EQ(rep.genus, 0);
  EXPECT_EQ(rep.num_components, 1);
  const Halfedges he = build_halfedges(m.num_vertices(), m.faces);
  const double rim = boundary_length(m, he);
  double top = 0.0;
  for (int v = 0; v < m.num_vertices(); ++v) {
    const Vec3& p = m.vertices[v];
    top = std::max(top, p.z());
    const double rho = std::hypot(p.x(), p.y());
    if (p.z() <= b.band_height) {
      EXPECT_TRUE(near(rho, b.radius)) << v;
    } else {
      const double dz = (p.z() - b.band_height) / b.crown_height, dr = rho / b.radius;
      EXPECT_NEAR(dr * dr + dz * dz, 1.0, 1e-4) << v;
    }
    if (he.is_boundary_vertex(v)) {
      EXPECT_EQ(p.z(), 0.0) << v;
    }
    EXPECT_TRUE(has_vertex(m, Vec3(-p.x(), p.y(), p.z()))) << v;
  }
  EXPECT_NEAR(top, b.band_height + b.crown_height, 1e-9);
  EXPECT_NEAR(rim, 560.0, 0.01 * 560.0);
  const Vec3 mid(0.0, 0.0, b.band_height);
  for (int f = 0; f < m.num_faces(); ++f) {
    const auto& t = m.faces[f];
    const Vec3 c = (m.vertices[t[0]] + m.vertices[t[1]] + m.vertices[t[2]]) / 3.0;
    const Vec3 out = c.z() > b.band_height ? Vec3(c - mid) : Vec3(c.x(), c.y(), 0.0);
    EXPECT_GT(face_normal(m, f).dot(out), 0.0) << f;
  }
  const double a = b.radius, h = b.crown_height, e = std::sqrt(1.0 - a * a / (h * h));
  const double area = kPi * a * a + kPi * a * h * std::asin(e) / e + 2.0 * kPi * a * b.band_height;
  EXPECT_NEAR(total_area(m), area, 0.01 * area);
  const std::vector<double> lengths = edge_lengths(m);
  const auto [lo, hi] = std::minmax_element(lengths.begin(), lengths.end());
  EXPECT_GT(*lo, 0.6 * edge);
  EXPECT_LT(*hi, 1.5 * edge);
  EXPECT_THROW(beanie(BeanieShape{89.0, 100.0, -1.0}, edge), InvalidInput);
  EXPECT_THROW(beanie(b, 0.0), InvalidInput);
}

// The sock: one boundary loop (the rim, a circle of the radius at the top
// of the leg), every vertex on the swept tube or the toe's hemisphere, the
// outward normals, the Pappus area, mirror-symmetric about y = 0.
TEST(Shapes, SockIsABentTubeClosedAtTheToe) {
  const SockShape s;
  const double edge = 4.0, r = s.radius, Rb = s.heel_radius, Lf = s.foot_length;
  const TriMesh m = sock(s, edge);
  const SurfaceReport rep = validate_surface(m);
  EXPECT_TRUE(rep.issues.empty()) << rep.summary();
  EXPECT_EQ(rep.num_boundary_loops, 1);
  EXPECT_EQ(rep.genus, 0);
  EXPECT_EQ(rep.num_components, 1);
  // The nearest point of the axis.
  auto axis_point = [&](const Vec3& p) {
    if (p.x() >= Lf) return Vec3(Lf, 0.0, 0.0);
    if (p.x() >= 0.0) return Vec3(p.x(), 0.0, 0.0);
    if (p.z() >= Rb) return Vec3(-Rb, 0.0, p.z());
    const Vec3 q(p.x(), 0.0, p.z() - Rb);
    return Vec3(Vec3(0.0, 0.0, Rb) + Rb * q.normalized());
  };
  const Halfedges he = build_halfedges(m.num_vertices(), m.faces);
  const double rim = boundary_length(m, he);
  double lo_x = 0.0, hi_x = 0.0, lo_z = 0.0;
  for (int v = 0; v < m.num_vertices(); ++v) {
    const Vec3& p = m.vertices[v];
    lo_x = std::min(lo_x, p.x());
    hi_x = std::max(hi_x, p.x());
    lo_z = std::min(lo_z, p.z());
    EXPECT_NEAR((p - axis_point(p)).norm(), r, 1e-9 * r) << v;
    if (he.is_boundary_vertex(v)) {
      EXPECT_NEAR(p.z(), Rb + s.leg_length, 1e-9) << v;
    }
    EXPECT_TRUE(has_vertex(m, Vec3(p.x(), -p.y(), p.z()))) << v;
  }
  EXPECT_NEAR(hi_x - lo_x, Lf + 2 * r + Rb, 1e-6);  // heel to toe: 256 mm
  EXPECT_NEAR(Rb + s.leg_length - lo_z, Rb + s.leg_length + r, 0.01 * r);  // sole to rim
  EXPECT_NEAR(rim, 2 * kPi * r, 0.01 * 2 * kPi * r);
  for (int f = 0; f < m.num_faces(); ++f) {
    const auto& t = m.faces[f];
    const Vec3 c = (m.vertices[t[0]] + m.vertices[t[1]] + m.vertices[t[2]]) / 3.0;
    EXPECT_GT(face_normal(m, f).dot(c - axis_point(c)), 0.0) << f;
  }
  const double area = 2 * kPi * r * r + 2 * kPi * r * (Lf + 0.5 * kPi * Rb + s.leg_length);
  EXPECT_NEAR(total_area(m), area, 0.01 * area);
  EXPECT_THROW(sock(SockShape{80.0, 110.0, 70.0, 120.0}, edge), InvalidInput);  // radius above the heel's
  EXPECT_THROW(sock(SockShape{38.0, 0.0, 70.0, 120.0}, edge), InvalidInput);
  EXPECT_THROW(sock(s, 0.0), InvalidInput);
}

// The cap: on the sphere, both rims on their exact circles (the face opening
// within 35 degrees of -y, the neck within 40 degrees of -z), two loops,
// area 2 pi r^2 (cos 35 + cos 40).
TEST(Shapes, CapIsASphereWithTwoOpenings) {
  const CapShape c;
  const double edge = 5.0, r = c.radius;
  const TriMesh m = cap(c, edge);
  const SurfaceReport rep = validate_surface(m);
  EXPECT_TRUE(rep.issues.empty()) << rep.summary();
  EXPECT_EQ(rep.num_boundary_loops, 2);
  EXPECT_EQ(rep.genus, 0);
  const Halfedges he = build_halfedges(m.num_vertices(), m.faces);
  const Vec3 face(0, -1, 0), neck(0, 0, -1);
  const double cf = std::cos(c.face_angle_deg * kPi / 180), cn = std::cos(c.neck_angle_deg * kPi / 180);
  int on_face = 0, on_neck = 0;
  for (int v = 0; v < m.num_vertices(); ++v) {
    const Vec3& p = m.vertices[v];
    EXPECT_TRUE(near(p.norm(), r)) << v;
    const Vec3 u = p / r;
    EXPECT_LE(u.dot(face), cf + 1e-9);  // outside the openings
    EXPECT_LE(u.dot(neck), cn + 1e-9);
    if (he.is_boundary_vertex(v)) {
      const bool f = std::abs(u.dot(face) - cf) < 1e-9, n = std::abs(u.dot(neck) - cn) < 1e-9;
      EXPECT_TRUE(f || n) << v;
      on_face += f;
      on_neck += n;
    }
  }
  EXPECT_NEAR(on_face, 2 * kPi * r * std::sin(c.face_angle_deg * kPi / 180) / edge, 0.15 * on_face);
  EXPECT_NEAR(on_neck, 2 * kPi * r * std::sin(c.neck_angle_deg * kPi / 180) / edge, 0.15 * on_neck);
  for (int f = 0; f < m.num_faces(); ++f) {
    const auto& t = m.faces[f];
    EXPECT_GT(face_normal(m, f).dot(m.vertices[t[0]] + m.vertices[t[1]] + m.vertices[t[2]]), 0.0);
  }
  const double area = 2 * kPi * r * r * (cf + cn);
  EXPECT_NEAR(total_area(m), area, 0.01 * area);
  CapShape overlap;
  overlap.face_angle_deg = 60.0;
  overlap.neck_angle_deg = 50.0;
  EXPECT_THROW(cap(overlap, 5.0), InvalidInput);
  CapShape tiny;
  tiny.face_angle_deg = 2.0;
  EXPECT_THROW(cap(tiny, 5.0), InvalidInput);
}

TEST(Shapes, SleeveIsATaperedBentTubeWithOutwardNormals) {
  const SleeveShape s;
  const TriMesh m = sleeve(s, 4.0);
  const SurfaceReport r = validate_surface(m);
  ASSERT_TRUE(r.ok() && r.num_boundary_loops == 2 && r.genus == 0) << r.summary();
  const double theta = s.bend_deg * std::numbers::pi / 180.0, L = s.bend_radius * theta;
  // Every vertex at its cross-section's radius from the arc axis (centre (R, 0, 0), plane y = 0).
  double outward = 0.0;
  for (int f = 0; f < m.num_faces(); ++f) {
    const Vec3 c = (m.vertices[m.faces[f][0]] + m.vertices[m.faces[f][1]] + m.vertices[m.faces[f][2]]) / 3.0;
    const double phi = std::atan2(c.z(), s.bend_radius - c.x());
    const Vec3 axis(s.bend_radius * (1.0 - std::cos(phi)), 0.0, s.bend_radius * std::sin(phi));
    outward += face_normal(m, f).dot((c - axis).normalized()) > 0.0 ? 1.0 : -1.0;
  }
  EXPECT_EQ(outward, m.num_faces()) << "some normals point inward";
  for (const Vec3& p : m.vertices) {
    const double phi = std::atan2(p.z(), s.bend_radius - p.x());
    const Vec3 axis(s.bend_radius * (1.0 - std::cos(phi)), 0.0, s.bend_radius * std::sin(phi));
    const double t = phi / theta;
    ASSERT_GT(t, -1e-9);
    ASSERT_LT(t, 1.0 + 1e-9);
    EXPECT_NEAR((p - axis).norm(), s.start_radius + (s.end_radius - s.start_radius) * t, 1e-6);
  }
  // Pappus: area = 2 pi r_mean L (the taper changes it by a factor 1 + O(((r1 - r0) / L)^2)).
  EXPECT_NEAR(total_area(m) / (std::numbers::pi * (s.start_radius + s.end_radius) * L), 1.0, 0.01);
  SleeveShape bad;
  bad.start_radius = 400.0;
  EXPECT_THROW(sleeve(bad, 5.0), InvalidInput);
  bad = {};
  bad.bend_deg = 0.0;
  EXPECT_THROW(sleeve(bad, 5.0), InvalidInput);
}

TEST(Shapes, MakeShapeByNameIsDeterministic) {
  const auto names = shape_names();
  ASSERT_EQ(names.size(), 11u);
  for (const auto& name : names) {
    const TriMesh a = make_shape(name, 8.0);
    const TriMesh b = make_shape(name, 8.0);
    const SurfaceReport r = validate_surface(a);
    if (name == "cap" || name == "tube" || name == "sleeve") {
      EXPECT_TRUE(r.ok() && r.num_boundary_loops == 2 && r.genus == 0) << name << ": " << r.summary();
    } else {
      EXPECT_TRUE(r.is_disk) << name;
    }
    EXPECT_EQ(a.faces, b.faces) << name;
    ASSERT_EQ(a.vertices.size(), b.vertices.size()) << name;
    for (size_t v = 0; v < a.vertices.size(); ++v) ASSERT_EQ(a.vertices[v], b.vertices[v]) << name;
  }
  // Default sizes: hemisphere r 75, rectangle 150 x 100.
  EXPECT_NEAR(bounding_box(make_shape("hemisphere", 10.0)).size().x(), 150.0, 1.0);
  EXPECT_NEAR(total_area(make_shape("rectangle", 10.0)), 15000.0, 1e-6);
}

TEST(Shapes, BadInputThrows) {
  try {
    make_shape("sphere", 5.0);
    FAIL() << "no exception";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("hemisphere, triple-peak, monkey-saddle"), std::string::npos);
  }
  EXPECT_THROW(make_shape("disk", 0.0), InvalidInput);
  EXPECT_THROW(make_shape("disk", -1.0), InvalidInput);
  EXPECT_THROW(make_shape("disk", std::nan("")), InvalidInput);
  EXPECT_THROW(make_shape("disk", 40.0), InvalidInput);    // larger than a quarter of the radius
  EXPECT_THROW(make_shape("disk", 1e-4), InvalidInput);    // billions of faces
  EXPECT_THROW(hemisphere(-3.0, 1.0), InvalidInput);
  EXPECT_THROW(rectangle(10.0, std::numeric_limits<double>::infinity(), 1.0), InvalidInput);
  EXPECT_THROW(cylinder_patch(10.0, 2.0 * kPi, 10.0, 1.0), InvalidInput);  // closed
}

}  // namespace
}  // namespace knitforge
