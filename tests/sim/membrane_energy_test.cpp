#include "knitforge/sim/membrane_energy.h"

#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "finite_difference_check.h"
#include "knitforge/util/errors.h"
#include "sim_test_meshes.h"

namespace knitforge {
namespace {

// A rest triangle in the material frame and its element.
MembraneElement element_from_rest(const Vec2& p0, const Vec2& p1, const Vec2& p2) {
  Mat2 D;
  D.col(0) = p1 - p0;
  D.col(1) = p2 - p0;
  MembraneElement e;
  e.v = {0, 1, 2};
  e.rest_inverse = D.inverse();
  e.rest_area_mm2 = 0.5 * D.determinant();
  return e;
}

test::Derivs element_derivs(const Eigen::VectorXd& x, const MembraneElement& e, const KnitMaterial& m,
                            PsdProjection proj = PsdProjection::None) {
  const ElementEnergy<3> r = membrane_element_energy(x.segment<3>(0), x.segment<3>(3), x.segment<3>(6), e, m,
                                                     Derivatives::Hessian, proj);
  return {r.value, r.gradient, r.hessian};
}

const MembraneElement kElement = element_from_rest({0, 0}, {3.2, 0}, {0.4, 2.2});

TEST(MembraneEnergy, DerivativesMatchFiniteDifferences) {
  const KnitMaterial m = default_single_jersey();
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-0.8, 0.8);
  // Random deformations: compressed, stretched into the stiff segment, sheared past 0.5.
  for (int trial = 0; trial < 20; ++trial) {
    Eigen::VectorXd x(9);
    x << 0, 0, 0, 3.2, 0, 0, 0.4, 2.2, 0;
    for (int k = 0; k < 9; ++k) x[k] += u(rng);
    test::expect_derivatives_match([&](const Eigen::VectorXd& y) { return element_derivs(y, kElement, m); }, x,
                                   1e-6, 1e-5);
  }
}

// Deformed triangles near collapse (x2 on the line x0 x1, slightly off it,
// or through it: an inverted element): value and derivatives stay finite and
// the gradient matches finite differences.
class MembraneNearDegenerate : public ::testing::TestWithParam<double> {};

TEST_P(MembraneNearDegenerate, FiniteAndConsistent) {
  const KnitMaterial m = default_single_jersey();
  Eigen::VectorXd x(9);
  x << 0, 0, 0, 3.0, 0, 0, 1.5, GetParam(), 0;
  const test::Derivs d = element_derivs(x, kElement, m);
  EXPECT_TRUE(std::isfinite(d.value));
  EXPECT_TRUE(d.gradient.allFinite());
  EXPECT_TRUE(d.hessian.allFinite());
  test::expect_derivatives_match([&](const Eigen::VectorXd& y) { return element_derivs(y, kElement, m); }, x, 1e-7,
                                 1e-5, false);
  const test::Derivs p = element_derivs(x, kElement, m, PsdProjection::Clamp);
  EXPECT_GE(Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(p.hessian).eigenvalues().minCoeff(),
            -1e-9 * p.hessian.norm());
}

INSTANTIATE_TEST_SUITE_P(Offsets, MembraneNearDegenerate, ::testing::Values(-1e-8, -1e-12, 0.0, 1e-12, 1e-8));

TEST(MembraneEnergy, ZeroAtRestInAnyPlacement) {
  const KnitMaterial m = default_single_jersey();
  const Mat3 R = test::rotation(Vec3(1, 2, 3), 0.9);
  const Vec3 t(10, -4, 7);
  const Vec3 x0 = t, x1 = R * Vec3(3.2, 0, 0) + t, x2 = R * Vec3(0.4, 2.2, 0) + t;
  const ElementEnergy<3> r = membrane_element_energy(x0, x1, x2, kElement, m);
  EXPECT_NEAR(r.value, 0.0, 1e-12);
  EXPECT_LT(r.gradient.norm(), 1e-10);
}

TEST(MembraneEnergy, InvariantUnderRigidMotion) {
  const KnitMaterial m = default_single_jersey();
  const Vec3 x0(0.1, -0.2, 0.3), x1(3.5, 0.1, -0.4), x2(0.2, 2.9, 0.5);
  const Mat3 R = test::rotation(Vec3(-1, 0.5, 2), 2.1);
  const Vec3 t(-3, 8, 1);
  const ElementEnergy<3> a = membrane_element_energy(x0, x1, x2, kElement, m);
  const ElementEnergy<3> b = membrane_element_energy(R * x0 + t, R * x1 + t, R * x2 + t, kElement, m);
  EXPECT_NEAR(a.value, b.value, 1e-10 * a.value);
  for (int k = 0; k < 3; ++k) {
    EXPECT_LT((R * a.gradient.segment<3>(3 * k) - b.gradient.segment<3>(3 * k)).norm(), 1e-9 * a.gradient.norm());
  }
  // The forces of a rigidly moved element sum to zero, as do their moments.
  Vec3 f = Vec3::Zero(), moment = Vec3::Zero();
  const Vec3 xs[3] = {x0, x1, x2};
  for (int k = 0; k < 3; ++k) {
    f += a.gradient.segment<3>(3 * k);
    moment += xs[k].cross(Vec3(a.gradient.segment<3>(3 * k)));
  }
  EXPECT_LT(f.norm(), 1e-10 * a.gradient.norm());
  EXPECT_LT(moment.norm(), 1e-9 * a.gradient.norm() * 4);
}

TEST(MembraneEnergy, ProjectionIsPsdAndExactWhenAlreadyPsd) {
  const KnitMaterial m = default_single_jersey();
  // Compressed along the course: the exact Hessian is indefinite.
  Eigen::VectorXd x(9);
  x << 0, 0, 0, 2.4, 0, 0, 0.3, 2.2, 0;
  const test::Derivs exact = element_derivs(x, kElement, m);
  const test::Derivs clamp = element_derivs(x, kElement, m, PsdProjection::Clamp);
  const test::Derivs abs = element_derivs(x, kElement, m, PsdProjection::Abs);
  EXPECT_LT(Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(exact.hessian).eigenvalues().minCoeff(), -1e-6);
  for (const auto* d : {&clamp, &abs}) {
    EXPECT_GE(Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(d->hessian).eigenvalues().minCoeff(),
              -1e-9 * d->hessian.norm());
  }
  // Stretched in both directions and unsheared: PSD already, unchanged.
  x << 0, 0, 0, 3.6, 0, 0, 0.45, 2.5, 0;
  const test::Derivs e2 = element_derivs(x, kElement, m);
  const test::Derivs c2 = element_derivs(x, kElement, m, PsdProjection::Clamp);
  EXPECT_LT((e2.hessian - c2.hessian).norm(), 1e-12 * e2.hessian.norm());
}

// Homogeneous deformations of a rest triangle: the strains and tensions the
// header defines, in the course/wale frame.
TEST(MembraneEnergy, StressOfHomogeneousStretchAndShear) {
  KnitMaterial m = default_single_jersey();
  m.poisson_course_wale = 0.0;
  // Course stretch 10 %: nominal course tension = 60 N/m x 0.1.
  const Mat2 F2 = (Mat2() << 1.1, 0, 0, 1).finished();
  auto place = [&](const Mat2& F, const Vec2& p) { return Vec3((F * p).x(), (F * p).y(), 0); };
  const Vec2 P0(0, 0), P1(3.2, 0), P2(0.4, 2.2);
  MembraneStress s = membrane_stress(place(F2, P0), place(F2, P1), place(F2, P2), kElement, m);
  EXPECT_NEAR(s.course_strain, 0.1, 1e-12);
  EXPECT_NEAR(s.course_n_per_m, 6.0, 1e-9);
  EXPECT_NEAR(s.wale_n_per_m, 0.0, 1e-9);
  // Cauchy stress: tension per deformed width = nominal / (wale stretch 1) ... along x.
  EXPECT_NEAR(s.principal_max_n_per_m, 6.0, 1e-9);
  EXPECT_NEAR(s.principal_max_kpa, 6.0 / m.thickness_mm, 1e-9);
  // Into the stiff segment: strain 0.4 -> 0.3 x 60 + 0.1 x 1500.
  const Mat2 F3 = (Mat2() << 1.4, 0, 0, 1).finished();
  s = membrane_stress(place(F3, P0), place(F3, P1), place(F3, P2), kElement, m);
  EXPECT_NEAR(s.course_n_per_m, 18.0 + 150.0, 1e-9);
  // Simple shear by gamma: the shear tension is G gamma.
  const Mat2 F4 = (Mat2() << 1, 0.05, 0, 1).finished();
  s = membrane_stress(place(F4, P0), place(F4, P1), place(F4, P2), kElement, m);
  EXPECT_NEAR(s.shear_strain, 0.05, 1e-12);
  EXPECT_NEAR(s.shear_n_per_m, 20.0 * 0.05, 1e-9);
}

TEST(KnitMaterial, ValidationNamesTheField) {
  KnitMaterial m = default_single_jersey();
  validate_material(m);
  m.course.segments = {{0.0, 60.0}, {0.2, -1.0}};
  EXPECT_THROW(validate_material(m), InvalidInput);
  m = default_single_jersey();
  m.poisson_course_wale = 0.9;  // (0.9 x 150)^2 > 60 x 150: not convex
  try {
    validate_material(m);
    FAIL() << "no error";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("poisson_course_wale"), std::string::npos);
  }
  m = default_single_jersey();
  m.thickness_mm = 0;
  EXPECT_THROW(validate_material(m), InvalidInput);
}

TEST(KnitMaterial, CurveIsTheIntegralOfThePiecewiseTension) {
  const TensionCurve c{{{0.0, 60.0}, {0.3, 1500.0}}, 30.0};
  const CurveValue a = evaluate_curve(c, 0.5);
  EXPECT_NEAR(a.tension, 0.3 * 60 + 0.2 * 1500, 1e-12);
  EXPECT_NEAR(a.energy, 0.5 * 60 * 0.09 + 0.3 * 60 * 0.2 + 0.5 * 1500 * 0.04, 1e-12);
  EXPECT_EQ(a.slope, 1500.0);
  const CurveValue b = evaluate_curve(c, -0.1);
  EXPECT_NEAR(b.tension, -3.0, 1e-12);
  EXPECT_EQ(b.slope, 30.0);
  const CurveValue s = evaluate_curve(c, -0.5, true);
  EXPECT_NEAR(s.tension, -(0.3 * 60 + 0.2 * 1500), 1e-12);
  EXPECT_NEAR(s.energy, a.energy, 1e-12);
}

}  // namespace
}  // namespace knitforge
