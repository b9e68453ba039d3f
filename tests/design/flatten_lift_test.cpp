// lift_map_to_surface(): the designed stitch mesh of a pattern with darts.
#include <algorithm>
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "hemisphere_darts.h"
#include "knitforge/design/flatten/flatten_surface.h"
#include "knitforge/design/flatten/knit_flattened_pattern.h"
#include "knitforge/design/flatten/lift_map_to_surface.h"
#include "knitforge/geometry/shapes.h"

namespace knitforge {
namespace {

// Four one-end darts from the hemisphere's rim towards its top: the shape of
// `knitforge flatten hemisphere --auto-darts 4 --auto-darts-rms-only`.
std::vector<DartSpec> four_darts(double radius) { return hemisphere_rim_darts(radius, 0.55 * radius); }

double triangle_area(const Vec3& a, const Vec3& b, const Vec3& c) { return 0.5 * (b - a).cross(c - a).norm(); }

struct KnitStitchSizes {
  double longest_course = 0.0;  ///< longest bottom / top edge over the stitch width
  double longest_wale = 0.0;    ///< longest left / right edge over the stitch height
  double smallest_area = 1e300; ///< smallest area over sw sh
  int knit = 0;
};

KnitStitchSizes knit_stitch_sizes(const StitchMesh& sm, const KnitParams& p) {
  KnitStitchSizes out;
  for (const Stitch& s : sm.stitches) {
    if (s.type != StitchType::Knit) continue;
    const Vec3& bl = sm.vertices[s.v[0]];
    const Vec3& br = sm.vertices[s.v[1]];
    const Vec3& tr = sm.vertices[s.v[2]];
    const Vec3& tl = sm.vertices[s.v[3]];
    out.longest_course = std::max({out.longest_course, (br - bl).norm() / p.stitch_width,
                                   (tr - tl).norm() / p.stitch_width});
    out.longest_wale = std::max({out.longest_wale, (tl - bl).norm() / p.stitch_height,
                                 (tr - br).norm() / p.stitch_height});
    const double area = triangle_area(bl, br, tr) + triangle_area(bl, tr, tl);
    out.smallest_area = std::min(out.smallest_area, area / (p.stitch_width * p.stitch_height));
    ++out.knit;
  }
  return out;
}

TEST(LiftMapToSurface, StitchesAcrossAClosedDartKeepTheirSize) {
  // The vertices merged across a dart's Collapsed wedge have their stitch
  // corners on the dart's two legs, one seam on the surface. Lifted at the
  // middle of the wedge (the mean pattern point) they landed on one leg far
  // from both sides: the longest course and wale edges were 5.3 times their
  // ideal length. Points outside the pattern (long rows, dart mouths) clamped
  // to the boundary collapsed whole stitches (smallest area 5e-16 sw sh).
  // Now: 1.67, 3.30 (a long row's stitch joined to the rows above a
  // Collapsed notch) and 0.018 (a stitch cut by a shallow dart leg).
  const double radius = 75.0;
  const TriMesh m = hemisphere(radius, 6.0);
  const Flattening f = flatten_surface(m, four_darts(radius));
  ASSERT_EQ(f.darts.size(), 4u);
  KnitPatternOptions opt;
  opt.evaluate = false;
  const KnitParams p{};
  const KnitPatternResult k = knit_flattened_pattern(f, m, p, opt);
  ASSERT_TRUE(k.knittability.ok()) << k.knittability.text();
  ASSERT_GT(k.raster.map.num_stitches(), 2000);
  const KnitStitchSizes s = knit_stitch_sizes(k.designed, p);
  ASSERT_GT(s.knit, 2000);
  EXPECT_LT(s.longest_course, 2.5);
  EXPECT_LT(s.longest_wale, 4.0);
  EXPECT_GT(s.smallest_area, 1e-3);
}

TEST(PatternPointsToSurface, ExtendMapsOutsidePointsThroughTheClosestTriangle) {
  TriMesh m;
  m.vertices = {Vec3(0, 0, 0), Vec3(10, 0, 5), Vec3(0, 10, 0)};
  m.faces = {{0, 1, 2}};
  const std::vector<Vec2> uv = {{0, 0}, {2, 0}, {0, 2}};
  const std::vector<Vec2> pts = {Vec2(0.5, 0.5), Vec2(3, 0), Vec2(4, 0)};
  const auto e = pattern_points_to_surface(m, uv, pts, OutsidePattern::Extend);
  EXPECT_TRUE(e[0].isApprox(Vec3(2.5, 2.5, 1.25), 1e-12));  // inside: as with Closest
  EXPECT_TRUE(e[1].isApprox(Vec3(15, 0, 7.5), 1e-12));      // the triangle's affine map
  EXPECT_TRUE(e[2].isApprox(Vec3(20, 0, 10), 1e-12));
  const auto c = pattern_points_to_surface(m, uv, pts, OutsidePattern::Closest);
  EXPECT_TRUE(c[1].isApprox(c[2], 1e-12));  // both clamped to the corner (2, 0)
}

}  // namespace
}  // namespace knitforge
