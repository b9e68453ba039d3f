#include "knitforge/geometry/resample_polyline.h"

#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "knitforge/util/errors.h"

namespace knitforge {
namespace {

std::vector<Vec3> straight(double length, int pieces) {
  std::vector<Vec3> p;
  for (int i = 0; i <= pieces; ++i) p.emplace_back(length * i / pieces, 0.0, 0.0);
  return p;
}

std::vector<Vec3> arc(double radius, double angle, int pieces) {
  std::vector<Vec3> p;
  for (int i = 0; i <= pieces; ++i) {
    const double a = angle * i / pieces;
    p.emplace_back(radius * std::cos(a), radius * std::sin(a), 0.0);
  }
  return p;
}

double polyline_length(const std::vector<Vec3>& p) {
  double len = 0.0;
  for (size_t i = 1; i < p.size(); ++i) len += (p[i] - p[i - 1]).norm();
  return len;
}

TEST(ResamplePolyline, EvenCountWithoutExtension) {
  const auto r = resample_polyline(straight(10.0, 7), 1.0);
  EXPECT_EQ(r.num_segments, 10);
  EXPECT_EQ(r.extension, 0.0);
  ASSERT_EQ(r.points.size(), 11u);
  for (int k = 0; k <= 10; ++k) {
    EXPECT_NEAR(r.points[k].x(), k, 1e-12);
    EXPECT_NEAR(r.arc_length[k], k, 1e-12);
    EXPECT_GE(r.segment[k], 0);
  }
  // Near-even counts use equal segments of L / n.
  const auto s = resample_polyline(straight(10.4, 3), 1.0);
  EXPECT_EQ(s.num_segments, 10);
  EXPECT_NEAR(s.segment_length, 1.04, 1e-12);
  EXPECT_DOUBLE_EQ(s.points.back().x(), 10.4);
}

TEST(ResamplePolyline, OddCountExtendsBothEndsSymmetrically) {
  const auto r = resample_polyline(straight(9.0, 4), 1.0);
  EXPECT_EQ(r.num_segments, 10);
  EXPECT_NEAR(r.extension, 0.5, 1e-12);
  EXPECT_DOUBLE_EQ(r.segment_length, 1.0);
  ASSERT_EQ(r.points.size(), 11u);
  EXPECT_NEAR(r.points.front().x(), -0.5, 1e-12);
  EXPECT_NEAR(r.points.back().x(), 9.5, 1e-12);
  EXPECT_EQ(r.segment.front(), -1);
  EXPECT_EQ(r.segment.back(), -2);
  for (int k = 1; k <= 10; ++k) EXPECT_NEAR((r.points[k] - r.points[k - 1]).norm(), 1.0, 1e-12);
  for (const Vec3& p : r.points) EXPECT_NEAR(p.y(), 0.0, 1e-15);
}

TEST(ResamplePolyline, CurvedPolylineKeepsArcLengthSpacing) {
  const double R = 10.0;
  const auto poly = arc(R, 0.73, 200);  // length ~7.3
  const double L = polyline_length(poly);
  const auto r = resample_polyline(poly, 1.0);
  EXPECT_EQ(r.num_segments, 8);
  EXPECT_NEAR(r.extension, (8.0 - L) / 2.0, 1e-12);
  for (int k = 1; k <= 8; ++k) {
    EXPECT_NEAR(r.arc_length[k] - r.arc_length[k - 1], 1.0, 1e-12);
    const double chord = (r.points[k] - r.points[k - 1]).norm();
    EXPECT_LE(chord, 1.0 + 1e-12);
    EXPECT_GE(chord, 0.995);  // chord of a unit arc of radius 10
  }
  // Interior samples lie on the arc; the extensions continue tangentially.
  for (int k = 1; k < 8; ++k) {
    if (r.segment[k] >= 0) {
      EXPECT_NEAR(r.points[k].norm(), R, 1e-3);
    }
  }
  const Vec3 t0 = (r.points[0] - poly[0]).normalized();
  EXPECT_NEAR(t0.dot(Vec3(0, -1, 0)), 1.0, 1e-2);  // the start tangent of the arc at angle 0 is +y
}

TEST(ResamplePolyline, CountIsAlwaysEvenAndSegmentsNeverDegenerate) {
  for (double L = 0.05; L < 25.0; L += 0.37) {
    for (bool extend : {true, false}) {
      ResampleOptions o;
      o.extend_ends = extend;
      const auto r = resample_polyline(straight(L, 5), 1.0, o);
      EXPECT_EQ(r.num_segments % 2, 0) << L;
      EXPECT_GE(r.num_segments, 2);
      ASSERT_EQ(static_cast<int>(r.points.size()), r.num_segments + 1);
      for (int k = 1; k <= r.num_segments; ++k) {
        const double d = (r.points[k] - r.points[k - 1]).norm();
        EXPECT_NEAR(d, r.segment_length, 1e-9);
      }
      if (extend) {
        // Exact target length when extended, otherwise within 1/(2n).
        if (r.extension > 0.0) {
          EXPECT_DOUBLE_EQ(r.segment_length, 1.0);
        } else {
          EXPECT_LE(std::abs(r.segment_length - 1.0), 0.5 / r.num_segments + 1e-12);
        }
        EXPECT_LE(r.extension, 1.0);
        EXPECT_NEAR(r.points.front().x(), -r.extension, 1e-12);
        EXPECT_NEAR(r.points.back().x(), L + r.extension, 1e-9);
      } else {
        EXPECT_EQ(r.extension, 0.0);
        EXPECT_NEAR(r.points.back().x(), L, 1e-9);
        EXPECT_LE(std::abs(r.num_segments - L), 1.0 + 1e-9 + (L < 1.0 ? 1.0 : 0.0));
      }
    }
  }
}

TEST(ResamplePolyline, TinyAndRepeatedPoints) {
  // Much shorter than the target: two segments, extended symmetrically.
  const auto r = resample_polyline({Vec3(0, 0, 0), Vec3(0, 0.1, 0)}, 1.0);
  EXPECT_EQ(r.num_segments, 2);
  EXPECT_NEAR(r.extension, 0.95, 1e-12);
  EXPECT_NEAR((r.points[0] - Vec3(0, -0.95, 0)).norm(), 0.0, 1e-12);
  EXPECT_NEAR((r.points[2] - Vec3(0, 1.05, 0)).norm(), 0.0, 1e-12);
  // Repeated points do not matter.
  const auto a = resample_polyline({Vec3(0, 0, 0), Vec3(0, 0, 0), Vec3(3, 0, 0), Vec3(3, 0, 0), Vec3(5, 0, 0),
                                    Vec3(5, 0, 0)},
                                   1.0);
  const auto b = resample_polyline({Vec3(0, 0, 0), Vec3(5, 0, 0)}, 1.0);
  ASSERT_EQ(a.points.size(), b.points.size());
  for (size_t i = 0; i < a.points.size(); ++i) EXPECT_NEAR((a.points[i] - b.points[i]).norm(), 0.0, 1e-12);
  EXPECT_EQ(a.num_segments, 6);
}

TEST(ResamplePolyline, RejectsBadInput) {
  EXPECT_THROW(resample_polyline({Vec3(0, 0, 0)}, 1.0), InvalidInput);
  EXPECT_THROW(resample_polyline({Vec3(0, 0, 0), Vec3(0, 0, 0)}, 1.0), InvalidInput);
  EXPECT_THROW(resample_polyline(straight(1.0, 1), 0.0), InvalidInput);
  EXPECT_THROW(resample_polyline(straight(1.0, 1), NAN), InvalidInput);
  EXPECT_THROW(resample_polyline({Vec3(0, 0, 0), Vec3(NAN, 0, 0)}, 1.0), InvalidInput);
  EXPECT_THROW(resample_polyline(straight(1e9, 1), 1e-3), InvalidInput);
}

}  // namespace
}  // namespace knitforge
