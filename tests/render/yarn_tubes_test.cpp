#include "knitforge/render/yarn_tubes.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>

#include "knitforge/util/errors.h"

namespace knitforge {
namespace {

constexpr double kPi = std::numbers::pi;

// Signed volume enclosed by a triangle mesh (divergence theorem).
double volume(const TriMesh& m) {
  double v = 0.0;
  for (const auto& f : m.faces) {
    v += m.vertices[f[0]].dot(m.vertices[f[1]].cross(m.vertices[f[2]])) / 6.0;
  }
  return v;
}

// After welding vertices at identical positions (the caps have their own
// copies of the end rings), every undirected edge is used by exactly two
// faces, in opposite directions.
bool closed_and_oriented(const TriMesh& m) {
  std::map<std::array<double, 3>, int> weld;
  std::vector<int> id(m.vertices.size());
  for (size_t v = 0; v < m.vertices.size(); ++v) {
    id[v] = weld.emplace(std::array<double, 3>{m.vertices[v].x(), m.vertices[v].y(), m.vertices[v].z()},
                         static_cast<int>(weld.size()))
                .first->second;
  }
  std::map<std::pair<int, int>, int> directed;
  for (const auto& f : m.faces) {
    for (int k = 0; k < 3; ++k) ++directed[{id[f[k]], id[f[(k + 1) % 3]]}];
  }
  for (const auto& [e, n] : directed) {
    if (n != 1) return false;
    auto it = directed.find({e.second, e.first});
    if (it == directed.end() || it->second != 1) return false;
  }
  return true;
}

std::vector<Vec3> helix(int n, double radius, double pitch, double turns) {
  std::vector<Vec3> p;
  for (int i = 0; i < n; ++i) {
    const double t = turns * 2.0 * kPi * i / (n - 1);
    p.emplace_back(radius * std::cos(t), radius * std::sin(t), pitch * t / (2.0 * kPi));
  }
  return p;
}

TEST(SmoothPolyline, InterpolatesEveryPointAndRespectsSpacing) {
  const std::vector<Vec3> pts = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {1, 1, 0}, {3, 2, 1}, {3, 2, 3}};
  const auto c = smooth_polyline(pts, 0.2);
  // every distinct input point is a sample, in order
  size_t j = 0;
  for (const Vec3& p : c) {
    if (j < pts.size() && (p - pts[j]).norm() == 0.0) {
      ++j;
      while (j < pts.size() && (pts[j] - pts[j - 1]).norm() == 0.0) ++j;  // the duplicate
    }
  }
  EXPECT_EQ(j, pts.size());
  // segment lengths 1, 1, sqrt(6), 2 -> 5 + 5 + 13 + 10 intervals
  EXPECT_EQ(c.size(), 5u + 5u + 13u + 10u + 1u);
  for (size_t i = 0; i + 1 < c.size(); ++i) EXPECT_LT((c[i + 1] - c[i]).norm(), 0.3) << i;
}

TEST(SmoothPolyline, StraightInputStaysStraight) {
  const std::vector<Vec3> pts = {{0, 0, 0}, {1, 1, 1}, {2, 2, 2}, {5, 5, 5}};
  for (const Vec3& p : smooth_polyline(pts, 0.1)) {
    EXPECT_NEAR(p.x(), p.y(), 1e-12);
    EXPECT_NEAR(p.x(), p.z(), 1e-12);
  }
}

TEST(SmoothPolyline, RejectsBadInput) {
  const std::vector<Vec3> pts = {{0, 0, 0}, {1, 0, 0}};
  EXPECT_THROW(smooth_polyline(pts, 0.0), InvalidInput);
  const std::vector<Vec3> bad = {{0, 0, 0}, {NAN, 0, 0}};
  EXPECT_THROW(smooth_polyline(bad, 1.0), InvalidInput);
}

TEST(ParallelTransport, FramesAreOrthonormalAndRotationMinimising) {
  const auto c = smooth_polyline(helix(60, 2.0, 1.5, 2.0), 0.05);
  const CurveFrames f = parallel_transport_frames(c);
  ASSERT_EQ(f.normals.size(), c.size());
  double twist = 0.0, bend = 0.0;
  for (size_t i = 0; i < c.size(); ++i) {
    EXPECT_NEAR(f.tangents[i].norm(), 1.0, 1e-12);
    EXPECT_NEAR(f.normals[i].norm(), 1.0, 1e-12);
    EXPECT_NEAR(f.normals[i].dot(f.tangents[i]), 0.0, 1e-12);
    if (i + 1 < c.size()) {
      const Vec3 b = f.tangents[i].cross(f.normals[i]);
      const Vec3 b1 = f.tangents[i + 1].cross(f.normals[i + 1]);
      twist += std::abs((f.normals[i + 1] - f.normals[i]).dot(0.5 * (b + b1)));  // rotation about the tangent
      bend += (f.tangents[i + 1] - f.tangents[i]).norm();
    }
  }
  // a Frenet frame of this helix turns about the tangent by its torsion
  // (0.059 rad/mm over 25.3 mm, 1.49 rad); the RMF only by the discretisation
  // error
  EXPECT_GT(bend, 1.0);
  EXPECT_LT(twist, 0.01);
}

TEST(ParallelTransport, PlanarCurveKeepsTheBinormal) {
  std::vector<Vec3> arc;
  for (int i = 0; i <= 40; ++i) arc.emplace_back(std::cos(0.05 * i), std::sin(0.05 * i), 0.0);
  const CurveFrames f = parallel_transport_frames(arc);
  // the normal's component out of the curve's plane never changes
  for (size_t i = 0; i < arc.size(); ++i) EXPECT_NEAR(f.normals[i].z(), f.normals[0].z(), 1e-9) << i;
  // tilted start: the same holds for a rotated copy of the arc
  const Eigen::AngleAxisd rot(0.7, Vec3(1, 2, 3).normalized());
  std::vector<Vec3> tilted;
  for (const Vec3& p : arc) tilted.push_back(rot * p);
  const Vec3 up = rot * Vec3::UnitZ();
  const CurveFrames g = parallel_transport_frames(tilted);
  EXPECT_GT(std::abs(g.normals[0].dot(up)), 0.1);  // a start with both components
  for (size_t i = 0; i < arc.size(); ++i) EXPECT_NEAR(g.normals[i].dot(up), g.normals[0].dot(up), 1e-9) << i;
  EXPECT_NEAR(f.arc_length.back(), 40 * 2 * std::sin(0.025), 1e-12);
}

TEST(YarnTube, StraightPrismHasExactVolumeAndOutwardOrientation) {
  TubeOptions o;
  o.plies = 8;
  o.vertices_per_ply = 1;
  o.ply_depth = 0.0;
  o.twist_per_mm = 0.0;
  const double r = 0.5, len = 4.0;
  const std::vector<Vec3> line = {{0, 0, 0}, {len, 0, 0}};
  const RenderMesh t = yarn_tube(line, o, r, {1, 2, 3});
  const int k = 8;
  ASSERT_EQ(t.mesh.num_vertices(), 2 * k + 2 * (k + 1));
  EXPECT_EQ(t.mesh.num_faces(), 2 * k + 2 * k);
  EXPECT_TRUE(closed_and_oriented(t.mesh));
  EXPECT_NEAR(volume(t.mesh), len * 0.5 * k * r * r * std::sin(2 * kPi / k), 1e-12);
  ASSERT_EQ(t.normals.size(), t.mesh.vertices.size());
  EXPECT_TRUE(t.vertex_colours.empty());
  EXPECT_EQ(t.colour, (RenderColour{1, 2, 3}));
  for (int v = 0; v < 2 * k; ++v) {  // side normals point away from the axis
    Vec3 radial = t.mesh.vertices[v];
    radial.x() = 0.0;
    EXPECT_GT(t.normals[v].dot(radial.normalized()), 0.99) << v;
  }
  EXPECT_NEAR(t.normals[2 * k + k].x(), -1.0, 1e-12);  // start cap centre
  EXPECT_NEAR(t.normals.back().x(), 1.0, 1e-12);       // end cap centre
}

TEST(YarnTube, PlyEnvelopeAndTwist) {
  TubeOptions o;
  o.plies = 6;
  o.vertices_per_ply = 2;
  o.ply_depth = 1.0;
  o.twist_per_mm = 0.25;
  o.ring_spacing = 0.1;
  o.capped = false;
  const double r = 0.6;
  // a slightly wavy line, so the curve is subdivided; the frames of a
  // straight x line are N = y, B = z
  const std::vector<Vec3> line = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}};
  const RenderMesh t = yarn_tube(line, o, r, {});
  const int k = 12;
  ASSERT_EQ(t.mesh.num_vertices() % k, 0);
  const int rings = t.mesh.num_vertices() / k;
  EXPECT_EQ(rings, 21);
  const double s = std::sin(kPi / 6), c = r / (1 + s);
  const double valley = c * std::cos(kPi / 6);
  for (int i = 0; i < rings; ++i) {
    const double x = t.mesh.vertices[i * k].x();
    for (int j = 0; j < k; ++j) {
      const Vec3 p = t.mesh.vertices[i * k + j];
      EXPECT_NEAR(p.x(), x, 1e-12);
      EXPECT_NEAR(std::hypot(p.y(), p.z()), j % 2 == 0 ? r : valley, 1e-12) << i << " " << j;
    }
    const double expected = 2 * kPi * 0.25 * x;  // twist phase after x mm
    const Vec3 p0 = t.mesh.vertices[i * k];
    EXPECT_NEAR(std::remainder(std::atan2(p0.z(), p0.y()) - expected, 2 * kPi), 0.0, 1e-9) << i;
  }
  EXPECT_FALSE(closed_and_oriented(t.mesh));  // open ends
}

TEST(YarnTube, TwistOfOnePlyPerRingKeepsThePrismExact) {
  // 0.5 turns/mm, 6 plies, rings every 1/3 mm: each ring is turned by exactly
  // one ply, and joining a vertex to the next ring's vertex one ply on makes
  // every side edge parallel to the axis (the exact prism volume). Joining
  // equal indices instead would shear every quad by 60 degrees.
  TubeOptions o;
  o.plies = 6;
  o.vertices_per_ply = 2;
  o.ply_depth = 0.0;
  o.twist_per_mm = 0.5;
  o.ring_spacing = 1.0 / 3.0;
  const std::vector<Vec3> line = {{0, 0, 0}, {2, 0, 0}, {4, 0, 0}};
  const RenderMesh t = yarn_tube(line, o, 0.3, {});
  EXPECT_EQ(t.mesh.num_vertices(), 13 * 12 + 2 * 13);
  EXPECT_TRUE(closed_and_oriented(t.mesh));
  EXPECT_NEAR(volume(t.mesh), 4.0 * 0.5 * 12 * 0.09 * std::sin(2 * kPi / 12), 1e-9);
  for (int f = 0; f < 2 * 12 * 12; ++f) {  // side triangles: one edge along the axis
    const auto& tri = t.mesh.faces[f];
    int axial = 0;
    for (int k = 0; k < 3; ++k) {
      const Vec3 e = t.mesh.vertices[tri[(k + 1) % 3]] - t.mesh.vertices[tri[k]];
      if (std::abs(e.y()) < 1e-9 && std::abs(e.z()) < 1e-9) ++axial;
    }
    EXPECT_EQ(axial, 1) << f;
  }
}

TEST(YarnTube, TwistedCurvedTubeIsClosedWithNearlyThePrismVolume) {
  TubeOptions o;
  o.plies = 6;
  o.vertices_per_ply = 4;
  o.ply_depth = 0.0;
  o.twist_per_mm = 0.5;
  const auto pts = helix(30, 3.0, 2.0, 1.0);
  const RenderMesh t = yarn_tube(pts, o, 0.3, {});
  EXPECT_TRUE(closed_and_oriented(t.mesh));
  double len = 0.0;
  const auto c = smooth_polyline(pts, 0.3);
  for (size_t i = 0; i + 1 < c.size(); ++i) len += (c[i + 1] - c[i]).norm();
  const double prism = len * 0.5 * 24 * 0.09 * std::sin(2 * kPi / 24);
  // rings turn by up to half a ply against the ply-aligned joins (here at
  // most 30 degrees, a chord factor of cos(15 deg)^2)
  EXPECT_GT(volume(t.mesh) / prism, 0.93);
  EXPECT_LT(volume(t.mesh) / prism, 1.0);
}

TEST(YarnTubes, OneMeshPerYarnWithItsColour) {
  YarnModel y;
  y.yarns.push_back({0, {{0, 0, 0}, {1, 0, 0}, {2, 1, 0}}, {0, 0, 1}});
  y.yarns.push_back({3, {{0, 5, 0}, {4, 5, 0}}, {0, 0}});
  y.yarns.push_back({4, {{1, 1, 1}}, {0}});  // a single point: no tube
  const std::vector<RenderColour> colours = {{10, 20, 30}, {40, 50, 60}};
  TubeOptions o;
  const auto tubes = yarn_tubes(y, KnitParams{}, o, colours);
  ASSERT_EQ(tubes.size(), 3u);
  EXPECT_EQ(tubes[0].name, "yarn 0");
  EXPECT_EQ(tubes[1].name, "yarn 3");
  EXPECT_EQ(tubes[1].colour, colours[1]);
  EXPECT_EQ(tubes[0].colour, colours[0]);
  EXPECT_TRUE(tubes[0].vertex_colours.empty());  // one colour per yarn: RenderMesh::colour
  EXPECT_TRUE(tubes[2].mesh.faces.empty());
  // default radius = 0.12 * stitch width
  const double r = 0.12 * KnitParams{}.stitch_width;
  double max_dist = 0.0;
  for (const Vec3& p : tubes[1].mesh.vertices) max_dist = std::max(max_dist, std::abs(p.y() - 5.0));
  EXPECT_NEAR(max_dist, r, 1e-12);
  EXPECT_TRUE(closed_and_oriented(tubes[0].mesh));
}

// The ring-by-ring float32 output (used by write_yarn_glb) is yarn_tube()'s
// geometry rounded to float, and the side indices of any run of rings are
// yarn_tube()'s faces shifted to that run.
TEST(TubeRings, FloatVerticesAndIndicesMatchTheMesh) {
  TubeOptions o;
  o.vertices_per_ply = 2;
  o.capped = false;
  o.ring_spacing = 0.2;
  const std::vector<Vec3> pts = helix(30, 2.0, 1.5, 2.0);
  const RenderMesh t = yarn_tube(pts, o, 0.35, {});
  const TubeSection sec = tube_section(o, 0.35);
  const std::vector<TubeRing> rings = tube_rings(pts, o, 0.35);
  const size_t K = static_cast<size_t>(sec.size());
  ASSERT_EQ(K, 12u);
  ASSERT_EQ(rings.size() * K, t.mesh.vertices.size());
  std::vector<float> pos(3 * K * rings.size()), nrm(pos.size());
  tube_ring_vertices(sec, rings, pos, nrm);
  for (size_t v = 0; v < t.mesh.vertices.size(); ++v) {
    for (int c = 0; c < 3; ++c) {
      EXPECT_EQ(pos[3 * v + static_cast<size_t>(c)], static_cast<float>(t.mesh.vertices[v][c])) << v;
      EXPECT_EQ(nrm[3 * v + static_cast<size_t>(c)], static_cast<float>(t.normals[v][c])) << v;
    }
    EXPECT_NEAR(t.normals[v].norm(), 1.0, 1e-12);
  }
  for (const TubeRing& r : rings) {  // orthonormal axes, u x w along the curve
    EXPECT_NEAR(r.u.norm(), 1.0, 1e-12);
    EXPECT_NEAR(r.w.norm(), 1.0, 1e-12);
    EXPECT_NEAR(r.u.dot(r.w), 0.0, 1e-12);
    EXPECT_GE(r.shift, 0);
    EXPECT_LT(r.shift, static_cast<int>(K));
  }
  // a run of rings [3, 9] written with base 100 into uint16 indices
  const std::span<const TubeRing> run = std::span<const TubeRing>(rings).subspan(3, 7);
  std::vector<uint16_t> idx(6 * K * 6);
  tube_side_indices(run, static_cast<int>(K), 100, idx);
  for (size_t f = 0; f < idx.size() / 3; ++f) {
    for (size_t c = 0; c < 3; ++c) {
      const int global = t.mesh.faces[2 * K * 3 + f][c];
      EXPECT_EQ(static_cast<int>(idx[3 * f + c]) - 100 + static_cast<int>(3 * K), global) << f;
    }
  }
  std::vector<uint16_t> wrong(5);
  EXPECT_THROW(tube_side_indices(run, static_cast<int>(K), 0, wrong), InvalidInput);
  std::vector<uint16_t> small(6 * K * 6);
  EXPECT_THROW(tube_side_indices(run, static_cast<int>(K), 65500, small), InvalidInput);  // overflows uint16
}

// Far along a long yarn (arc length 10^5 mm) the twist phase is still exact:
// the u axis of a straight tube turns by twist * distance between rings.
TEST(TubeRings, TwistPhaseStaysExactOnLongYarns) {
  TubeOptions o;
  o.twist_per_mm = 0.15;
  o.ring_spacing = 0.5;
  const double far = 1e5;
  const std::vector<Vec3> line = {{0, 0, 0}, {far, 0, 0}, {far + 2.0, 0, 0}};
  // three points on a line: smoothing keeps it straight
  const std::vector<TubeRing> rings = tube_rings(line, o, 0.3);
  ASSERT_GT(rings.size(), 3u);
  const TubeRing& a = rings[rings.size() - 2];
  const TubeRing& b = rings.back();
  const double ds = b.centre.x() - a.centre.x();
  const double angle = std::atan2(a.u.cross(b.u).dot(Vec3::UnitX()), a.u.dot(b.u));
  EXPECT_NEAR(angle, 2.0 * kPi * o.twist_per_mm * ds, 1e-6);
  const double turns = o.twist_per_mm * b.centre.x();
  const double expect = 2.0 * kPi * (turns - std::floor(turns));  // phase from ring 0's u
  const double got = std::atan2(rings[0].u.cross(b.u).dot(Vec3::UnitX()), rings[0].u.dot(b.u));
  EXPECT_NEAR(std::remainder(got - expect, 2.0 * kPi), 0.0, 1e-6);
}

TEST(YarnTube, RejectsBadOptions) {
  const std::vector<Vec3> line = {{0, 0, 0}, {1, 0, 0}};
  TubeOptions o;
  EXPECT_THROW(yarn_tube(line, o, 0.0, {}), InvalidInput);
  o.plies = 0;
  EXPECT_THROW(yarn_tube(line, o, 0.4, {}), InvalidInput);
  o = {};
  o.ply_depth = 1.5;
  EXPECT_THROW(yarn_tube(line, o, 0.4, {}), InvalidInput);
  o = {};
  o.vertices_per_ply = 0;
  EXPECT_THROW(yarn_tube(line, o, 0.4, {}), InvalidInput);
  o = {};
  o.ring_spacing = -1.0;
  EXPECT_THROW(yarn_tube(line, o, 0.4, {}), InvalidInput);
  YarnModel y;
  y.yarns.push_back({2, {{0, 0, 0}, {NAN, 0, 0}}, {0, 0}});
  try {
    yarn_tubes(y, KnitParams{}, {});
    FAIL();
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("yarn 0 (id 2)"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace knitforge
