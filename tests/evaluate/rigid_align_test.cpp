#include "knitforge/evaluate/rigid_align.h"

#include <cmath>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "knitforge/util/errors.h"

namespace knitforge {
namespace {

std::vector<Vec3> random_points(int n, uint32_t seed, double scale = 50.0) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-scale, scale);
  std::vector<Vec3> p(n);
  for (Vec3& x : p) x = Vec3(u(rng), u(rng), u(rng));
  return p;
}

Mat3 rotation(double angle, Vec3 axis) { return Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix(); }

TEST(RigidAlign, RecoversAKnownMotionExactly) {
  const std::vector<Vec3> from = random_points(40, 1);
  for (int k = 0; k < 6; ++k) {
    const Mat3 R = rotation(0.3 + 1.1 * k, Vec3(1, 2 - k, 0.5 * k));  // includes angles near pi
    const Vec3 t(10.0 * k - 7, 3, -20);
    std::vector<Vec3> to;
    for (const Vec3& p : from) to.push_back(R * p + t);
    const RigidTransform T = rigid_align(from, to);
    EXPECT_LT((T.rotation - R).cwiseAbs().maxCoeff(), 1e-9) << k;
    EXPECT_LT((T.translation - t).cwiseAbs().maxCoeff(), 1e-9) << k;
    EXPECT_NEAR(T.rotation.determinant(), 1.0, 1e-12);
  }
}

TEST(RigidAlign, ThreePointsSuffice) {
  const std::vector<Vec3> from = {Vec3(0, 0, 0), Vec3(3, 0, 0), Vec3(0, 2, 0)};
  const Mat3 R = rotation(2.0, Vec3(0.3, -1, 0.2));
  const Vec3 t(1, 2, 3);
  std::vector<Vec3> to;
  for (const Vec3& p : from) to.push_back(R * p + t);
  const RigidTransform T = rigid_align(from, to);
  EXPECT_LT((T.rotation - R).cwiseAbs().maxCoeff(), 1e-9);
  EXPECT_LT((T.translation - t).cwiseAbs().maxCoeff(), 1e-9);
}

TEST(RigidAlign, NeverReturnsAReflection) {
  // The target is the mirror image of the source: the best *proper* rotation
  // must be returned, with det +1 and an orthonormal matrix.
  const std::vector<Vec3> from = random_points(30, 2);
  std::vector<Vec3> to;
  for (const Vec3& p : from) to.push_back(Vec3(-p.x(), p.y(), p.z()));
  const RigidTransform T = rigid_align(from, to);
  EXPECT_NEAR(T.rotation.determinant(), 1.0, 1e-12);
  EXPECT_LT((T.rotation.transpose() * T.rotation - Mat3::Identity()).cwiseAbs().maxCoeff(), 1e-12);
  // Its residual is no worse than that of any of many random rotations
  // (each with its optimal translation).
  auto residual = [&](const Mat3& R) {
    Vec3 cf = Vec3::Zero(), ct = Vec3::Zero();
    for (size_t i = 0; i < from.size(); ++i) cf += from[i], ct += to[i];
    const Vec3 t = (ct - R * cf) / static_cast<double>(from.size());
    double s = 0;
    for (size_t i = 0; i < from.size(); ++i) s += (R * from[i] + t - to[i]).squaredNorm();
    return s;
  };
  const double best = residual(T.rotation);
  std::mt19937 rng(3);
  std::normal_distribution<double> g;
  for (int k = 0; k < 200; ++k) {
    const Mat3 R = rotation(3.0 * std::abs(g(rng)), Vec3(g(rng), g(rng), g(rng)));
    EXPECT_LE(best, residual(R) * (1 + 1e-12));
  }
}

TEST(RigidAlign, ZeroWeightsIgnoreOutliers) {
  std::vector<Vec3> from = random_points(20, 4);
  const Mat3 R = rotation(0.7, Vec3(0, 0, 1));
  const Vec3 t(0, -5, 2);
  std::vector<Vec3> to;
  for (const Vec3& p : from) to.push_back(R * p + t);
  std::vector<double> w(20, 2.5);
  to[3] += Vec3(100, 0, 0);
  to[7] += Vec3(0, 40, 9);
  w[3] = w[7] = 0;
  const RigidTransform T = rigid_align(from, to, w);
  EXPECT_LT((T.rotation - R).cwiseAbs().maxCoeff(), 1e-9);
  EXPECT_LT((T.translation - t).cwiseAbs().maxCoeff(), 1e-9);
  // Without the weights the outliers pull the fit away.
  const RigidTransform U = rigid_align(from, to);
  EXPECT_GT((U.translation - t).norm(), 1.0);
}

TEST(RigidAlign, BadInputThrows) {
  const std::vector<Vec3> a = random_points(5, 5), b = random_points(4, 6);
  EXPECT_THROW(rigid_align(a, b), InvalidInput);
  EXPECT_THROW(rigid_align(std::vector<Vec3>{}, std::vector<Vec3>{}), InvalidInput);
  std::vector<Vec3> c = a;
  c[2].x() = NAN;
  EXPECT_THROW(rigid_align(a, c), InvalidInput);
  EXPECT_THROW(rigid_align(a, a, std::vector<double>(5, 0.0)), InvalidInput);
  EXPECT_THROW(rigid_align(a, a, std::vector<double>{1, 1, -1, 1, 1}), InvalidInput);
  EXPECT_THROW(rigid_align(a, a, std::vector<double>{1, 1}), InvalidInput);
}

// A bumpy height field z = f(x, y) over [0, 60]^2, not symmetric, so the
// alignment onto it is unique.
TriMesh bumpy_surface(int n) {
  TriMesh m;
  const double h = 60.0 / n;
  for (int i = 0; i <= n; ++i) {
    for (int j = 0; j <= n; ++j) {
      const double x = j * h, y = i * h;
      m.vertices.emplace_back(x, y, 8 * std::sin(x / 13) * std::cos(y / 17) + 0.002 * x * y);
    }
  }
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      const int a = i * (n + 1) + j, b = a + 1, c = a + n + 2, d = a + n + 1;
      m.faces.push_back({a, b, c});
      m.faces.push_back({a, c, d});
    }
  }
  return m;
}

TEST(AlignToSurface, RecoversASmallMotionOntoACurvedSurface) {
  const TriMesh surface = bumpy_surface(40);
  // Points on the surface (its vertices away from the border), moved by a
  // small rigid motion; ICP must bring them back onto it.
  std::vector<Vec3> on;
  for (const Vec3& v : surface.vertices) {
    if (v.x() > 8 && v.x() < 52 && v.y() > 8 && v.y() < 52) on.push_back(v);
  }
  const Mat3 R = rotation(0.03, Vec3(1, 1, 0));
  const Vec3 t(0.6, -0.4, 0.8);
  std::vector<Vec3> moved;
  for (const Vec3& p : on) moved.push_back(R * p + t);
  IcpOptions o;
  o.max_iterations = 200;
  o.tolerance = 1e-9;
  const IcpResult r = align_to_surface(moved, surface, RigidTransform{}, o);
  EXPECT_GT(r.initial_rms, 0.5);
  EXPECT_LT(r.rms, 1e-3 * r.initial_rms);
  EXPECT_LE(r.rms, r.initial_rms);
  EXPECT_NEAR(r.transform.rotation.determinant(), 1.0, 1e-12);
  // The recovered motion undoes the applied one.
  const RigidTransform back = r.transform.after(RigidTransform{R, t});
  EXPECT_LT((back.rotation - Mat3::Identity()).norm(), 1e-3);
  EXPECT_LT(back.translation.norm(), 0.05);
}

TEST(AlignToSurface, StartsFromTheInitialTransformAndNeverGetsWorse) {
  const TriMesh surface = bumpy_surface(20);
  const std::vector<Vec3> pts(surface.vertices.begin() + 50, surface.vertices.begin() + 200);
  // Already on the surface: identity is optimal, RMS 0, no iteration needed.
  const IcpResult r0 = align_to_surface(pts, surface);
  EXPECT_EQ(r0.rms, 0.0);
  EXPECT_EQ(r0.iterations, 0);
  // With zero iterations the initial transform is returned unchanged.
  IcpOptions o;
  o.max_iterations = 0;
  const RigidTransform init{rotation(0.1, Vec3(0, 0, 1)), Vec3(1, 2, 3)};
  const IcpResult r1 = align_to_surface(pts, surface, init, o);
  EXPECT_EQ(r1.transform.rotation, init.rotation);
  EXPECT_EQ(r1.transform.translation, init.translation);
  EXPECT_EQ(r1.rms, r1.initial_rms);
  o.max_iterations = 5;
  const IcpResult r2 = align_to_surface(pts, surface, init, o);
  EXPECT_LT(r2.rms, r1.rms);
  o.max_iterations = -1;
  EXPECT_THROW(align_to_surface(pts, surface, init, o), InvalidInput);
  EXPECT_THROW(align_to_surface(std::vector<Vec3>{}, surface), InvalidInput);
}

// ICP from `init` (at most 30 rounds) converges within 20 to its RMS
// distance's minimum: no small turn about any axis through the aligned
// points' centroid, nor any small shift, lowers it.
IcpResult expect_fast_convergence_to_a_minimum(const std::vector<Vec3>& pts, const TriMesh& surface,
                                               const RigidTransform& init, double tolerance) {
  IcpOptions o;
  o.max_iterations = 30;
  o.tolerance = tolerance;
  const IcpResult r = align_to_surface(pts, surface, init, o);
  EXPECT_TRUE(r.converged);
  EXPECT_LE(r.iterations, 20);
  const SurfaceBvh bvh(surface);
  auto rms = [&](const RigidTransform& T) {
    double s = 0;
    for (const Vec3& p : pts) s += std::pow(bvh.closest_point(T.apply(p)).distance, 2);
    return std::sqrt(s / pts.size());
  };
  EXPECT_NEAR(rms(r.transform), r.rms, 1e-12);
  Vec3 centre = Vec3::Zero();
  for (const Vec3& p : pts) centre += r.transform.apply(p);
  centre /= pts.size();
  for (int j = 0; j < 3; ++j) {
    for (const double s : {-1.0, 1.0}) {
      const Mat3 dR = rotation(s * 1e-3, Vec3::Unit(j));
      const RigidTransform turn{dR, centre - dR * centre};
      const RigidTransform shift{Mat3::Identity(), s * 1e-2 * Vec3::Unit(j)};
      EXPECT_GE(rms(turn.after(r.transform)), r.rms - 1e-9) << "axis " << j << " sign " << s;
      EXPECT_GE(rms(shift.after(r.transform)), r.rms - 1e-9) << "axis " << j << " sign " << s;
    }
  }
  return r;
}

// A shape far from its target (a bowl over the bumpy surface's grid, turned
// and moved): ICP's Newton step converges in a few rounds
// to a minimum of the RMS distance, where no small rotation about any axis
// or translation lowers it (point-to-plane steps alone crawl there at a
// ratio of about 0.9 a round and stop at the round limit).
TEST(AlignToSurface, ConvergesFastFarFromTheTarget) {
  const TriMesh surface = bumpy_surface(30);
  std::vector<Vec3> pts;
  for (const Vec3& v : surface.vertices) {
    if (v.x() > 5 && v.x() < 55 && v.y() > 5 && v.y() < 55) {
      pts.push_back(Vec3(v.x(), v.y(), 0.01 * ((v.x() - 30) * (v.x() - 30) + (v.y() - 25) * (v.y() - 25))));
    }
  }
  const IcpResult r =
      expect_fast_convergence_to_a_minimum(pts, surface, {rotation(0.15, Vec3(1, -2, 0.5)), Vec3(2, -1, 1)}, 1e-10);
  EXPECT_GT(r.rms, 1.0);  // far from the surface even when aligned
}

// Over a flat disk turning about its axis is held by nothing and the
// in-plane motions only by the points beyond its rim: ICP must still converge
// to a minimum in a few rounds (where Newton's matrix is indefinite there,
// as for the free short-column disk of the e2e test DesignPrediction, the
// step is taken with its eigenvalues' absolute values).
TEST(AlignToSurface, ConvergesOverAFlatTarget) {
  // A flat disk of radius 30 (rings of 6k triangles fanned round the
  // centre): turning about its axis is held by nothing at all.
  TriMesh flat;
  flat.vertices.emplace_back(0, 0, 0);
  const int rings = 10;
  for (int k = 1; k <= rings; ++k) {
    for (int a = 0; a < 6 * k; ++a) {
      const double t = 2 * M_PI * a / (6 * k);
      flat.vertices.emplace_back(3.0 * k * std::cos(t), 3.0 * k * std::sin(t), 0);
    }
  }
  auto vertex = [](int k, int a) { return k == 0 ? 0 : 1 + 3 * k * (k - 1) + (a % (6 * k) + 6 * k) % (6 * k); };
  for (int k = 1; k <= rings; ++k) {
    // Ring k - 1 to ring k: each outer vertex a, with the inner vertex at its angle.
    for (int a = 0; a < 6 * k; ++a) {
      const int inner = k == 1 ? 0 : vertex(k - 1, (a * (k - 1)) / k);
      const int inner_next = k == 1 ? 0 : vertex(k - 1, ((a + 1) * (k - 1) + k - 1) / k);
      flat.faces.push_back({inner, vertex(k, a), vertex(k, a + 1)});
      if (inner_next != inner) flat.faces.push_back({inner, vertex(k, a + 1), inner_next});
    }
  }
  // A wrinkled dome a little wider than the disk.
  std::vector<Vec3> pts;
  for (int i = -16; i <= 16; ++i) {
    for (int j = -16; j <= 16; ++j) {
      const double x = 2.0 * j, y = 2.0 * i;
      if (x * x + y * y > 32.0 * 32.0) continue;
      pts.emplace_back(x, y, 6 - 0.01 * (x * x + y * y) + 1.5 * std::sin(x / 7) * std::sin(y / 9));
    }
  }
  expect_fast_convergence_to_a_minimum(pts, flat, {rotation(0.05, Vec3(0.3, 1, 2)), Vec3(1, -1, 0.5)}, 1e-8);
}

}  // namespace
}  // namespace knitforge
