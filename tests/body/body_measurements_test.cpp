// Girths by sections (body/body_measurements.h) on meshes with known answers.
#include "knitforge/body/body_measurements.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "knitforge/util/errors.h"

namespace knitforge {
namespace {

constexpr double kPi = std::numbers::pi;

// An open tube of `sides` around the axis through `c` along z, rings at
// z = c.z + 0, 10, ..., 100; optionally with a notch (one vertex per ring
// pulled in to half the radius: a concave section).
TriMesh tube(const Vec3& c, double radius, int sides, bool notch = false) {
  TriMesh m;
  for (int r = 0; r <= 10; ++r) {
    for (int s = 0; s < sides; ++s) {
      const double phi = 2.0 * kPi * s / sides;
      const double rr = notch && s == 0 ? 0.5 * radius : radius;
      m.vertices.push_back(c + Vec3(rr * std::cos(phi), rr * std::sin(phi), 10.0 * r));
    }
  }
  auto id = [&](int r, int s) { return r * sides + s % sides; };
  for (int r = 0; r < 10; ++r) {
    for (int s = 0; s < sides; ++s) {
      m.faces.push_back({id(r, s), id(r + 1, s), id(r + 1, s + 1)});
      m.faces.push_back({id(r, s), id(r + 1, s + 1), id(r, s + 1)});
    }
  }
  return m;
}

TriMesh join(const TriMesh& a, const TriMesh& b) {
  TriMesh m = a;
  const int off = a.num_vertices();
  m.vertices.insert(m.vertices.end(), b.vertices.begin(), b.vertices.end());
  for (auto f : b.faces) m.faces.push_back({f[0] + off, f[1] + off, f[2] + off});
  return m;
}

double polygon_perimeter(double radius, int sides) { return 2.0 * sides * radius * std::sin(kPi / sides); }

TEST(SectionGirth, HorizontalCutOfACylinderIsItsPolygonsPerimeter) {
  const TriMesh m = tube({0, 0, 0}, 50.0, 64);
  // Between rings (z = 43), through a ring (z = 50: vertices on the plane).
  for (double z : {43.0, 50.0, 0.5}) {
    EXPECT_NEAR(section_girth(m, {0, 0, z}, Vec3::UnitZ(), {0, 0, z}), polygon_perimeter(50.0, 64), 1e-9) << z;
  }
}

TEST(SectionGirth, TiltedCutOfACylinderIsLongerLikeAnEllipse) {
  const TriMesh m = tube({0, 0, 0}, 30.0, 256);
  const double tilt = 0.4;  // the plane's normal leans by 0.4 rad: an ellipse with semi-axes r, r / cos
  const Vec3 n(std::sin(tilt), 0.0, std::cos(tilt));
  const double a = 30.0, b = 30.0 / std::cos(tilt);
  const double h = std::pow(a - b, 2) / std::pow(a + b, 2);
  const double ramanujan = kPi * (a + b) * (1.0 + 3.0 * h / (10.0 + std::sqrt(4.0 - 3.0 * h)));
  EXPECT_NEAR(section_girth(m, {0, 0, 50}, n, {0, 0, 50}), ramanujan, 1e-3 * ramanujan);
}

TEST(SectionGirth, ConcaveSectionIsMeasuredAcrossLikeATape) {
  // The notch makes the section concave; a tape spans it, so the girth is the
  // convex hull's perimeter: the notch costs less than its detour.
  const TriMesh m = tube({0, 0, 0}, 40.0, 16, true);
  const double g = section_girth(m, {0, 0, 45}, Vec3::UnitZ(), {0, 0, 45});
  const double full = polygon_perimeter(40.0, 16);
  EXPECT_LT(g, full);
  // Hull = the 16-gon without its vertex 0: its two neighbours joined.
  const double side = 2.0 * 40.0 * std::sin(kPi / 16);
  const double chord = 2.0 * 40.0 * std::sin(2.0 * kPi / 16);
  EXPECT_NEAR(g, full - 2.0 * side + chord, 1e-9);
}

TEST(SectionGirth, PicksTheLoopAroundTheAxisPoint) {
  const TriMesh m = join(tube({-100, 0, 0}, 40.0, 32), tube({100, 0, 0}, 20.0, 32));
  EXPECT_NEAR(section_girth(m, {0, 0, 45}, Vec3::UnitZ(), {-100, 0, 45}), polygon_perimeter(40.0, 32), 1e-9);
  EXPECT_NEAR(section_girth(m, {0, 0, 45}, Vec3::UnitZ(), {95, 3, 45}), polygon_perimeter(20.0, 32), 1e-9);
  // Outside both: the nearest loop.
  EXPECT_NEAR(section_girth(m, {0, 0, 45}, Vec3::UnitZ(), {30, 0, 45}), polygon_perimeter(20.0, 32), 1e-9);
  EXPECT_THROW(section_girth(m, {0, 0, 500}, Vec3::UnitZ(), {0, 0, 500}), InvalidInput);
}

TEST(Measurements, NamesRoundTrip) {
  for (int k = 0; k < kNumMeasurements; ++k) {
    const auto m = static_cast<Measurement>(k);
    EXPECT_EQ(measurement_from_key(measurement_info(m).key), m);
  }
  EXPECT_THROW(measurement_from_key("bust"), InvalidInput);
}

}  // namespace
}  // namespace knitforge
