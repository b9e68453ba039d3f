#include "knitforge/convert/relax_stitch_mesh.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include <Eigen/SVD>

#include "convert/map_test_helpers.h"
#include "knitforge/convert/map_to_stitch_mesh.h"
#include "knitforge/convert/random_knitting_map.h"

using namespace knitforge;
using namespace knitforge::test;

namespace {

const KnitParams kP{3.5, 2.8};

// Relative edge length errors against the ideal shapes, sorted.
std::vector<double> edge_length_errors(const StitchMesh& m, const KnitParams& p) {
  std::vector<double> out;
  for (const Stitch& s : m.stitches) {
    const std::vector<Vec3> ideal = ideal_stitch_shape(s.type, p);
    const int n = s.corners();
    for (int k = 0; k < n; ++k) {
      const double want = (ideal[(k + 1) % n] - ideal[k]).norm();
      const double got = (m.vertices[s.v[(k + 1) % n]] - m.vertices[s.v[k]]).norm();
      out.push_back(std::abs(got - want) / want);
    }
  }
  std::sort(out.begin(), out.end());
  return out;
}

double edge_length_error(const StitchMesh& m, const KnitParams& p) {
  double worst = 0;
  for (const Stitch& s : m.stitches) {
    const std::vector<Vec3> ideal = ideal_stitch_shape(s.type, p);
    const int n = s.corners();
    for (int k = 0; k < n; ++k) {
      const double want = (ideal[(k + 1) % n] - ideal[k]).norm();
      const double got = (m.vertices[s.v[(k + 1) % n]] - m.vertices[s.v[k]]).norm();
      worst = std::max(worst, std::abs(got - want) / want);
    }
  }
  return worst;
}

// Largest distance of a vertex from the least-squares plane of all vertices.
double non_planarity(const std::vector<Vec3>& pts) {
  Vec3 c = Vec3::Zero();
  for (const Vec3& p : pts) c += p;
  c /= static_cast<double>(pts.size());
  Eigen::MatrixXd a(pts.size(), 3);
  for (size_t k = 0; k < pts.size(); ++k) a.row(k) = (pts[k] - c).transpose();
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(a, Eigen::ComputeThinV);
  const Vec3 n = svd.matrixV().col(2);
  double worst = 0;
  for (const Vec3& p : pts) worst = std::max(worst, std::abs((p - c).dot(n)));
  return worst;
}

// A 5 x 4 knit rectangle bent in z.
StitchMesh bent_rectangle() {
  StitchMesh bent = map_to_stitch_mesh_topology(parse_map({"KKKKK", "KKKKK", "KKKKK", "KKKKK"}), kP);
  for (Vec3& p : bent.vertices) p.z() = 0.02 * (p.x() - 8) * (p.x() - 8) + 0.5 * std::sin(p.y());
  return bent;
}

// Relaxation from the given geometry, run to convergence.
RelaxOptions to_convergence() {
  RelaxOptions ro;
  ro.warm_up = 0;
  ro.max_iterations = 5000;
  ro.tolerance = 1e-14;
  return ro;
}

}  // namespace

TEST(RelaxStitchMesh, IdealShapes) {
  const auto q = ideal_stitch_shape(StitchType::Knit, kP);
  ASSERT_EQ(q.size(), 4u);
  EXPECT_EQ(q[2], Vec3(3.5, 2.8, 0));
  const auto l = ideal_stitch_shape(StitchType::ShortRowLeft, kP);
  ASSERT_EQ(l.size(), 3u);
  // Seed §3.2.3: isosceles triangles whose shared sides keep their
  // neighbours' lengths: short-row ends w, w, h; increases/decreases h, h, w.
  auto edge = [](const std::vector<Vec3>& t, int i) { return (t[(i + 1) % 3] - t[i]).norm(); };
  for (StitchType t : {StitchType::ShortRowLeft, StitchType::ShortRowRight}) {
    const auto s = ideal_stitch_shape(t, kP);
    const int apex = apex_corner(t);
    EXPECT_NEAR(edge(s, apex), 3.5, 1e-12);            // apex -> next corner
    EXPECT_NEAR(edge(s, (apex + 2) % 3), 3.5, 1e-12);  // previous corner -> apex
    EXPECT_NEAR(edge(s, (apex + 1) % 3), 2.8, 1e-12);  // the base
    EXPECT_NEAR(s[apex].y(), 1.4, 1e-12);
  }
  for (StitchType t : {StitchType::Increase, StitchType::Decrease}) {
    const auto s = ideal_stitch_shape(t, kP);
    const int apex = apex_corner(t);
    EXPECT_NEAR(edge(s, apex), 2.8, 1e-12);
    EXPECT_NEAR(edge(s, (apex + 2) % 3), 2.8, 1e-12);
    EXPECT_NEAR(edge(s, (apex + 1) % 3), 3.5, 1e-12);
    EXPECT_NEAR(s[apex].x(), 1.75, 1e-12);
  }
  EXPECT_EQ(l[0].x(), 3.5 - std::sqrt(3.5 * 3.5 - 1.4 * 1.4));
}

TEST(RelaxStitchMesh, ShapingFreeMapRelaxesToTheExactRectangle) {
  RandomMapOptions o;
  o.rows = 12;
  o.cols = 9;
  const KnittingMap map = random_knitting_map(o);
  const StitchMesh m = map_to_stitch_mesh(map, kP);  // default warm-up
  double lo_x = 1e9, hi_x = -1e9, lo_y = 1e9, hi_y = -1e9, max_z = 0;
  for (const Vec3& p : m.vertices) {
    lo_x = std::min(lo_x, p.x()), hi_x = std::max(hi_x, p.x());
    lo_y = std::min(lo_y, p.y()), hi_y = std::max(hi_y, p.y());
    max_z = std::max(max_z, std::abs(p.z()));
  }
  const double W = 9 * 3.5, H = 12 * 2.8;
  EXPECT_NEAR(hi_x - lo_x, W, 1e-6 * W);
  EXPECT_NEAR(hi_y - lo_y, H, 1e-6 * H);
  EXPECT_LE(max_z, 1e-6 * W);
  EXPECT_LE(edge_length_error(m, kP), 1e-6);
}

TEST(RelaxStitchMesh, BentRectangleRelaxesToRigidStitches) {
  // Start from a rectangle bent in z (no warm-up). Quads may hinge along
  // whole courses or wales at no cost, so the result need not be flat, but
  // every stitch must become its ideal rectangle again.
  const StitchMesh bent = bent_rectangle();
  RelaxOptions ro = to_convergence();
  const RelaxResult r = relax_stitch_mesh(bent, kP, ro);
  EXPECT_LE(edge_length_error(r.mesh, kP), 1e-3);
  for (const Stitch& s : r.mesh.stitches) {
    const Vec3 a = r.mesh.vertices[s.v[1]] - r.mesh.vertices[s.v[0]];
    const Vec3 b = r.mesh.vertices[s.v[3]] - r.mesh.vertices[s.v[0]];
    EXPECT_NEAR(a.normalized().dot(b.normalized()), 0.0, 1e-3);  // right angle
  }
  EXPECT_LT(r.energy.back(), 1e-6 * r.energy.front());
  for (size_t k = 1; k < r.energy.size(); ++k) EXPECT_LE(r.energy[k], r.energy[k - 1] * (1 + 1e-12));
}

TEST(RelaxStitchMesh, BendingHingesAreFlatPairsOfIdealStitches) {
  // A flat layout of ideal stitches has zero energy with the bending term
  // too: every hinge target is the two ideal shapes joined along their
  // shared edge, on opposite sides of it.
  const StitchMesh flat = map_to_stitch_mesh_topology(parse_map({"KKKKK", "KKKKK", "KKKKK", "KKKKK"}), kP);
  RelaxOptions ro;
  ro.warm_up = 0;
  ro.bending = 0.5;
  ro.max_iterations = 3;
  const RelaxResult r = relax_stitch_mesh(flat, kP, ro);
  EXPECT_LT(r.energy.front(), 1e-20);
  // Bending adds energy only where the fabric folds: the same rectangle
  // folded along one wale line costs more with bending than without.
  StitchMesh folded = flat;
  for (Vec3& p : folded.vertices) {
    if (p.x() > 2 * kP.stitch_width + 1e-9) {
      const double d = p.x() - 2 * kP.stitch_width;
      p.x() = 2 * kP.stitch_width + d * std::cos(0.5);
      p.z() = d * std::sin(0.5);
    }
  }
  RelaxOptions plain = ro;
  plain.bending = 0;
  EXPECT_LT(relax_stitch_mesh(folded, kP, plain).energy.front(), 1e-20);  // a fold costs nothing without it
  EXPECT_GT(relax_stitch_mesh(folded, kP, ro).energy.front(), 1e-3);
}

TEST(RelaxStitchMesh, BendingMakesTheRestShapeOfAFlatFabricFlat) {
  // Without bending, a bent knit-only rectangle relaxes to rigid stitches
  // but keeps (part of) its bend, since folds are free; with bending it
  // relaxes all the way back to a plane.
  const StitchMesh bent = bent_rectangle();
  RelaxOptions ro = to_convergence();
  const RelaxResult free_folds = relax_stitch_mesh(bent, kP, ro);
  ro.bending = 0.1;
  const RelaxResult stiff = relax_stitch_mesh(bent, kP, ro);
  EXPECT_GT(non_planarity(free_folds.mesh.vertices), 0.05);
  EXPECT_LT(non_planarity(stiff.mesh.vertices), 1e-3);
  EXPECT_LE(edge_length_error(stiff.mesh, kP), 1e-3);
  for (size_t k = 1; k < stiff.energy.size(); ++k) EXPECT_LE(stiff.energy[k], stiff.energy[k - 1] * (1 + 1e-12));
}

TEST(RelaxStitchMesh, ShortRowsRelaxToANonPlanarSurface) {
  RandomMapOptions o;
  o.seed = 5;
  o.rows = 24;
  o.cols = 20;
  o.short_row_ends = 16;
  o.short_columns = 3;
  const KnittingMap map = random_knitting_map(o);
  const StitchMesh topo = map_to_stitch_mesh_topology(map, kP);
  RelaxOptions ro;
  const RelaxResult r = relax_stitch_mesh(topo, kP, ro);
  double max_z = 0;
  for (const Vec3& p : r.mesh.vertices) max_z = std::max(max_z, std::abs(p.z()));
  EXPECT_GT(max_z, 0.5 * 3.5) << "the relaxed fabric stays flat";
  // The ideal shapes do not fit together exactly next to shaping stitches
  // (a short-row end's bottom side is sqrt(w^2 + h^2/4) = 1.08 w long, an
  // increase's sides sqrt(w^2/4 + h^2) = 1.18 h), so a few edges there stay
  // off by more than 10%.
  const std::vector<double> err = edge_length_errors(r.mesh, kP);
  EXPECT_LE(err[err.size() * 95 / 100], 0.10);
  EXPECT_LE(err.back(), 0.25);
  ASSERT_GE(r.energy.size(), 2u);
  for (size_t k = 1; k < r.energy.size(); ++k) EXPECT_LE(r.energy[k], r.energy[k - 1] * (1 + 1e-12));
  EXPECT_LT(r.energy.back(), 0.1 * r.energy.front());
  // Without the warm-up the result stays in the plane (seed Fig. 1.5c).
  ro.warm_up = 0;
  const RelaxResult flat = relax_stitch_mesh(topo, kP, ro);
  for (const Vec3& p : flat.mesh.vertices) EXPECT_EQ(p.z(), 0.0);
  // Topology is untouched.
  ASSERT_EQ(r.mesh.num_stitches(), topo.num_stitches());
  for (int s = 0; s < topo.num_stitches(); ++s) EXPECT_EQ(r.mesh.stitches[s].v, topo.stitches[s].v);
}

TEST(RelaxStitchMesh, RejectsBadInput) {
  const StitchMesh m = map_to_stitch_mesh_topology(parse_map({"KK"}), kP);
  EXPECT_THROW(relax_stitch_mesh(StitchMesh{}, kP), InvalidInput);
  EXPECT_THROW(relax_stitch_mesh(m, KnitParams{-1, 2}), InvalidInput);
  RelaxOptions bad;
  bad.warm_up = -1;
  EXPECT_THROW(relax_stitch_mesh(m, kP, bad), InvalidInput);
  bad.warm_up = 0;
  bad.bending = -0.1;
  EXPECT_THROW(relax_stitch_mesh(m, kP, bad), InvalidInput);
  bad.bending = std::nan("");
  EXPECT_THROW(relax_stitch_mesh(m, kP, bad), InvalidInput);
  StitchMesh nan = m;
  nan.vertices[0].x() = std::nan("");
  EXPECT_THROW(relax_stitch_mesh(nan, kP), InvalidInput);
  StitchMesh broken = m;
  broken.stitches[0].v[2] = 99;
  EXPECT_THROW(relax_stitch_mesh(broken, kP), TopologyError);
}
