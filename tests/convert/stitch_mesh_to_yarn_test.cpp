#include "knitforge/convert/stitch_mesh_to_yarn.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <ctime>
#include <random>
#include <set>
#include <utility>
#include <vector>

#include "knitforge/convert/map_to_stitch_mesh.h"
#include "knitforge/convert/random_knitting_map.h"
#include "knitforge/convert/sample_knitting_map.h"
#include "knitforge/core/stitch_adjacency.h"
#include "knitforge/util/errors.h"

using namespace knitforge;

namespace {

#if defined(__SANITIZE_ADDRESS__)
constexpr bool kSanitized = true;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
constexpr bool kSanitized = true;
#else
constexpr bool kSanitized = false;
#endif
#else
constexpr bool kSanitized = false;
#endif

const KnitParams kParams{};  // 3.5 x 2.8 mm

std::vector<int> knitting_order(const StitchMesh& mesh) {
  const StitchAdjacency adj(mesh);
  int first = -1;
  for (int s = 0; s < mesh.num_stitches() && first < 0; ++s) {
    if (adj.previous_stitch(s) < 0) first = s;
  }
  std::vector<int> order;
  for (int s = first; s >= 0; s = adj.next_stitch(s)) order.push_back(s);
  return order;
}

/// The structural properties every yarn model must have: one polyline per
/// yarn; each stitch of that yarn one contiguous run, in knitting order; the
/// last stitch also owns the exit point; no jumps; vertices near their stitch.
void expect_valid_yarn(const StitchMesh& mesh, const YarnModel& model, double max_step) {
  const std::vector<int> order = knitting_order(mesh);
  ASSERT_EQ(static_cast<int>(order.size()), mesh.num_stitches());
  std::set<int> ids;
  for (const Stitch& s : mesh.stitches) ids.insert(s.yarn);
  ASSERT_EQ(model.yarns.size(), ids.size());
  size_t total_runs = 0;
  for (const Yarn& y : model.yarns) {
    ASSERT_EQ(y.points.size(), y.stitch.size());
    ASSERT_GE(y.points.size(), 2u);
    std::vector<int> expected;
    for (int s : order) {
      if (mesh.stitches[s].yarn == y.id) expected.push_back(s);
    }
    std::vector<int> runs;
    for (size_t i = 0; i < y.stitch.size(); ++i) {
      if (i == 0 || y.stitch[i] != y.stitch[i - 1]) runs.push_back(y.stitch[i]);
    }
    EXPECT_EQ(runs, expected) << "yarn " << y.id;  // contiguous, once, in knitting order
    total_runs += runs.size();
    for (size_t i = 1; i < y.points.size(); ++i) {
      ASSERT_LT((y.points[i] - y.points[i - 1]).norm(), max_step) << "jump at vertex " << i << " of yarn " << y.id;
    }
    for (size_t i = 0; i < y.points.size(); ++i) {
      const int s = y.stitch[i];
      const Stitch& st = mesh.stitches[s];
      double diag = 0;
      for (int a = 0; a < st.corners(); ++a) {
        for (int b = 0; b < st.corners(); ++b) {
          diag = std::max(diag, (mesh.vertices[st.v[a]] - mesh.vertices[st.v[b]]).norm());
        }
      }
      ASSERT_LT((y.points[i] - stitch_centroid(mesh, s)).norm(), 1.2 * diag + 1.0)
          << "vertex " << i << " strays from stitch " << s;
      ASSERT_TRUE(y.points[i].allFinite());
    }
  }
  EXPECT_EQ(total_runs, mesh.stitches.size());
}

KnittingMap plain_map(int rows, int cols) { return KnittingMap(rows, cols, CellType::Knit); }

}  // namespace

TEST(StitchMeshToYarn, CanonicalCornersInterpolate) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> U(-5, 5);
  for (int t = 0; t < kNumStitchTypes; ++t) {
    const auto type = static_cast<StitchType>(t);
    StitchMesh m;
    Stitch s;
    s.type = type;
    for (int i = 0; i < corner_count(type); ++i) {
      m.vertices.emplace_back(U(rng), U(rng), U(rng));
      s.v[i] = i;
    }
    m.stitches.push_back(s);
    const auto corners = canonical_corners(type);
    ASSERT_EQ(static_cast<int>(corners.size()), corner_count(type));
    for (int i = 0; i < corner_count(type); ++i) {
      const Vec3 p = deform_canonical_point(m, 0, Vec3(corners[i].x(), corners[i].y(), 0), 0.4);
      EXPECT_LT((p - m.vertices[i]).norm(), 1e-12) << name(type) << " corner " << i;
    }
    // The apex of a shaping stitch is its apex corner.
    if (is_shaping(type)) {
      EXPECT_EQ(apex_vertex(m.stitches[0]), s.v[apex_corner(type)]);
    }
    // z moves along the unit facet normal, scaled by the radius.
    const Vec3 a = deform_canonical_point(m, 0, Vec3(0.5, 0.5, 0), 0.4);
    const Vec3 b = deform_canonical_point(m, 0, Vec3(0.5, 0.5, 2.0), 0.4);
    EXPECT_NEAR((b - a).norm(), 0.8, 1e-12);
    if (corner_count(type) == 3) {
      const Vec3 e1 = m.vertices[1] - m.vertices[0], e2 = m.vertices[2] - m.vertices[0];
      EXPECT_NEAR((b - a).dot(e1), 0, 1e-9);
      EXPECT_NEAR((b - a).dot(e2), 0, 1e-9);
      EXPECT_GT((b - a).dot(e1.cross(e2)), 0);  // towards the front (CCW side)
    }
  }
}

TEST(StitchMeshToYarn, PlainSheetOneContinuousYarn) {
  const StitchMesh mesh = map_to_stitch_mesh_topology(plain_map(6, 8), kParams);
  const YarnModel y = stitch_mesh_to_yarn(mesh, kParams);
  ASSERT_EQ(y.yarns.size(), 1u);
  EXPECT_EQ(y.yarns[0].id, 0);
  expect_valid_yarn(mesh, y, 1.5 * kParams.stitch_width);
  // Each stitch's run starts on the side the yarn enters from: the left for
  // stitches knitted left to right, the right for the others (mirrored loops).
  const Yarn& yarn = y.yarns[0];
  for (size_t i = 0; i < yarn.points.size(); ++i) {
    if (i > 0 && yarn.stitch[i] == yarn.stitch[i - 1]) continue;
    const Stitch& st = mesh.stitches[yarn.stitch[i]];
    const double left = mesh.vertices[st.v[0]].x(), right = mesh.vertices[st.v[1]].x();
    EXPECT_NEAR(yarn.points[i].x(), st.direction > 0 ? left : right, 1e-9);
  }
  // Flat mesh in z = 0: the legs are in front (z > 0), the head and the
  // sinker behind; the offsets scale with the yarn radius.
  YarnOptions opt;
  opt.yarn_radius = 0.5;
  const YarnModel a = stitch_mesh_to_yarn(mesh, kParams, opt);
  opt.yarn_radius = 1.0;
  const YarnModel b = stitch_mesh_to_yarn(mesh, kParams, opt);
  double zmax = 0;
  for (size_t i = 0; i < a.yarns[0].points.size(); ++i) {
    EXPECT_NEAR(2 * a.yarns[0].points[i].z(), b.yarns[0].points[i].z(), 1e-12);
    EXPECT_NEAR(a.yarns[0].points[i].head<2>()(0), b.yarns[0].points[i].head<2>()(0), 1e-12);
    zmax = std::max(zmax, std::abs(a.yarns[0].points[i].z()));
  }
  EXPECT_NEAR(zmax, 0.5, 1e-12);
  // The default radius is 0.12 stitch widths.
  double zdef = 0;
  for (const Vec3& p : y.yarns[0].points) zdef = std::max(zdef, std::abs(p.z()));
  EXPECT_NEAR(zdef, 0.12 * kParams.stitch_width, 1e-12);
}

TEST(StitchMeshToYarn, LoopsInterlockWithTheCourseAbove) {
  // In a flat sheet the head of a loop (above its top side) lies behind
  // (z < 0) and the legs of the loop above cross it in front (z > 0).
  const StitchMesh mesh = map_to_stitch_mesh_topology(plain_map(3, 3), kParams);
  const YarnModel y = stitch_mesh_to_yarn(mesh, kParams);
  const double h = kParams.stitch_height;
  int heads = 0, legs_in_front = 0;
  for (size_t i = 0; i < y.yarns[0].points.size(); ++i) {
    const Vec3& p = y.yarns[0].points[i];
    const Stitch& st = mesh.stitches[y.yarns[0].stitch[i]];
    const double top = (st.course + 1) * h;
    if (p.y() > top + 0.05 * h) {
      EXPECT_LT(p.z(), 0) << "head point above the top side must be behind";
      ++heads;
    }
    const bool inside = std::abs(p.x() - (st.wale + 0.5) * kParams.stitch_width) < 0.4 * kParams.stitch_width;
    if (inside && p.y() > st.course * h + 0.3 * h && p.y() < top - 0.3 * h) {
      EXPECT_GT(p.z(), 0) << "leg points must be in front";
      ++legs_in_front;
    }
  }
  EXPECT_GT(heads, 0);
  EXPECT_GT(legs_in_front, 0);
}

TEST(StitchMeshToYarn, ShortRowTurnPassesThroughTheApex) {
  KnittingMap map(4, 4, CellType::Knit);
  map.at(1, 0) = map.at(2, 0) = CellType::Collapsed;
  map.at(1, 1) = map.at(2, 1) = CellType::ShortRowLeft;
  const StitchMesh mesh = map_to_stitch_mesh_topology(map, kParams);
  const YarnModel y = stitch_mesh_to_yarn(mesh, kParams);
  ASSERT_EQ(y.yarns.size(), 1u);
  expect_valid_yarn(mesh, y, 1.5 * kParams.stitch_width);
  const Yarn& yarn = y.yarns[0];
  // The lower short-row end: its last vertex (entry of the upper one) is the
  // apex pushed back by one yarn radius.
  int lower = -1;
  for (int s = 0; s < mesh.num_stitches(); ++s) {
    if (mesh.stitches[s].type == StitchType::ShortRowLeft && mesh.stitches[s].course == 1) lower = s;
  }
  ASSERT_GE(lower, 0);
  const Vec3 apex = mesh.vertices[apex_vertex(mesh.stitches[lower])];
  size_t first_upper = 0;
  for (size_t i = 1; i < yarn.points.size(); ++i) {
    if (yarn.stitch[i - 1] == lower && yarn.stitch[i] != lower) first_upper = i;
  }
  ASSERT_GT(first_upper, 0u);
  const double r = 0.12 * kParams.stitch_width;
  EXPECT_LT((yarn.points[first_upper] - (apex - Vec3(0, 0, r))).norm(), 1e-9);
  EXPECT_LT((yarn.points[first_upper - 1] - apex).norm(), 0.5 * kParams.stitch_width);  // runs into the apex
}

TEST(StitchMeshToYarn, RandomShapedMapsGiveValidYarns) {
  for (uint64_t seed = 1; seed <= 20; ++seed) {
    RandomMapOptions o;
    o.seed = seed;
    o.rows = 16;
    o.cols = 16;
    o.short_row_ends = 2 * static_cast<int>(seed % 4);
    o.short_columns = static_cast<int>(seed % 3);
    o.boundary_shaping = seed % 2 == 0;
    const StitchMesh mesh = map_to_stitch_mesh_topology(random_knitting_map(o), kParams);
    const YarnModel y = stitch_mesh_to_yarn(mesh, kParams);
    expect_valid_yarn(mesh, y, 1.5 * kParams.stitch_width);
  }
}

TEST(StitchMeshToYarn, RelaxedMeshGivesValidYarn) {
  RandomMapOptions o;
  o.rows = 12;
  o.cols = 12;
  o.short_row_ends = 4;
  o.short_columns = 1;
  const StitchMesh mesh = map_to_stitch_mesh(random_knitting_map(o), kParams);
  const YarnModel y = stitch_mesh_to_yarn(mesh, kParams);
  expect_valid_yarn(mesh, y, 1.5 * kParams.stitch_width);
}

TEST(StitchMeshToYarn, TwoYarnsGiveTwoPolylines) {
  KnittingMap map = plain_map(6, 5);
  for (int r = 3; r < 6; ++r) {
    for (int c = 0; c < 5; ++c) map.set_yarn(r, c, 1);
  }
  const StitchMesh mesh = map_to_stitch_mesh_topology(map, kParams);
  const YarnModel y = stitch_mesh_to_yarn(mesh, kParams);
  ASSERT_EQ(y.yarns.size(), 2u);
  EXPECT_EQ(y.yarns[0].id, 0);
  EXPECT_EQ(y.yarns[1].id, 1);
  expect_valid_yarn(mesh, y, 1.5 * kParams.stitch_width);
  for (const Yarn& yarn : y.yarns) {
    for (int s : yarn.stitch) EXPECT_EQ(mesh.stitches[s].yarn, yarn.id);
  }
}

TEST(StitchMeshToYarn, BoundaryRolesChangeTheLoops) {
  // Bind-off loops close lower than regular heads; cast-on feet stay flat.
  const StitchMesh mesh = map_to_stitch_mesh_topology(plain_map(3, 4), kParams);
  const YarnModel y = stitch_mesh_to_yarn(mesh, kParams);
  std::vector<double> top_of(mesh.num_stitches(), -1e9), zmin_low(mesh.num_stitches(), 0);
  for (size_t i = 0; i < y.yarns[0].points.size(); ++i) {
    const int s = y.yarns[0].stitch[i];
    const Vec3& p = y.yarns[0].points[i];
    top_of[s] = std::max(top_of[s], p.y() - (mesh.stitches[s].course + 1) * kParams.stitch_height);
    if (p.y() - mesh.stitches[s].course * kParams.stitch_height < 0.2 * kParams.stitch_height &&
        std::abs(p.x() - (mesh.stitches[s].wale + 0.5) * kParams.stitch_width) < 0.3 * kParams.stitch_width) {
      zmin_low[s] = std::min(zmin_low[s], p.z());
    }
  }
  for (int s = 0; s < mesh.num_stitches(); ++s) {
    const Stitch& st = mesh.stitches[s];
    if (st.roles & kRoleBindOff) {
      EXPECT_LT(top_of[s], 0.15 * kParams.stitch_height);
    } else {
      EXPECT_GT(top_of[s], 0.25 * kParams.stitch_height);
    }
    if (st.roles & kRoleCastOn) {
      EXPECT_EQ(zmin_low[s], 0);  // feet in the fabric plane
    } else {
      EXPECT_LT(zmin_low[s], 0);  // feet behind the head below
    }
  }
}

TEST(StitchMeshToYarn, OutsideDecreaseHeadsLeanInwards) {
  RandomMapOptions o;
  o.rows = 20;
  o.cols = 16;
  o.boundary_shaping = true;
  int checked = 0;
  for (uint64_t seed = 1; seed <= 5; ++seed) {
    o.seed = seed;
    const StitchMesh mesh = map_to_stitch_mesh_topology(random_knitting_map(o), kParams);
    const YarnModel y = stitch_mesh_to_yarn(mesh, kParams);
    expect_valid_yarn(mesh, y, 1.5 * kParams.stitch_width);
    const StitchAdjacency adj(mesh);
    std::vector<Vec3> top(mesh.num_stitches(), Vec3::Constant(-1e9));
    for (size_t i = 0; i < y.yarns[0].points.size(); ++i) {
      Vec3& t = top[y.yarns[0].stitch[i]];
      if (y.yarns[0].points[i].y() > t.y()) t = y.yarns[0].points[i];
    }
    for (int s = 0; s < mesh.num_stitches(); ++s) {
      const Stitch& st = mesh.stitches[s];
      if (!(st.roles & kRoleOutsideDecrease) || st.type != StitchType::Knit || (st.roles & kRoleBindOff)) continue;
      const bool open_left = adj.neighbor(s, Side::Left) < 0;
      if (open_left == (adj.neighbor(s, Side::Right) < 0)) continue;
      const double centre = stitch_centroid(mesh, s).x();
      if (open_left) {
        EXPECT_GT(top[s].x(), centre + 0.1 * kParams.stitch_width) << "stitch " << s;
      } else {
        EXPECT_LT(top[s].x(), centre - 0.1 * kParams.stitch_width) << "stitch " << s;
      }
      ++checked;
    }
  }
  EXPECT_GT(checked, 0);
}

TEST(StitchMeshToYarn, BadInputThrows) {
  StitchMesh mesh = map_to_stitch_mesh_topology(plain_map(2, 3), kParams);
  YarnOptions opt;
  opt.yarn_radius = -1;
  EXPECT_THROW(stitch_mesh_to_yarn(mesh, kParams, opt), InvalidInput);
  EXPECT_THROW(stitch_mesh_to_yarn(mesh, KnitParams{0, 2.8}), InvalidInput);
  StitchMesh neg = mesh;
  neg.stitches[2].yarn = -1;
  EXPECT_THROW(stitch_mesh_to_yarn(neg, kParams), InvalidInput);
  // Both rows left to right: no one-stroke order.
  KnittingMap m = plain_map(2, 3);
  m.direction = {1, 1};
  EXPECT_THROW(stitch_mesh_to_yarn(map_to_stitch_mesh_topology(m, kParams), kParams), TopologyError);
  EXPECT_TRUE(stitch_mesh_to_yarn(StitchMesh{}, kParams).yarns.empty());
}

// Speed is measured in bench/bench_yarn.cpp, not here.
TEST(StitchMeshToYarn, LargeSheetIsOneYarnFromFirstToLastStitch) {
  const int side = kSanitized ? 100 : 300;
  const StitchMesh mesh = map_to_stitch_mesh_topology(plain_map(side, side), kParams);
  const YarnModel y = stitch_mesh_to_yarn(mesh, kParams);
  ASSERT_EQ(y.yarns.size(), 1u);
  EXPECT_EQ(y.yarns[0].stitch.front(), 0);
  EXPECT_EQ(y.yarns[0].stitch.back(), side * side - 1);
}

namespace knitforge {
namespace {

TEST(StitchMeshToYarnTube, FollowsATubesStitchesInKnittingOrder) {
  const KnitParams params;
  const StitchMesh mesh = map_to_stitch_mesh_topology(tube_knitting_map(), params);  // 20 rounds of 24
  const YarnModel y = stitch_mesh_to_yarn(mesh, params);
  ASSERT_EQ(y.yarns.size(), 1u);
  // Every stitch visited once, in index order (the knitting order of a tube's stitch mesh).
  std::vector<int> order;
  for (int s : y.yarns[0].stitch)
    if (order.empty() || order.back() != s) order.push_back(s);
  ASSERT_EQ(static_cast<int>(order.size()), mesh.num_stitches());
  for (int i = 0; i < mesh.num_stitches(); ++i) ASSERT_EQ(order[static_cast<size_t>(i)], i);
  // Stitches out of knitting order (two far-apart stitches swapped) are refused.
  StitchMesh shuffled = mesh;
  std::swap(shuffled.stitches[5], shuffled.stitches[300]);
  EXPECT_THROW(stitch_mesh_to_yarn(shuffled, params), TopologyError);
}

}  // namespace
}  // namespace knitforge
