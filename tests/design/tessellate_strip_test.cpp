#include "knitforge/design/shortrow/tessellate_strip.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "knitforge/geometry/halfedges.h"
#include "knitforge/util/errors.h"

namespace knitforge {
namespace {

using Faces = std::vector<StripFace>;

std::vector<Vec3> line(double x, double y0, double y1, int segments) {
  std::vector<Vec3> p;
  for (int k = 0; k <= segments; ++k) p.emplace_back(x, y0 + (y1 - y0) * k / segments, 0.0);
  return p;
}

std::vector<Vec3> ys(double x, std::initializer_list<double> y) {
  std::vector<Vec3> p;
  for (double v : y) p.emplace_back(x, v, 0.0);
  return p;
}

/// Arc of radius r about (cx, 0), angles -theta..theta; x = cx + sign r cos t,
/// y = r sin t, so it runs in +y. Sampled into an even number of segments of
/// length close to sh.
std::vector<Vec3> arc(double cx, double sign, double r, double theta, double sh) {
  const int pairs = static_cast<int>(std::lround(r * 2.0 * theta / (2.0 * sh)));
  const int n = 2 * pairs;
  std::vector<Vec3> p;
  for (int k = 0; k <= n; ++k) {
    const double t = -theta + 2.0 * theta * k / n;
    p.emplace_back(cx + sign * r * std::cos(t), r * std::sin(t), 0.0);
  }
  return p;
}

StripOptions opts(double sw, double sh) {
  StripOptions o;
  o.stitch_width = sw;
  o.stitch_height = sh;
  return o;
}

StripFace face(StitchType t, std::array<int, 4> c, int course) {
  StripFace f;
  f.type = t;
  f.corners = c;
  f.course = course;
  f.direction = course % 2 == 0 ? 1 : -1;
  return f;
}

void expect_faces(const Faces& got, const Faces& want) {
  ASSERT_EQ(got.size(), want.size());
  for (size_t k = 0; k < got.size(); ++k) {
    EXPECT_EQ(got[k].type, want[k].type) << "face " << k;
    EXPECT_EQ(got[k].corners, want[k].corners) << "face " << k;
    EXPECT_EQ(got[k].course, want[k].course) << "face " << k;
    EXPECT_EQ(got[k].direction, want[k].direction) << "face " << k;
  }
}

/// Every face valid, CCW from +z, courses 0..n-1 alternating; the faces
/// form one manifold, consistently oriented strip (a disk).
void expect_valid_strip(const StripTessellation& t, const std::vector<Vec3>& a,
                        const std::vector<Vec3>& b) {
  std::vector<Vec3> pts = a;
  pts.insert(pts.end(), b.begin(), b.end());
  std::vector<int> start{0}, verts;
  for (size_t f = 0; f < t.faces.size(); ++f) {
    const StripFace& s = t.faces[f];
    const int n = corner_count(s.type);
    EXPECT_EQ(s.course, static_cast<int>(f));
    EXPECT_EQ(s.direction, f % 2 == 0 ? 1 : -1);
    if (n == 3) {
      EXPECT_EQ(s.corners[3], -1);
    }
    double area2 = 0.0;
    for (int k = 0; k < n; ++k) {
      const int v = s.corners[static_cast<size_t>(k)];
      ASSERT_GE(v, 0);
      ASSERT_LT(v, static_cast<int>(pts.size()));
      for (int m = 0; m < k; ++m) EXPECT_NE(v, s.corners[static_cast<size_t>(m)]);
      const Vec3& p = pts[static_cast<size_t>(v)];
      const Vec3& q = pts[static_cast<size_t>(s.corners[static_cast<size_t>((k + 1) % n)])];
      area2 += p.x() * q.y() - q.x() * p.y();
      verts.push_back(v);
    }
    EXPECT_GT(area2, 0.0) << "face " << f << " is not counter-clockwise";
    start.push_back(static_cast<int>(verts.size()));
  }
  const Halfedges h = build_halfedges(static_cast<int>(pts.size()), start, verts);
  int comps = 0;
  h.face_components(&comps);
  EXPECT_EQ(comps, 1);
  EXPECT_EQ(h.boundary_loops().size(), 1u);
  // Every sample is used (nothing of the strip dropped).
  for (int v = 0; v < static_cast<int>(pts.size()); ++v) EXPECT_FALSE(h.is_isolated_vertex(v)) << v;
}

int count_ops(const StripTessellation& t, StripOperator op) {
  return static_cast<int>(std::count_if(t.steps.begin(), t.steps.end(),
                                        [&](const StripStep& s) { return s.op == op; }));
}

double min_interior_apex_distance(const StripTessellation& t) {
  double d = std::numeric_limits<double>::infinity();
  for (size_t p = 0; p < t.apexes.size(); ++p)
    for (size_t q = 0; q < p; ++q)
      if (!t.apexes[p].on_wale_end && !t.apexes[q].on_wale_end)
        d = std::min(d, (t.apexes[p].position - t.apexes[q].position).norm());
  return d;
}

TEST(TessellateStrip, ParallelEqualWalesGiveOnlyQuads) {
  const auto a = line(0.0, 0.0, 20.0, 20), b = line(4.0, 0.0, 20.0, 20);
  const StripTessellation t = tessellate_strip(a, b, opts(4.0, 1.0));
  ASSERT_EQ(t.steps.size(), 10u);
  EXPECT_EQ(count_ops(t, StripOperator::ABAdvance), 10);
  ASSERT_EQ(t.faces.size(), 20u);
  for (int k = 0; k < 20; ++k)
    EXPECT_EQ(t.faces[static_cast<size_t>(k)].corners, (std::array<int, 4>{k, 21 + k, 22 + k, k + 1}));
  EXPECT_TRUE(t.apexes.empty());
  EXPECT_EQ(t.source, (std::array<int, 2>{0, 0}));
  EXPECT_EQ(t.target, (std::array<int, 2>{10, 10}));
  EXPECT_NEAR(t.cost, 20 * 4.0, 1e-9);
  EXPECT_EQ(t.lambda_growths, 0);
  EXPECT_DOUBLE_EQ(t.lambda, 6.0);
  expect_valid_strip(t, a, b);
}

TEST(TessellateStrip, ShorterRightWaleGivesRightEndPairsOnB) {
  // Concentric arcs: A (left, radius 24) longer than B (right, radius 20).
  const double sw = 4.0, sh = 1.0, theta = 1.2;
  const auto a = arc(30.0, -1.0, 24.0, theta, sh), b = arc(30.0, -1.0, 20.0, theta, sh);
  const int na = static_cast<int>(a.size()) / 2, nb = static_cast<int>(b.size()) / 2;
  ASSERT_EQ(na, 29);
  ASSERT_EQ(nb, 24);
  const StripTessellation t = tessellate_strip(a, b, opts(sw, sh));
  EXPECT_EQ(t.source, (std::array<int, 2>{0, 0}));
  EXPECT_EQ(t.target, (std::array<int, 2>{na, nb}));
  EXPECT_EQ(count_ops(t, StripOperator::AAdvance), na - nb);
  EXPECT_EQ(count_ops(t, StripOperator::BAdvance) + count_ops(t, StripOperator::BBAdvance), 0);
  ASSERT_EQ(static_cast<int>(t.apexes.size()), na - nb);
  // Length difference in stitch pairs: (24 - 20) * 2.4 / (2 sh) = 4.8.
  EXPECT_NEAR(static_cast<double>(t.apexes.size()), 4.0 * 2.0 * theta / (2.0 * sh), 1.0);
  for (const StripApex& p : t.apexes) {
    EXPECT_GE(p.vertex, static_cast<int>(a.size()));  // on B
    EXPECT_EQ((p.vertex - static_cast<int>(a.size())) % 2, 0);
  }
  int right = 0;
  for (const StripFace& f : t.faces) {
    EXPECT_NE(f.type, StitchType::ShortRowLeft);
    right += f.type == StitchType::ShortRowRight;
  }
  EXPECT_EQ(right, 2 * (na - nb));
  expect_valid_strip(t, a, b);
}

TEST(TessellateStrip, ShorterLeftWaleGivesLeftEndPairsOnA) {
  const double sw = 4.0, sh = 1.0, theta = 1.2;
  const auto a = arc(-30.0, 1.0, 20.0, theta, sh), b = arc(-30.0, 1.0, 24.0, theta, sh);
  const int na = static_cast<int>(a.size()) / 2, nb = static_cast<int>(b.size()) / 2;
  ASSERT_EQ(nb - na, 5);
  const StripTessellation t = tessellate_strip(a, b, opts(sw, sh));
  EXPECT_EQ(count_ops(t, StripOperator::AAdvance), 0);
  EXPECT_EQ(count_ops(t, StripOperator::BAdvance) + 2 * count_ops(t, StripOperator::BBAdvance),
            nb - na);
  ASSERT_EQ(static_cast<int>(t.apexes.size()), nb - na);
  for (const StripApex& p : t.apexes) {
    EXPECT_LT(p.vertex, static_cast<int>(a.size()));  // on A, odd sample
    EXPECT_EQ(p.vertex % 2, 1);
    EXPECT_FALSE(p.on_wale_end);
  }
  // Left-end pairs sit on (odd, even) courses.
  for (size_t f = 0; f + 1 < t.faces.size(); ++f)
    if (t.faces[f].type == StitchType::ShortRowLeft && (f == 0 || t.faces[f - 1].type == StitchType::Knit)) {
      EXPECT_EQ(t.faces[f].course % 2, 1);
    }
  expect_valid_strip(t, a, b);
}

TEST(TessellateStrip, AAdvancePatternExact) {
  // A: 4 segments, B: 2 segments; only A-advance + AB-advance fit, A first is shorter.
  const auto a = ys(0.0, {0, 1, 2, 3, 4}), b = ys(4.0, {0, 2.5, 4});
  const StripTessellation t = tessellate_strip(a, b, opts(4.0, 1.0));
  ASSERT_EQ(t.steps.size(), 2u);
  EXPECT_EQ(t.steps[0].op, StripOperator::AAdvance);
  EXPECT_EQ(t.steps[1].op, StripOperator::ABAdvance);
  // b_l -> 5 + l.
  expect_faces(t.faces, {face(StitchType::ShortRowRight, {0, 5, 1, -1}, 0),
                         face(StitchType::ShortRowRight, {1, 5, 2, -1}, 1),
                         face(StitchType::Knit, {2, 5, 6, 3}, 2),
                         face(StitchType::Knit, {3, 6, 7, 4}, 3)});
  ASSERT_EQ(t.apexes.size(), 1u);
  EXPECT_EQ(t.apexes[0].vertex, 5);
  EXPECT_TRUE(t.apexes[0].on_wale_end);
  expect_valid_strip(t, a, b);
}

TEST(TessellateStrip, BAdvancePatternExact) {
  const auto a = ys(0.0, {0, 2, 4}), b = ys(4.0, {0, 1, 2, 3, 4});
  const StripTessellation t = tessellate_strip(a, b, opts(4.0, 1.0));
  ASSERT_EQ(t.steps.size(), 1u);
  EXPECT_EQ(t.steps[0].op, StripOperator::BAdvance);
  // b_l -> 3 + l.
  expect_faces(t.faces, {face(StitchType::Knit, {0, 3, 4, 1}, 0),
                         face(StitchType::ShortRowLeft, {1, 4, 5, -1}, 1),
                         face(StitchType::ShortRowLeft, {1, 5, 6, -1}, 2),
                         face(StitchType::Knit, {1, 6, 7, 2}, 3)});
  ASSERT_EQ(t.apexes.size(), 1u);
  EXPECT_EQ(t.apexes[0].vertex, 1);
  EXPECT_FALSE(t.apexes[0].on_wale_end);
  // Bridges a1b1, a1b2, a1b3, a2b4; no earlier apex, so no diffusion cost.
  EXPECT_NEAR(t.cost, 2 * std::sqrt(17.0) + 4.0 + 4.0, 1e-9);
  expect_valid_strip(t, a, b);
}

TEST(TessellateStrip, BBAdvancePatternExact) {
  const auto a = ys(0.0, {0, 3, 6}), b = ys(4.0, {0, 1, 2, 3, 4, 5, 6});
  StripOptions o = opts(4.0, 1.0);
  const StripTessellation t = tessellate_strip(a, b, o);
  ASSERT_EQ(t.steps.size(), 1u);
  EXPECT_EQ(t.steps[0].op, StripOperator::BBAdvance);
  // b_l -> 3 + l.
  expect_faces(t.faces, {face(StitchType::Knit, {0, 3, 4, 1}, 0),
                         face(StitchType::ShortRowLeft, {1, 4, 5, -1}, 1),
                         face(StitchType::ShortRowLeft, {1, 5, 6, -1}, 2),
                         face(StitchType::ShortRowLeft, {1, 6, 7, -1}, 3),
                         face(StitchType::ShortRowLeft, {1, 7, 8, -1}, 4),
                         face(StitchType::Knit, {1, 8, 9, 2}, 5)});
  ASSERT_EQ(t.apexes.size(), 2u);
  EXPECT_EQ(t.apexes[0].vertex, 1);
  EXPECT_EQ(t.apexes[1].vertex, 1);
  // Bridges a1b1..a1b5 and a2b6, plus mu exp(0) for the second pair at the same apex.
  const double len = 2 * std::sqrt(20.0) + 2 * std::sqrt(17.0) + 4.0 + 4.0;
  EXPECT_NEAR(t.cost, len + 100.0 * 4.0, 1e-9);
  o.mu = 0.0;
  EXPECT_NEAR(tessellate_strip(a, b, o).cost, len, 1e-9);
  expect_valid_strip(t, a, b);
}

TEST(TessellateStrip, BoundaryFanCoversPartOfBBelowA) {
  // B starts 2 mm below A: the bottom part is a B-fan at a_0, then AB-advance.
  const auto a = ys(0.0, {2, 3, 4}), b = ys(4.0, {0, 1, 2, 3, 4});
  const StripTessellation t = tessellate_strip(a, b, opts(4.0, 1.0));
  EXPECT_EQ(t.source, (std::array<int, 2>{0, 1}));
  EXPECT_EQ(t.target, (std::array<int, 2>{1, 2}));
  ASSERT_EQ(t.steps.size(), 2u);
  EXPECT_EQ(t.steps[0].op, StripOperator::BFan);
  EXPECT_EQ(t.steps[1].op, StripOperator::ABAdvance);
  expect_faces(t.faces, {face(StitchType::ShortRowLeft, {0, 3, 4, -1}, 0),
                         face(StitchType::ShortRowLeft, {0, 4, 5, -1}, 1),
                         face(StitchType::Knit, {0, 5, 6, 1}, 2),
                         face(StitchType::Knit, {1, 6, 7, 2}, 3)});
  ASSERT_EQ(t.apexes.size(), 1u);
  EXPECT_TRUE(t.apexes[0].on_wale_end);
  expect_valid_strip(t, a, b);
}

TEST(TessellateStrip, LongerEndsAreCoveredOnBothSides) {
  // A extends 6 mm below and B 6 mm above: caps are tessellated, nothing dropped.
  const auto a = line(0.0, 0.0, 20.0, 20), b = line(4.0, 6.0, 26.0, 20);
  const StripTessellation t = tessellate_strip(a, b, opts(4.0, 1.0));
  EXPECT_EQ(t.source, (std::array<int, 2>{3, 0}));
  EXPECT_EQ(t.target, (std::array<int, 2>{10, 7}));
  expect_valid_strip(t, a, b);
  for (const StripApex& p : t.apexes) EXPECT_TRUE(p.on_wale_end);
}

TEST(TessellateStrip, ApexDiffusionSpreadsApexes) {
  const double sw = 4.0, sh = 1.0, theta = 1.2;
  const auto a = arc(14.0, -1.0, 12.0, theta, sh), b = arc(14.0, -1.0, 8.0, theta, sh);
  StripOptions o = opts(sw, sh);
  o.mu = 0.0;
  const StripTessellation off = tessellate_strip(a, b, o);
  o.mu = 100.0 * sw;
  const StripTessellation on = tessellate_strip(a, b, o);
  ASSERT_EQ(off.apexes.size(), on.apexes.size());
  ASSERT_GE(on.apexes.size(), 3u);
  const double d_off = min_interior_apex_distance(off), d_on = min_interior_apex_distance(on);
  EXPECT_GT(d_on, d_off + 0.5 * sh) << d_off << " " << d_on;
  expect_valid_strip(on, a, b);
  // Apexes of earlier strips push this strip's apexes away too: put them where
  // the mu = 0 solution has its interior apexes.
  std::vector<Vec3> earlier;
  for (const StripApex& q : off.apexes)
    if (!q.on_wale_end) earlier.push_back(q.position);
  ASSERT_GE(earlier.size(), 3u);
  auto nearest_to_earlier = [&](const StripTessellation& t) {
    double nearest = std::numeric_limits<double>::infinity();
    for (const StripApex& q : t.apexes)
      if (!q.on_wale_end)
        for (const Vec3& r : earlier) nearest = std::min(nearest, (q.position - r).norm());
    return nearest;
  };
  StripOptions p = opts(sw, sh);
  p.previous_apexes = earlier;
  p.mu = 0.0;
  EXPECT_EQ(nearest_to_earlier(tessellate_strip(a, b, p)), 0.0);  // no diffusion: same places
  p.mu = 100.0 * sw;
  const StripTessellation next = tessellate_strip(a, b, p);
  EXPECT_GT(nearest_to_earlier(next), 1.5 * sw);
  expect_valid_strip(next, a, b);
}

TEST(TessellateStrip, LambdaGrowsUntilAPathExists) {
  // Wales 7 mm apart, initial lambda = 4 + 2 = 6 mm: two 10 % growths reach 7.26 mm.
  const auto a = line(0.0, 0.0, 10.0, 10), b = line(7.0, 0.0, 10.0, 10);
  StripOptions o = opts(4.0, 1.0);
  o.strip_index = 7;
  const StripTessellation t = tessellate_strip(a, b, o);
  EXPECT_EQ(t.lambda_growths, 2);
  EXPECT_NEAR(t.lambda, 6.0 * 1.1 * 1.1, 1e-12);
  EXPECT_EQ(count_ops(t, StripOperator::ABAdvance), 5);
  o.max_lambda_growths = 1;
  try {
    tessellate_strip(a, b, o);
    FAIL() << "expected SolverError";
  } catch (const SolverError& e) {
    EXPECT_NE(std::string(e.what()).find("strip 7"), std::string::npos) << e.what();
  }
}

TEST(TessellateStrip, Deterministic) {
  const auto a = arc(14.0, -1.0, 12.0, 1.2, 1.0), b = arc(14.0, -1.0, 8.0, 1.2, 1.0);
  const StripTessellation t1 = tessellate_strip(a, b, opts(4.0, 1.0));
  const StripTessellation t2 = tessellate_strip(a, b, opts(4.0, 1.0));
  ASSERT_EQ(t1.faces.size(), t2.faces.size());
  for (size_t f = 0; f < t1.faces.size(); ++f) EXPECT_EQ(t1.faces[f].corners, t2.faces[f].corners);
  EXPECT_EQ(t1.cost, t2.cost);
}

TEST(TessellateStrip, BadInputThrows) {
  const auto a = line(0.0, 0.0, 4.0, 4), b = line(4.0, 0.0, 4.0, 4);
  EXPECT_THROW(tessellate_strip(line(0.0, 0.0, 3.0, 3), b, opts(4.0, 1.0)), InvalidInput);
  EXPECT_THROW(tessellate_strip(a, {Vec3(4, 0, 0)}, opts(4.0, 1.0)), InvalidInput);
  EXPECT_THROW(tessellate_strip(a, b, opts(0.0, 1.0)), InvalidInput);
  StripOptions o = opts(4.0, 1.0);
  o.mu = -1.0;
  EXPECT_THROW(tessellate_strip(a, b, o), InvalidInput);
  auto bad = a;
  bad[2].y() = std::nan("");
  EXPECT_THROW(tessellate_strip(bad, b, opts(4.0, 1.0)), InvalidInput);
}

}  // namespace
}  // namespace knitforge
