#include <cmath>

#include <gtest/gtest.h>

#include "saddle_dart.h"

#include "hemisphere_darts.h"
#include "knitforge/design/flatten/dart.h"
#include "knitforge/design/flatten/flatten_surface.h"
#include "knitforge/geometry/shapes.h"
#include "knitforge/geometry/surface_checks.h"
#include "knitforge/util/errors.h"

namespace knitforge {
namespace {

constexpr double kR = 60.0;

// Four one-end darts on the hemisphere, tips at 30 mm from the axis.
std::vector<DartSpec> four_darts() { return hemisphere_rim_darts(kR, 30.0); }

TEST(FlattenDarts, CuttingKeepsTheMeshAManifoldDisk) {
  const TriMesh m = hemisphere(kR, 6.0);
  const CutDarts cut = cut_darts(m, four_darts());
  const SurfaceReport rep = validate_surface(cut.mesh);
  EXPECT_TRUE(rep.ok()) << rep.summary();
  EXPECT_TRUE(rep.manifold);
  EXPECT_TRUE(rep.is_disk) << rep.summary();  // one-end darts open the boundary
  ASSERT_EQ(cut.darts.size(), 4u);
  for (const auto& d : cut.darts) {
    EXPECT_NE(d.notch_a, d.notch_b);
    // Both notch copies sit where the boundary point was.
    EXPECT_LT((cut.mesh.vertices[d.notch_a] - cut.mesh.vertices[d.notch_b]).norm(), 1e-9);
    EXPECT_NEAR(std::hypot(cut.mesh.vertices[d.notch_a].x(), cut.mesh.vertices[d.notch_a].y()), kR, 0.5);
    EXPECT_GT(d.length, 15.0);
  }
}

TEST(FlattenDarts, AlignmentHoldsAndDistortionDrops) {
  const TriMesh m = hemisphere(kR, 6.0);
  FlattenOptions opt;
  opt.enforce_dart_angle = false;
  const Flattening plain = flatten_surface(m, {}, opt);
  const Flattening darted = flatten_surface(m, four_darts(), opt);
  double size = 0.0;
  for (const auto& p : darted.uv) size = std::max(size, p.norm());
  for (const auto& d : darted.darts) {
    const Vec2 a = darted.uv[d.notch_a];
    const Vec2 b = darted.uv[d.notch_b];
    if (d.orientation == DartOrientation::Horizontal) {
      EXPECT_LE(std::abs(a.x() - b.x()), 1e-6 * size);
      EXPECT_GT(std::abs(a.y() - b.y()), 1.0);  // the dart opened
    } else {
      EXPECT_LE(std::abs(a.y() - b.y()), 1e-6 * size);
      EXPECT_GT(std::abs(a.x() - b.x()), 1.0);
    }
    EXPECT_GT(d.angle_deg, 1.0);
    EXPECT_LE(d.alignment_error, 1e-6 * size);
  }
  EXPECT_LT(darted.stats.rms_log_sigma, 0.8 * plain.stats.rms_log_sigma);
  EXPECT_TRUE(darted.flipped_faces.empty());
  EXPECT_TRUE(plain.flipped_faces.empty());
}

TEST(FlattenDarts, TwoEndDartOnMonkeySaddle) {
  const TriMesh m = monkey_saddle(6.0);
  const DartSpec d = saddle_two_end_dart();
  const CutDarts cut = cut_darts(m, {d});
  const SurfaceReport rep = validate_surface(cut.mesh);
  EXPECT_TRUE(rep.ok() && rep.manifold) << rep.summary();
  EXPECT_EQ(rep.num_boundary_loops, 2);
  EXPECT_EQ(rep.num_components, 1);
  FlattenOptions opt;
  opt.enforce_dart_angle = false;
  const Flattening plain = flatten_surface(m, {}, opt);
  const Flattening f = flatten_surface(m, {d}, opt);
  ASSERT_EQ(f.darts.size(), 1u);
  EXPECT_EQ(f.darts[0].tips.size(), 2u);
  EXPECT_LE(f.darts[0].alignment_error, 1e-9 * 100.0);
  EXPECT_LT(f.stats.rms_log_sigma, plain.stats.rms_log_sigma);
}

TEST(FlattenDarts, BadDartsGiveClearErrors) {
  const TriMesh m = hemisphere(kR, 8.0);
  DartSpec inside;  // one-end, both points inside, no to_boundary
  inside.points = {DartWaypoint::at_position(Vec3(10, 0, 59)), DartWaypoint::at_position(Vec3(20, 0, 56))};
  try {
    cut_darts(m, {inside});
    FAIL() << "expected InvalidInput";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("dart 0"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("boundary"), std::string::npos) << e.what();
  }
  DartSpec off;
  off.points = {DartWaypoint::at_vertex(m.num_vertices() + 3), DartWaypoint::at_vertex(0)};
  DartSpec ok = four_darts()[0];
  try {
    cut_darts(m, {ok, off});
    FAIL() << "expected InvalidInput";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("dart 1, point 0"), std::string::npos) << e.what();
  }
  DartSpec bad_bary;
  bad_bary.to_boundary = true;
  bad_bary.points = {DartWaypoint::in_face(0, Vec3(0.5, 0.7, -0.2))};
  EXPECT_THROW(cut_darts(m, {bad_bary}), InvalidInput);
  DartSpec too_few;
  too_few.type = DartType::TwoEnd;
  too_few.points = {DartWaypoint::at_vertex(0)};
  EXPECT_THROW(cut_darts(m, {too_few}), InvalidInput);
}

TEST(FlattenDarts, WideDartIsRejectedWhenEnforced) {
  const TriMesh m = hemisphere(kR, 6.0);
  DartSpec d = four_darts()[0];
  FlattenOptions opt;
  opt.stitch_width = 20.0;  // limit 2 atan(2.8 / 20) = 16 degrees
  try {
    flatten_surface(m, {d}, opt);
    FAIL() << "expected InvalidInput";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("dart 0"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("degrees"), std::string::npos) << e.what();
  }
}

TEST(FlattenDarts, NonDiskInputIsRejected) {
  TriMesh tet;
  tet.vertices = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)};
  tet.faces = {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}};
  EXPECT_THROW(flatten_surface(tet), TopologyError);
}

TEST(FlattenDarts, AngleLimits) {
  EXPECT_NEAR(dart_angle_limit(DartOrientation::Horizontal, 3.5, 2.8),
              2.0 * std::atan(0.8) * 180.0 / 3.14159265358979, 1e-9);
  EXPECT_NEAR(dart_angle_limit(DartOrientation::Horizontal, 3.0, 3.0), 90.0, 1e-9);
  EXPECT_NEAR(dart_angle_limit(DartOrientation::Vertical, 6.0, 3.0), 90.0, 1e-9);
  EXPECT_THROW(dart_angle_limit(DartOrientation::Vertical, 0.0, 3.0), InvalidInput);
}

}  // namespace
}  // namespace knitforge
