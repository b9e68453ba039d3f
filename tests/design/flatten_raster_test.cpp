#include <cmath>

#include <gtest/gtest.h>

#include "knitforge/convert/map_knittability.h"
#include "knitforge/design/flatten/dart_hints.h"
#include "knitforge/design/flatten/flatten_surface.h"
#include "knitforge/design/flatten/knit_flattened_pattern.h"
#include "knitforge/design/flatten/lift_map_to_surface.h"
#include "knitforge/design/flatten/rasterize_pattern.h"
#include "knitforge/geometry/shapes.h"
#include "knitforge/util/errors.h"

namespace knitforge {
namespace {

// A flat pattern given directly (mesh in z = 0, uv = x, y).
std::vector<Vec2> planar_uv(const TriMesh& m) {
  std::vector<Vec2> uv;
  for (const auto& p : m.vertices) uv.emplace_back(p.x(), p.y());
  return uv;
}

int count_cells(const KnittingMap& map, CellType t) {
  int n = 0;
  for (auto c : map.cells) n += c == t ? 1 : 0;
  return n;
}

TEST(RasterizePattern, RectangleGivesAPlainSheet) {
  // 35 x 28 mm at 3.5 x 2.8 mm: 10 wales, 5 bitmap rows of 5.6 mm = 10 courses.
  const TriMesh m = rectangle(35.0, 28.0, 3.0);
  const KnitParams p{3.5, 2.8};
  const RasterizedPattern r = rasterize_pattern(m, planar_uv(m), p);
  EXPECT_EQ(r.map.cols, 10);
  EXPECT_EQ(r.map.rows, 10);
  EXPECT_EQ(count_cells(r.map, CellType::Knit), 100);
  EXPECT_EQ(r.added_long_rows, 0);
  EXPECT_NEAR(r.origin.x(), -17.5, 1e-9);
  EXPECT_NEAR(r.origin.y(), -14.0, 1e-9);
  const KnittabilityReport rep = check_knittability(r.map, p);
  EXPECT_TRUE(rep.violations.empty()) << rep.text();
}

TEST(RasterizePattern, SideNotchBecomesPairedShortRows) {
  // A 70 x 56 mm rectangle with a wedge cut in from the right side (a
  // horizontal one-end dart left open): rows at the wedge turn early.
  TriMesh m;
  const double w = 70.0, h = 56.0;
  // Polygon: (0,0) (w,0) (w,h/2-12) (w/2,h/2) (w,h/2+12) (w,h) (0,h), fan from (w/4, h/2).
  const std::vector<Vec2> poly = {{0, 0},          {w, 0}, {w, h / 2 - 12}, {w / 2, h / 2},
                                  {w, h / 2 + 12}, {w, h}, {0, h}};
  m.vertices.push_back(Vec3(w / 4, h / 2, 0));
  for (const auto& q : poly) m.vertices.push_back(Vec3(q.x(), q.y(), 0));
  for (int i = 0; i < 7; ++i) m.faces.push_back({0, 1 + i, 1 + (i + 1) % 7});
  const KnitParams p{3.5, 2.8};
  const RasterizedPattern r = rasterize_pattern(m, planar_uv(m), p);
  const int srr = count_cells(r.map, CellType::ShortRowRight);
  EXPECT_GT(srr, 4);
  EXPECT_EQ(srr % 2, 0);  // turns come in pairs
  EXPECT_GT(count_cells(r.map, CellType::Collapsed), 10);
  const KnittabilityReport rep = check_knittability(r.map, p);
  EXPECT_TRUE(rep.violations.empty()) << rep.text();
}

TEST(RasterizePattern, BadInputThrows) {
  const TriMesh m = rectangle(35.0, 28.0, 3.0);
  EXPECT_THROW(rasterize_pattern(m, planar_uv(m), KnitParams{0.0, 2.8}), InvalidInput);
  EXPECT_THROW(rasterize_pattern(m, {}, KnitParams{}), InvalidInput);
  auto uv = planar_uv(m);
  uv[3].x() = std::nan("");
  EXPECT_THROW(rasterize_pattern(m, uv, KnitParams{}), InvalidInput);
}

struct BuiltIn {
  const char* name;
  std::vector<DartSpec> darts;
};

std::vector<DartSpec> hemisphere_darts() {
  std::vector<DartSpec> darts;
  const double r = 40.0, R = 75.0, z = std::sqrt(R * R - r * r);
  const Vec3 tips[4] = {Vec3(r, 0, z), Vec3(-r, 0, z), Vec3(0, r, z), Vec3(0, -r, z)};
  for (int i = 0; i < 4; ++i) {
    DartSpec d;
    d.orientation = i < 2 ? DartOrientation::Horizontal : DartOrientation::Vertical;
    d.points = {DartWaypoint::at_position(tips[i])};
    d.to_boundary = true;
    darts.push_back(d);
  }
  return darts;
}

std::vector<DartSpec> saddle_darts() {
  DartSpec d;
  d.type = DartType::TwoEnd;
  d.orientation = DartOrientation::Vertical;
  d.points = {DartWaypoint::at_position(Vec3(0, -20, 0)), DartWaypoint::at_position(Vec3(0, 20, 0))};
  return {d};
}

TEST(KnitFlattenedPattern, BuiltInShapesGiveKnittableMaps) {
  const std::vector<BuiltIn> cases = {{"hemisphere", hemisphere_darts()},
                                      {"hemisphere", {}},
                                      {"monkey-saddle", saddle_darts()},
                                      {"monkey-saddle", {}},
                                      {"triple-peak", {}}};
  for (const auto& c : cases) {
    const TriMesh m = make_shape(c.name, 6.0);
    const Flattening f = flatten_surface(m, c.darts);
    KnitPatternOptions opt;
    opt.evaluate = false;
    const KnitPatternResult k = knit_flattened_pattern(f, m, KnitParams{}, opt);
    EXPECT_TRUE(k.knittability.violations.empty())
        << c.name << " with " << c.darts.size() << " darts: " << k.knittability.text();
    EXPECT_EQ(k.designed.num_stitches(), k.raster.map.num_stitches()) << c.name;
    // Roughly the pattern's area in stitches.
    EXPECT_NEAR(k.raster.map.num_stitches() * 3.5 * 2.8, f.stats.area_2d, 0.25 * f.stats.area_2d) << c.name;
  }
}

TEST(KnitFlattenedPattern, LiftedStitchesLieOnTheSurfaceAndEvaluate) {
  const TriMesh m = hemisphere(50.0, 6.0);
  const Flattening f = flatten_surface(m);
  const KnitPatternResult k = knit_flattened_pattern(f, m, KnitParams{});
  ASSERT_TRUE(k.knittability.ok()) << k.knittability.text();
  for (const auto& v : k.designed.vertices) {
    EXPECT_NEAR(v.norm(), 50.0, 0.5);  // on the (triangulated) sphere
    EXPECT_GE(v.z(), -1e-9);
  }
  ASSERT_TRUE(k.evaluation.has_value());
  EXPECT_TRUE(std::isfinite(k.evaluation->rms_error));
  EXPECT_LT(k.evaluation->designed_rms_error, 0.5);
  EXPECT_LT(k.evaluation->relative_rms_error, 0.2);
}

TEST(PatternPointsToSurface, MapsThroughBarycentricCoordinates) {
  TriMesh m;
  m.vertices = {Vec3(0, 0, 0), Vec3(10, 0, 5), Vec3(0, 10, 0)};
  m.faces = {{0, 1, 2}};
  const std::vector<Vec2> uv = {{0, 0}, {2, 0}, {0, 2}};
  const auto p = pattern_points_to_surface(m, uv, {Vec2(1, 0), Vec2(0.5, 0.5), Vec2(5, -1)});
  EXPECT_TRUE(p[0].isApprox(Vec3(5, 0, 2.5), 1e-12));
  EXPECT_TRUE(p[1].isApprox(Vec3(2.5, 2.5, 1.25), 1e-12));
  EXPECT_TRUE(p[2].isApprox(Vec3(10, 0, 5), 1e-12));  // outside: closest corner
}

TEST(DartHints, AutoDartsLowerTheDistortionOfADome) {
  const TriMesh m = hemisphere(60.0, 6.0);
  FlattenOptions opt;
  opt.enforce_dart_angle = false;
  const AutoDarts a = add_darts_automatically(m, {}, 3, opt);
  ASSERT_GE(a.added.size(), 1u) << a.stop_reason;
  ASSERT_EQ(a.rms_sequence.size(), a.added.size() + 1);
  for (size_t i = 1; i < a.rms_sequence.size(); ++i) EXPECT_LT(a.rms_sequence[i], a.rms_sequence[i - 1]);
  for (const auto& h : a.added) EXPECT_EQ(h.spec.type, DartType::OneEnd);
  EXPECT_EQ(a.flattening.darts.size(), a.darts.size());
}

TEST(DartHints, SaddleGetsATwoEndDart) {
  const TriMesh m = monkey_saddle(6.0);
  const Flattening f = flatten_surface(m);
  const auto h = propose_dart(f);
  ASSERT_TRUE(h.has_value());
  EXPECT_EQ(h->spec.type, DartType::TwoEnd);
  EXPECT_THROW(propose_dart(f, DartHintOptions{1.5, 0.3, 0.15}), InvalidInput);
}

}  // namespace
}  // namespace knitforge
