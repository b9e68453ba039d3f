#include "knitforge/sim/bending_energy.h"

#include <cmath>
#include <numbers>
#include <random>

#include <gtest/gtest.h>

#include "finite_difference_check.h"
#include "knitforge/sim/sim_model.h"
#include "sim_test_meshes.h"

namespace knitforge {
namespace {

const BendingHinge kHinge{{0, 1, 2, 3}, 0.7};

test::Derivs hinge_derivs(const Eigen::VectorXd& x) {
  const ElementEnergy<4> r =
      hinge_element_energy(x.segment<3>(0), x.segment<3>(3), x.segment<3>(6), x.segment<3>(9), kHinge);
  return {r.value, r.gradient, r.hessian};
}

Eigen::VectorXd flat_hinge() {
  Eigen::VectorXd x(12);
  x << 0, 0, 0, 3, 0.2, 0, 1.2, 2.1, 0, 1.9, -2.4, 0;
  return x;
}

TEST(BendingEnergy, GradientAndHessianMatchFiniteDifferences) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-0.6, 0.6);
  for (int trial = 0; trial < 20; ++trial) {
    Eigen::VectorXd x = flat_hinge();
    for (int k = 0; k < 12; ++k) x[k] += u(rng);
    test::expect_derivatives_match(hinge_derivs, x, 1e-6, 1e-5, true);
  }
}

// Flat hinges too (θ = 0, where ∇²θ drops out).
TEST(BendingEnergy, HessianExactWhenFlat) {
  Eigen::VectorXd x = flat_hinge();
  // Any in-plane placement is flat.
  x[4] += 0.3;
  x[9] -= 0.2;
  test::expect_derivatives_match(hinge_derivs, x, 1e-6, 1e-5, true);
}

TEST(BendingEnergy, AngleSignAndMagnitude) {
  // Fold the x3 wing up by 30 degrees about the edge along x.
  const Vec3 x0(0, 0, 0), x1(2, 0, 0), x2(1, 1, 0);
  const double a = std::numbers::pi / 6;
  const Vec3 x3(1, -std::cos(a), std::sin(a));
  EXPECT_NEAR(std::abs(dihedral_angle(x0, x1, x2, x3)), a, 1e-12);
  EXPECT_NEAR(dihedral_angle(x0, x1, x2, x3), -dihedral_angle(x0, x1, x2, Vec3(1, -std::cos(a), -std::sin(a))),
              1e-12);
  EXPECT_NEAR(hinge_element_energy(x0, x1, x2, x3, kHinge, Derivatives::Value).value, 0.7 * a * a, 1e-12);
}

// The value-and-gradient path (Derivatives::Gradient, what the L-BFGS phase
// evaluates, its cross products formed once) gives the value and gradient
// of the Hessian paths (checked against finite differences above), on
// random, flat and degenerate hinges.
TEST(BendingEnergy, GradientPathEqualsHessianPath) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-0.6, 0.6);
  std::vector<Eigen::VectorXd> cases;
  for (int trial = 0; trial < 20; ++trial) {
    Eigen::VectorXd x = flat_hinge();
    for (int k = 0; k < 12; ++k) x[k] += u(rng);
    cases.push_back(x);
  }
  cases.push_back(flat_hinge());
  for (double off : {-1e-12, 0.0, 1e-12}) {
    Eigen::VectorXd x = flat_hinge();
    x.segment<3>(6) = Vec3(1.5, 0.1 * off, off);  // x2 on the hinge edge
    cases.push_back(x);
  }
  Eigen::VectorXd collapsed = flat_hinge();
  collapsed.segment<3>(3) = collapsed.segment<3>(0);  // the edge itself has length 0
  cases.push_back(collapsed);
  for (const Eigen::VectorXd& x : cases) {
    const Vec3 x0 = x.segment<3>(0), x1 = x.segment<3>(3), x2 = x.segment<3>(6), x3 = x.segment<3>(9);
    const ElementEnergy<4> g = hinge_element_energy(x0, x1, x2, x3, kHinge, Derivatives::Gradient);
    // The Clamp Hessian path forms the gradient by the same expressions: the same bits.
    const ElementEnergy<4> h = hinge_element_energy(x0, x1, x2, x3, kHinge, Derivatives::Hessian, PsdProjection::Clamp);
    EXPECT_EQ(g.value, h.value);
    for (int k = 0; k < 12; ++k) EXPECT_EQ(g.gradient[k], h.gradient[k]) << "entry " << k;
    // The exact path's forward-mode duals round differently in the last bits.
    const ElementEnergy<4> e = hinge_element_energy(x0, x1, x2, x3, kHinge, Derivatives::Hessian, PsdProjection::None);
    EXPECT_EQ(g.value, e.value);
    EXPECT_LE((g.gradient - e.gradient).norm(), 1e-13 * (1.0 + e.gradient.norm()));
    EXPECT_EQ(g.value, hinge_element_energy(x0, x1, x2, x3, kHinge, Derivatives::Value).value);
  }
}

class BendingNearDegenerate : public ::testing::TestWithParam<double> {};

TEST_P(BendingNearDegenerate, FiniteValues) {
  // x2 on (or just off) the hinge edge: a degenerate wing.
  Eigen::VectorXd x = flat_hinge();
  x.segment<3>(6) = Vec3(1.5, 0.1 * GetParam(), GetParam());
  const test::Derivs d = hinge_derivs(x);
  EXPECT_TRUE(std::isfinite(d.value));
  EXPECT_TRUE(d.gradient.allFinite());
  EXPECT_TRUE(d.hessian.allFinite());
}

INSTANTIATE_TEST_SUITE_P(Offsets, BendingNearDegenerate, ::testing::Values(-1e-12, 0.0, 1e-12, 1e-6));

TEST(BendingEnergy, ZeroForcesAndInvariance) {
  const Eigen::VectorXd x = flat_hinge();
  const Mat3 R = test::rotation(Vec3(0.3, -1, 2), 1.3);
  const Vec3 t(4, 5, -6);
  Eigen::VectorXd y(12), z(12);
  for (int k = 0; k < 4; ++k) y.segment<3>(3 * k) = R * x.segment<3>(3 * k) + t;
  EXPECT_NEAR(hinge_derivs(y).value, 0.0, 1e-20);
  EXPECT_LT(hinge_derivs(y).gradient.norm(), 1e-12);
  // A folded hinge: same energy after a rigid motion, forces sum to zero.
  z = x;
  z[11] = 0.8;
  for (int k = 0; k < 4; ++k) y.segment<3>(3 * k) = R * z.segment<3>(3 * k) + t;
  const test::Derivs a = hinge_derivs(z), b = hinge_derivs(y);
  EXPECT_NEAR(a.value, b.value, 1e-12 * a.value);
  Vec3 f = Vec3::Zero();
  for (int k = 0; k < 4; ++k) f += b.gradient.segment<3>(3 * k);
  EXPECT_LT(f.norm(), 1e-10 * b.gradient.norm());
}

// A sheet bent into a cylinder across its courses (or wales): the hinge
// energy is the plate energy ½ D κ² per area of the bent strip, with the
// rigidity of the curvature's direction.
TEST(BendingEnergy, CylinderGivesPlateEnergyPerDirection) {
  const int cols = 8, rows = 6;
  const double w = 3.0, h = 2.0, R = 40.0;
  const StitchMesh sheet = test::knit_sheet(cols, rows, w, h);
  KnitMaterial m = default_single_jersey();
  m.bending_course_un_m = 1.5;
  m.bending_wale_un_m = 4.0;
  SimModelOptions opt;
  opt.materials = {m};
  const SimModel model = build_sim_model(sheet, KnitParams{w, h}, opt);
  for (int dir = 0; dir < 2; ++dir) {
    Eigen::VectorXd x(3 * model.num_vertices());
    for (int v = 0; v < model.num_vertices(); ++v) {
      const Vec3 p = sheet.vertices[v];
      // Arc length along the bent direction maps to an angle on the circle.
      const double s = dir == 0 ? p.x() : p.y(), t = dir == 0 ? p.y() : p.x();
      const double phi = s / R;
      const Vec3 q = dir == 0 ? Vec3(R * std::sin(phi), t, R - R * std::cos(phi))
                              : Vec3(t, R * std::sin(phi), R - R * std::cos(phi));
      x.segment<3>(3 * v) = q;
    }
    EnergyEval ev(model.num_vertices(), Derivatives::Value);
    add_bending_energy(model, x, ev);
    // Bent across the courses (dir 0): the interior wale edges fold; the
    // strip between the first and last column has area (cols - 1) w x rows h.
    const double D = dir == 0 ? m.bending_course_un_m : m.bending_wale_un_m;
    const double area = dir == 0 ? (cols - 1) * w * rows * h : cols * w * (rows - 1) * h;
    EXPECT_NEAR(ev.value, 0.5 * D * area / (R * R), 1e-9 * ev.value) << "direction " << dir;
  }
}

}  // namespace
}  // namespace knitforge
