// Wale extraction of the short-column route (Alg. 3.1-3.3, column_wales.h).
#include "knitforge/design/shortcolumn/column_wales.h"

#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "design/shortcolumn/test_meshes.h"
#include "knitforge/design/shortcolumn/harmonic_field.h"
#include "knitforge/geometry/shapes.h"
#include "knitforge/util/errors.h"

namespace knitforge {
namespace {

const KnitParams kParams{3.5, 2.8};

double distance_to_polyline(const std::vector<Vec3>& pl, const Vec3& p) {
  double best = 1e300;
  for (size_t k = 0; k + 1 < pl.size(); ++k) {
    const Vec3 ab = pl[k + 1] - pl[k];
    const double t = std::clamp((p - pl[k]).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
    best = std::min(best, (pl[k] + t * ab - p).norm());
  }
  return best;
}

/// Properties every extraction must have: strips start on even samples, the
/// parities alternate along both wales, forks are shared samples.
void expect_consistent_strips(const ColumnWales& w) {
  ASSERT_EQ(w.samples.size(), w.parity.size());
  for (const ColumnStrip& s : w.strips) {
    ASSERT_GE(s.a.size(), 3u);
    ASSERT_GE(s.b.size(), 3u);
    EXPECT_EQ(s.a.size() % 2, 1u) << "an even number of segments";
    EXPECT_EQ(s.b.size() % 2, 1u);
    for (size_t k = 0; k < s.a.size(); ++k) EXPECT_EQ(w.parity[static_cast<size_t>(s.a[k])], static_cast<int>(k % 2));
    for (size_t k = 0; k < s.b.size(); ++k) EXPECT_EQ(w.parity[static_cast<size_t>(s.b[k])], static_cast<int>(k % 2));
    EXPECT_EQ(s.start_increase, s.a.front() == s.b.front());
    EXPECT_EQ(s.end_decrease, s.a.back() == s.b.back());
  }
}

TEST(ColumnWales, ParallelIsocurvesGiveWholeWalesOnly) {
  // f = x on a rectangle: the fronts advance straight, no wale lags.
  const TriMesh m = rectangle(60.0, 40.0, 2.0);
  std::vector<double> f;
  for (const Vec3& p : m.vertices) f.push_back(p.x());
  const ColumnWales w = extract_column_wales(m, f, kParams);
  expect_consistent_strips(w);
  EXPECT_EQ(w.fill_steps, 0);
  EXPECT_EQ(w.region_splits, 0);
  // 60 mm / 3.5 mm = 17.1 advances of the whole front (the last narrower
  // region closed by a last strip).
  EXPECT_GE(w.whole_steps, 16);
  EXPECT_LE(w.whole_steps, 18);
  for (const ColumnStrip& s : w.strips) {
    if (s.start_increase) continue;  // the last strip, along the boundary
    std::vector<Vec3> a;
    for (int id : s.a) a.push_back(w.samples[static_cast<size_t>(id)]);
    for (int id : s.b) {
      const Vec3& p = w.samples[static_cast<size_t>(id)];
      EXPECT_NEAR(distance_to_polyline(a, p), kParams.stitch_width, 0.05) << "wales one stitch width apart";
      EXPECT_NEAR(p.y(), std::clamp(p.y(), -20.0, 20.0), 1e-9);
    }
  }
  EXPECT_LT(w.uncovered_area, 1e-6);
}

TEST(ColumnWales, SpreadingIsocurvesGiveShortWalesThatForkFromTheFront) {
  // f = angle on a quarter annulus: the isocurves (rays) spread with r, the
  // fronts (parallel offsets) lag at large r: short wales fill the lag.
  const TriMesh m = test::polar_grid(20.0, 80.0, 0.0, std::numbers::pi / 2, 40, 60);
  std::vector<double> f;
  for (const Vec3& p : m.vertices) f.push_back(std::atan2(p.y(), p.x()));
  const ColumnWales w = extract_column_wales(m, f, kParams);
  expect_consistent_strips(w);
  EXPECT_GT(w.fill_steps, 0);
  int forks = 0, short_strips = 0;
  for (const ColumnStrip& s : w.strips) {
    forks += s.start_increase;
    short_strips += s.short_wale;
  }
  EXPECT_GT(forks, 0);
  EXPECT_GT(short_strips, 0);
  for (const Vec3& p : w.samples) {
    const double r = std::hypot(p.x(), p.y());
    EXPECT_GT(r, 20.0 - 0.002) << "inside (the inner rim's chords dip 0.0017 mm below r = 20)";
    EXPECT_LT(r, 80.0 + 1e-6);
    EXPECT_NEAR(p.z(), 0.0, 1e-9);
  }
  // The outer arc is 4 x the inner one: the number of wales grows towards it.
  EXPECT_GT(static_cast<int>(w.wales.size()), w.whole_steps);
  // No sample is the apex of two increases.
  std::vector<int> increases(w.samples.size(), 0);
  for (const ColumnStrip& s : w.strips)
    if (s.start_increase && !s.end_decrease) {
      EXPECT_LE(++increases[static_cast<size_t>(s.a.front())], 1);
    }
}

TEST(JoinedWales, AFrontAlongTheRimGetsOneWaleAcrossTheStretchItRemoves) {
  // A 30 x 20 mm rectangle with a slot 2 mm wide cut in from its right side
  // (y 9..11, x 11..30), f = x: the fronts are the lines x = 3.5, 7, 10.5;
  // the next one, x = 14, meets the slot, whose tip (x = 11) lies closer
  // than sw to the front x = 10.5. The isocurve d = sw leaves the surface at
  // the slot's lower side and comes back at its upper side: joined along
  // the rim, the whole front gets one wale, across the slot's tip.
  const TriMesh m = test::grid_cells(30, 20, 1.0, [](int i, int j) { return !(i >= 11 && (j == 9 || j == 10)); });
  std::vector<double> f;
  for (const Vec3& p : m.vertices) f.push_back(p.x());
  const ColumnWales w = extract_column_wales(m, f, kParams);
  expect_consistent_strips(w);
  EXPECT_GE(w.joined_arcs, 1);
  auto at = [&](int id) { return w.samples[static_cast<size_t>(id)]; };
  // The strips whose old front faces the slot's tip (x = 10.5, y in 9..11).
  int facing = 0;
  for (const ColumnStrip& s : w.strips) {
    bool faces_tip = false;
    for (int id : s.a) faces_tip = faces_tip || (std::abs(at(id).x() - 10.5) < 0.2 && at(id).y() > 9.0 && at(id).y() < 11.0);
    if (!faces_tip) continue;
    ++facing;
    // The whole front, bottom to top, is the strip's old side.
    EXPECT_NEAR(at(s.a.front()).y(), 0.0, 1e-6);
    EXPECT_NEAR(at(s.a.back()).y(), 20.0, 1e-6);
    // Its new wale runs along the slot's tip, and at x = 14 above and below.
    bool across_tip = false;
    for (int id : s.b) {
      const Vec3 p = at(id);
      across_tip = across_tip || (p.x() < 11.0 + 1e-6 && p.y() > 9.0 && p.y() < 11.0);
      if (p.y() < 8.0 || p.y() > 12.0) {
        EXPECT_NEAR(p.x(), 14.0, 0.05) << p.transpose();
      }
    }
    EXPECT_TRUE(across_tip) << "the wale crosses the stretch of rim it removes";
  }
  EXPECT_EQ(facing, 1) << "one strip for the front along the rim";
  // Both sides of the slot continue from where the wale leaves and rejoins
  // the rim (the slot's sides at x = 14).
  bool below = false, above = false;
  for (const ColumnStrip& s : w.strips) {
    below = below || ((at(s.a.back()) - Vec3(14.0, 9.0, 0.0)).norm() < 1e-6 && at(s.a.front()).y() < 1e-6);
    above = above || ((at(s.a.front()) - Vec3(14.0, 11.0, 0.0)).norm() < 1e-6 && at(s.a.back()).y() > 20.0 - 1e-6);
  }
  EXPECT_TRUE(below);
  EXPECT_TRUE(above);
  // The strips cover the surface but for the slivers at its right end
  // (narrower than a stitch, left uncovered): no hole in front of the tip.
  double covered = 0.0;
  for (const ColumnStrip& s : w.strips) {
    std::vector<Vec3> ring;
    for (int id : s.a) ring.push_back(at(id));
    for (auto it = s.b.rbegin(); it != s.b.rend(); ++it) ring.push_back(at(*it));
    double twice = 0.0;
    for (size_t k = 0; k < ring.size(); ++k) {
      const Vec3& p = ring[k];
      const Vec3& q = ring[(k + 1) % ring.size()];
      twice += p.x() * q.y() - q.x() * p.y();
    }
    covered += std::abs(twice) / 2.0;
  }
  EXPECT_NEAR(covered + w.uncovered_area, w.surface_area, 0.01 * w.surface_area);
}

TEST(ColumnWales, AShortColumnsWaleHasMoreThanHalfTheSegmentsOfTheFrontItReplaces) {
  // A random b of the Fig. 3.16 experiment where a short column's old front
  // (between its fork and its join) was 8 segments and its new wale 4: the
  // strip had no tessellation without four stacked short-row ends.
  const TriMesh m = hemisphere();
  const HarmonicField h = harmonic_field(m, {0.463155, 0.527030, 1.129328, 1.163904});
  const ColumnWales w = extract_column_wales(m, h.value, kParams);
  expect_consistent_strips(w);
  int short_columns = 0;
  for (const ColumnStrip& s : w.strips) {
    if (!(s.start_increase && s.end_decrease)) continue;
    ++short_columns;
    const size_t na = s.a.size() - 1, nb = s.b.size() - 1;
    if (na == 2) continue;  // a single stitch pair: 2 opposite 2
    EXPECT_GT(2 * nb, na) << "short column: A " << na << " segments, B " << nb;
    EXPECT_LE(nb, 2 * na);
    EXPECT_GE(nb, 4u);
  }
  EXPECT_GT(short_columns, 10);
}

TEST(ColumnWales, ANewWaleHasAtMostTwiceTheSegmentsOfTheFrontItFaces) {
  // A random b (example_06 with N = 100) whose start interval is 8 mm: the
  // first wale around it is about 19 mm long, 8 segments against 2, and the
  // first strip had no tessellation (tessellate_strip() covers B up to
  // twice A).
  const TriMesh m = hemisphere();
  const HarmonicField h = harmonic_field(m, {0.439573, 0.456673, 0.920743, 1.255550});
  const ColumnWales w = extract_column_wales(m, h.value, kParams);
  expect_consistent_strips(w);
  ASSERT_FALSE(w.strips.empty());
  for (const ColumnStrip& s : w.strips) EXPECT_LE(s.b.size() - 1, 2 * (s.a.size() - 1)) << "strip of column " << s.column;
}

TEST(ColumnWales, RejectsFieldsItCannotStartFrom) {
  const TriMesh m = rectangle(30.0, 20.0, 2.0);
  std::vector<double> f(static_cast<size_t>(m.num_vertices()), 0.0);
  EXPECT_THROW(extract_column_wales(m, f, kParams), InvalidInput) << "constant";
  for (size_t v = 0; v < f.size(); ++v) f[v] = m.vertices[v].squaredNorm();  // minimum inside
  try {
    extract_column_wales(m, f, kParams);
    FAIL() << "no error";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("not on the boundary"), std::string::npos) << e.what();
  }
  f.pop_back();
  EXPECT_THROW(extract_column_wales(m, f, kParams), InvalidInput);
  f.assign(static_cast<size_t>(m.num_vertices()), 0.0);
  for (size_t v = 0; v < f.size(); ++v) f[v] = m.vertices[v].x();
  EXPECT_THROW(extract_column_wales(m, f, KnitParams{0.0, 2.8}), InvalidInput);
}

}  // namespace
}  // namespace knitforge
