// The short-column ends of the strip tessellation (seed §3.3.4): a strip
// whose two wales meet at a fork starts with an Increase, one whose wales
// rejoin ends with a Decrease, and the faces cover the strip exactly.
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "knitforge/core/stitch.h"
#include "knitforge/design/shortrow/tessellate_strip.h"
#include "knitforge/util/errors.h"

namespace knitforge {
namespace {

constexpr double kSw = 3.5, kSh = 2.8;

std::vector<Vec3> straight(int segments) {
  std::vector<Vec3> p;
  for (int k = 0; k <= segments; ++k) p.emplace_back(0.0, k * kSh, 0.0);
  return p;
}

/// A wale right of x = 0 that leaves the origin (fork), runs at x = sw and,
/// when `rejoin`, comes back to x = 0 at its top.
std::vector<Vec3> branch(int segments, bool rejoin) {
  std::vector<Vec3> p;
  for (int k = 0; k <= segments; ++k) {
    double x = kSw * std::min(1.0, k / 2.0);
    if (rejoin) x = std::min(x, kSw * (segments - k) / 2.0);
    p.emplace_back(x, k * kSh, 0.0);
  }
  return p;
}

StripOptions fork_options(bool start, bool end) {
  StripOptions o;
  o.stitch_width = kSw;
  o.stitch_height = kSh;
  o.start_increase = start;
  o.end_decrease = end;
  o.allow_double_advance = false;
  return o;
}

Vec3 corner(const std::vector<Vec3>& a, const std::vector<Vec3>& b, int id) {
  return id < static_cast<int>(a.size()) ? a[static_cast<size_t>(id)] : b[static_cast<size_t>(id) - a.size()];
}

/// Signed area (z up) of a face.
double face_area(const std::vector<Vec3>& a, const std::vector<Vec3>& b, const StripFace& f) {
  const int n = f.corners[3] < 0 ? 3 : 4;
  double s = 0.0;
  for (int k = 0; k < n; ++k) {
    const Vec3 p = corner(a, b, f.corners[static_cast<size_t>(k)]), q = corner(a, b, f.corners[static_cast<size_t>((k + 1) % n)]);
    s += p.x() * q.y() - q.x() * p.y();
  }
  return 0.5 * s;
}

/// Area between the left wale a and the right wale b (the polygon b up, a down).
double strip_area(const std::vector<Vec3>& a, const std::vector<Vec3>& b) {
  std::vector<Vec3> poly(b.begin(), b.end());
  poly.insert(poly.end(), a.rbegin(), a.rend());
  double s = 0.0;
  for (size_t k = 0; k < poly.size(); ++k) {
    const Vec3& p = poly[k];
    const Vec3& q = poly[(k + 1) % poly.size()];
    s += p.x() * q.y() - q.x() * p.y();
  }
  return 0.5 * s;
}

int count(const StripTessellation& t, StitchType type) {
  int n = 0;
  for (const StripFace& f : t.faces) n += f.type == type;
  return n;
}

TEST(ForkTessellation, AStripFromAForkStartsWithAnIncreaseAtTheFork) {
  const std::vector<Vec3> a = straight(8), b = branch(8, false);
  const StripTessellation t = tessellate_strip(a, b, fork_options(true, false));
  ASSERT_FALSE(t.faces.empty());
  EXPECT_EQ(count(t, StitchType::Increase), 1);
  EXPECT_EQ(count(t, StitchType::Decrease), 0);
  const StripFace& first = t.faces.front();
  EXPECT_EQ(first.type, StitchType::Increase);
  EXPECT_EQ(first.corners[0], 0) << "the Increase's apex is the fork a_0";
  EXPECT_EQ(first.corners[3], -1);
  EXPECT_EQ(first.direction, 1) << "the first course runs left to right";
  // b_0 (= a_0) is never used: the fork is one vertex.
  for (const StripFace& f : t.faces)
    for (int c : f.corners) EXPECT_NE(c, static_cast<int>(a.size())) << "b_0 used";
  // Every face keeps its orientation, and together they cover the strip.
  double sum = 0.0;
  for (const StripFace& f : t.faces) {
    const double ar = face_area(a, b, f);
    EXPECT_GT(ar, 0.0);
    sum += ar;
  }
  EXPECT_NEAR(sum, strip_area(a, b), 1e-9);
}

TEST(ForkTessellation, AShortColumnStartsWithAnIncreaseAndEndsWithADecrease) {
  const std::vector<Vec3> a = straight(8), b = branch(8, true);
  const StripTessellation t = tessellate_strip(a, b, fork_options(true, true));
  EXPECT_EQ(count(t, StitchType::Increase), 1);
  EXPECT_EQ(count(t, StitchType::Decrease), 1);
  EXPECT_EQ(t.faces.front().type, StitchType::Increase);
  EXPECT_EQ(t.faces.back().type, StitchType::Decrease);
  EXPECT_EQ(t.faces.back().corners[2], static_cast<int>(a.size()) - 1) << "the Decrease's apex is the join a_2na";
  double sum = 0.0;
  for (const StripFace& f : t.faces) sum += face_area(a, b, f);
  EXPECT_NEAR(sum, strip_area(a, b), 1e-9);
  // Courses: the parities of a strip's faces alternate bottom to top.
  for (const StripFace& f : t.faces) EXPECT_EQ(f.direction, f.course % 2 == 0 ? 1 : -1);
}

TEST(ForkTessellation, TheSmallestShortColumnIsAnIncreaseOnADecrease) {
  const std::vector<Vec3> a = straight(2);
  const std::vector<Vec3> b{Vec3(0, 0, 0), Vec3(kSw, kSh, 0), Vec3(0, 2 * kSh, 0)};
  const StripTessellation t = tessellate_strip(a, b, fork_options(true, true));
  ASSERT_EQ(t.faces.size(), 2u);
  EXPECT_EQ(t.faces[0].type, StitchType::Increase);
  EXPECT_EQ(t.faces[1].type, StitchType::Decrease);
  ASSERT_EQ(t.steps.size(), 1u);
  EXPECT_EQ(t.steps[0].op, StripOperator::IncreaseDecrease);
}

TEST(ForkTessellation, WithoutDoubleAdvancesNoApexHoldsFourShortRowEnds) {
  // B twice as long as A: B-advances only, two short-row ends per apex.
  const std::vector<Vec3> a = straight(4);
  std::vector<Vec3> b;
  for (int k = 0; k <= 8; ++k) b.emplace_back(kSw * std::min(1.0, k / 2.0), k * kSh / 2.0, 0.0);
  const StripTessellation t = tessellate_strip(a, b, fork_options(true, false));
  std::vector<int> per_apex(a.size() + b.size(), 0);
  for (const StripFace& f : t.faces)
    if (f.type == StitchType::ShortRowLeft || f.type == StitchType::ShortRowRight)
      ++per_apex[static_cast<size_t>(f.corners[static_cast<size_t>(apex_corner(f.type))])];
  for (int n : per_apex) EXPECT_LE(n, 2);
  for (const StripStep& s : t.steps) {
    EXPECT_NE(s.op, StripOperator::BBAdvance);
    EXPECT_NE(s.op, StripOperator::IncreaseBB);
  }
  double sum = 0.0;
  for (const StripFace& f : t.faces) sum += face_area(a, b, f);
  EXPECT_NEAR(sum, strip_area(a, b), 1e-9);
}

TEST(ForkTessellation, WithoutDoubleAdvancesNoTwoAAdvancesShareAnInnerApex) {
  // A three times as long as B and no apex diffusion: the shortest path
  // needs A-advances; two in a row at one inner apex of B would stack four
  // right ends there, so each inner apex takes at most one pair.
  for (const bool fork : {false, true}) {
    SCOPED_TRACE(fork);
    std::vector<Vec3> a, b;
    for (int k = 0; k <= 12; ++k) a.emplace_back(0.0, k * kSh, 0.0);
    for (int l = 0; l <= 4; ++l) b.emplace_back(fork ? kSw * std::min(1.0, l / 2.0) : kSw, l * 3.0 * kSh, 0.0);
    StripOptions o = fork_options(fork, false);
    o.mu = 0.0;
    const StripTessellation t = tessellate_strip(a, b, o);
    const int inner_lo = static_cast<int>(a.size()) + 1, inner_hi = static_cast<int>(a.size() + b.size()) - 2;
    std::vector<int> per_apex(a.size() + b.size(), 0);
    for (const StripFace& f : t.faces)
      if (f.type == StitchType::ShortRowRight)
        ++per_apex[static_cast<size_t>(f.corners[static_cast<size_t>(apex_corner(f.type))])];
    for (int v = inner_lo; v <= inner_hi; ++v) EXPECT_LE(per_apex[static_cast<size_t>(v)], 2) << "b_" << v - a.size();
    int a_advances = 0;
    for (const StripStep& s : t.steps) a_advances += s.op == StripOperator::AAdvance;
    EXPECT_GE(a_advances, 2);
    double sum = 0.0;
    for (const StripFace& f : t.faces) sum += face_area(a, b, f);
    EXPECT_NEAR(sum, strip_area(a, b), 1e-9);
  }
}

TEST(ForkTessellation, AForkWhoseWalesDoNotMeetIsRejected) {
  std::vector<Vec3> a = straight(8), b = branch(8, false);
  b[0] = Vec3(0.5, 0.0, 0.0);
  try {
    tessellate_strip(a, b, fork_options(true, false));
    FAIL() << "no error";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("starts at a fork"), std::string::npos) << e.what();
  }
  a = straight(8), b = branch(8, false);
  EXPECT_THROW(tessellate_strip(a, b, fork_options(false, true)), InvalidInput) << "the ends differ: no join";
}

}  // namespace
}  // namespace knitforge
