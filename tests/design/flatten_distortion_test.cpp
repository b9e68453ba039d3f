#include <cmath>

#include <gtest/gtest.h>

#include "knitforge/design/flatten/flattening_distortion.h"
#include "knitforge/util/errors.h"

namespace knitforge {
namespace {

Mat2 rotation(double a) {
  Mat2 r;
  r << std::cos(a), -std::sin(a), std::sin(a), std::cos(a);
  return r;
}

// A 3D triangle in a tilted plane, its isometric 2D frame, and q = A x.
TEST(FlatteningDistortion, KnownAffineMapGivesExactSingularValues) {
  const Vec3 o(1.0, 2.0, 3.0);
  const Vec3 u = Vec3(1.0, 1.0, 0.0).normalized();
  const Vec3 w = Vec3(-1.0, 1.0, 2.0).normalized();  // orthogonal to u
  const Vec2 x1(4.0, 0.0);
  const Vec2 x2(1.0, 3.0);
  const Vec3 p0 = o;
  const Vec3 p1 = o + x1.x() * u + x1.y() * w;
  const Vec3 p2 = o + x2.x() * u + x2.y() * w;
  // A = R(0.7) diag(2, 0.6) R(-0.3): singular values 2, 0.6; U = R(0.7).
  const Mat2 A = rotation(0.7) * Vec2(2.0, 0.6).asDiagonal() * rotation(-0.3);
  const Vec2 q0(5.0, -1.0);
  const Mat2 T = triangle_map(p0, p1, p2, q0, q0 + A * x1, q0 + A * x2);
  ASSERT_TRUE(T.isApprox(A, 1e-12));
  const FaceDistortion d = decompose_map(T);
  EXPECT_NEAR(d.sigma1, 2.0, 1e-12);
  EXPECT_NEAR(d.sigma2, 0.6, 1e-12);
  EXPECT_NEAR(std::abs(d.dir1.dot(rotation(0.7).col(0))), 1.0, 1e-12);
  EXPECT_NEAR(std::abs(d.dir2.dot(rotation(0.7).col(1))), 1.0, 1e-12);
  EXPECT_FALSE(d.flipped);
  EXPECT_NEAR(d.dominant_log(), std::log(2.0), 1e-12);
}

TEST(FlatteningDistortion, MirroredMapIsFlipped) {
  Mat2 M;
  M << 1.0, 0.0, 0.0, -3.0;
  const FaceDistortion d = decompose_map(M);
  EXPECT_TRUE(d.flipped);
  EXPECT_NEAR(d.sigma1, 3.0, 1e-12);
  EXPECT_NEAR(d.sigma2, 1.0, 1e-12);
}

TEST(FlatteningDistortion, StatsOfUniformScaling) {
  TriMesh m;
  m.vertices = {Vec3(0, 0, 0), Vec3(2, 0, 0), Vec3(2, 1, 0), Vec3(0, 1, 0)};
  m.faces = {{0, 1, 2}, {0, 2, 3}};
  // x scaled by 2, y by 0.5.
  std::vector<Vec2> uv;
  for (const auto& p : m.vertices) uv.emplace_back(2.0 * p.x(), 0.5 * p.y());
  const auto d = flattening_distortion(m, uv);
  const DistortionStats s = distortion_stats(m, uv, d);
  EXPECT_NEAR(s.max_log_sigma, std::log(2.0), 1e-12);
  EXPECT_NEAR(s.min_log_sigma, std::log(0.5), 1e-12);
  EXPECT_NEAR(s.mean_log_sigma, 0.0, 1e-12);
  EXPECT_NEAR(s.rms_log_sigma, std::log(2.0), 1e-12);
  EXPECT_NEAR(s.area_3d, 2.0, 1e-12);
  EXPECT_NEAR(s.area_2d, 2.0, 1e-12);
  EXPECT_EQ(s.flipped_faces, 0);
  const auto e = vertex_distortion_energy(m, d);
  EXPECT_NEAR(e[0], 2.0 * std::log(2.0) * std::log(2.0), 1e-12);
}

TEST(FlatteningDistortion, ColoursWhiteAtOneBlueCompressionRedStretch) {
  FaceDistortion iso;
  FaceDistortion comp;
  comp.sigma1 = 1.0;
  comp.sigma2 = 0.5;
  FaceDistortion str;
  str.sigma1 = 2.0;
  str.sigma2 = 0.9;
  const auto c = distortion_colours({iso, comp, str}, 0.3);
  EXPECT_EQ(c[0], (Rgb8{255, 255, 255}));
  EXPECT_EQ(c[1], (Rgb8{0, 0, 255}));
  EXPECT_EQ(c[2], (Rgb8{255, 0, 0}));
  EXPECT_THROW(distortion_colours({iso}, 0.0), InvalidInput);
}

TEST(FlatteningDistortion, SizeMismatchThrows) {
  TriMesh m;
  m.vertices = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)};
  m.faces = {{0, 1, 2}};
  EXPECT_THROW(flattening_distortion(m, {Vec2::Zero()}), InvalidInput);
}

TEST(FlatteningDistortion, SvgHasOnePolygonPerFace) {
  TriMesh m;
  m.vertices = {Vec3(0, 0, 0), Vec3(2, 0, 0), Vec3(2, 1, 0), Vec3(0, 1, 0)};
  m.faces = {{0, 1, 2}, {0, 2, 3}};
  std::vector<Vec2> uv;
  for (const auto& p : m.vertices) uv.emplace_back(p.x(), p.y());
  const std::string svg = pattern_svg(m, uv, flattening_distortion(m, uv), {Vec2(1, 1)});
  size_t polys = 0;
  for (size_t p = svg.find("<polygon"); p != std::string::npos; p = svg.find("<polygon", p + 1)) ++polys;
  EXPECT_EQ(polys, 2u);
  EXPECT_NE(svg.find("<circle"), std::string::npos);
  EXPECT_EQ(svg.find("nan"), std::string::npos);
}

}  // namespace
}  // namespace knitforge
