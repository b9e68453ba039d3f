// Finite-difference checks of the remaining energy terms (inertia, gravity,
// contact barrier, friction) and of the assembled mesh energy: every term's
// gradient and Hessian through the one shared check of finite_difference_check.h.

#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "finite_difference_check.h"
#include "knitforge/sim/bending_energy.h"
#include "knitforge/sim/contact_barrier.h"
#include "knitforge/sim/contact_candidates.h"
#include "knitforge/sim/contact_energy.h"
#include "knitforge/sim/friction_energy.h"
#include "knitforge/sim/inertia_energy.h"
#include "knitforge/sim/membrane_energy.h"
#include "knitforge/sim/sim_model.h"
#include "sim_test_meshes.h"

namespace knitforge {
namespace {

// A dense matrix from an EnergyEval's lower-triangle Hessian.
Eigen::MatrixXd dense_hessian(const EnergyEval& ev) {
  const Eigen::MatrixXd lower = Eigen::MatrixXd(ev.pattern->matrix(ev.hessian_values));
  Eigen::MatrixXd full = lower + lower.transpose();
  full.diagonal() -= lower.diagonal();
  return full;
}

// One large body triangle in z = 0 (normal +z).
KinematicBody plane_body() {
  TriMesh m;
  m.vertices = {{-10, -10, 0}, {10, -10, 0}, {0, 10, 0}};
  m.faces = {{0, 1, 2}};
  return KinematicBody(m);
}

TEST(ContactBarrier, DerivativesMatchFiniteDifferences) {
  for (double r : {1e-3, 0.05, 0.3, 0.7, 0.99}) {
    const BarrierValue b = contact_barrier(r);
    const double h = 1e-7 * r;
    const BarrierValue p = contact_barrier(r + h), m = contact_barrier(r - h);
    EXPECT_NEAR(b.db, (p.b - m.b) / (2 * h), 1e-6 * (std::abs(b.db) + 1)) << "r = " << r;
    EXPECT_NEAR(b.d2b, (p.db - m.db) / (2 * h), 1e-5 * (std::abs(b.d2b) + 1)) << "r = " << r;
    EXPECT_GT(b.b, 0.0);
    EXPECT_LT(b.db, 0.0);  // decreasing
    EXPECT_GT(b.d2b, 0.0);  // convex
  }
  // C² at r = 1 and infinite at contact.
  const BarrierValue near = contact_barrier(1 - 1e-9);
  EXPECT_NEAR(near.b, 0.0, 1e-15);
  EXPECT_NEAR(near.db, 0.0, 1e-12);
  EXPECT_EQ(contact_barrier(1.0).b, 0.0);
  EXPECT_TRUE(std::isinf(contact_barrier(0.0).b));
}

// The inertia + damping + gravity terms are quadratic/linear in x: exact
// derivatives, and stationarity is the backward-Euler update.
TEST(InertiaEnergy, DerivativesAndBackwardEulerStationarity) {
  SimModel model = build_sim_model(test::knit_sheet(2, 2, 1.25, 1.0), KnitParams{});
  const int n = model.num_vertices();
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1, 1);
  Eigen::VectorXd xn(3 * n), v(3 * n), x(3 * n);
  for (int k = 0; k < 3 * n; ++k) xn[k] = u(rng), v[k] = 100 * u(rng), x[k] = xn[k] + 0.5 * u(rng);
  const double h = 0.01;
  const Vec3 g(0, 0, -9810);
  const Eigen::VectorXd xt = predict_positions(xn, v, h, g);
  const auto pattern = build_hessian_pattern(model);
  auto f = [&](const Eigen::VectorXd& y) {
    EnergyEval ev(n, Derivatives::Hessian, pattern);
    add_inertia_energy(model, y, xt, xn, h, ev);
    add_gravity_energy(model, y, g, ev);
    return test::Derivs{ev.value, ev.gradient, dense_hessian(ev)};
  };
  test::expect_derivatives_match(f, x, 1e-4, 1e-6);
  // Zero gradient (without gravity potential, which predict_positions carries)
  // exactly at the damped backward-Euler update, per vertex:
  // m (x - x̃)/h² + c (x - x_n)/h = 0.
  EnergyEval ev(n, Derivatives::Gradient);
  Eigen::VectorXd xs(3 * n);
  for (int i = 0; i < n; ++i) {
    const double m = model.vertex_mass_kg[i] / (h * h), c = model.vertex_damping_kg_s[i] / h;
    xs.segment<3>(3 * i) = (m * xt.segment<3>(3 * i) + c * xn.segment<3>(3 * i)) / (m + c);
  }
  add_inertia_energy(model, xs, xt, xn, h, ev);
  EXPECT_LT(ev.gradient.cwiseAbs().maxCoeff(), 1e-12 * (1 + xs.cwiseAbs().maxCoeff()));
}

// Barrier of one vertex against the body, in each closest-point region of the
// face (interior, edge, corner): gradient and (unprojected) Hessian match
// finite differences; the force pushes away from the body.
class ContactRegion : public ::testing::TestWithParam<Vec3> {};

TEST_P(ContactRegion, PairBarrierDerivatives) {
  const KinematicBody body = plane_body();
  ContactParams params;
  params.distance_mm = 0.5;
  const Vec3 p0 = GetParam();
  const auto q = body.closest_point_within(p0, 1.0);
  ASSERT_TRUE(q.has_value());
  const ContactPair pair{0, *q};
  auto f = [&](const Eigen::VectorXd& y) {
    const PairBarrier b = pair_barrier(y, pair, body, 2.0, params, PsdProjection::None);
    return test::Derivs{b.value, b.gradient, b.hessian};
  };
  test::expect_derivatives_match(f, p0, 1e-7, 1e-5);
  const PairBarrier b = pair_barrier(p0, pair, body, 2.0, params, PsdProjection::None);
  EXPECT_GT(b.normal_force_mn, 0.0);
  EXPECT_LT(b.gradient.dot(p0 - q->where.point), 0.0);  // energy falls moving away
  // Projected: positive semi-definite.
  const PairBarrier bp = pair_barrier(p0, pair, body, 2.0, params, PsdProjection::Clamp);
  EXPECT_GE(Eigen::SelfAdjointEigenSolver<Mat3>(bp.hessian).eigenvalues().minCoeff(), -1e-9);
}

INSTANTIATE_TEST_SUITE_P(Regions, ContactRegion,
                         ::testing::Values(Vec3(0.3, 0.2, 0.21),     // face interior
                                           Vec3(0.1, -10.2, 0.25),   // beyond edge 0-1
                                           Vec3(10.15, -10.2, 0.2),  // beyond corner 1
                                           Vec3(2.0, 1.0, 0.05)));   // close to the face

// Friction potential of lagged pairs, both in the smoothed (static) zone
// and sliding: derivatives match; the force opposes the slip and is μλ when
// sliding faster than ε_v.
TEST(FrictionEnergy, DerivativesAndCoulombForce) {
  const KinematicBody body = plane_body();
  SimModel model = build_sim_model(test::knit_sheet(1, 1, 1.25, 1.0), KnitParams{});
  const int n = model.num_vertices();
  ContactParams params;
  params.friction = 0.4;
  params.friction_velocity_mm_s = 1.0;
  Eigen::VectorXd xn(3 * n);
  for (int i = 0; i < n; ++i) xn.segment<3>(3 * i) = model.rest_positions[i] + Vec3(0, 0, 0.2);
  const std::vector<ContactPair> contacts = find_contact_candidates(body, xn, params.distance_mm);
  ASSERT_EQ(contacts.size(), static_cast<size_t>(n));
  const std::vector<FrictionPair> pairs = build_friction_pairs(model, contacts, body, body, xn, params);
  ASSERT_EQ(pairs.size(), static_cast<size_t>(n));
  const double h = 0.01;  // ε = ε_v h = 0.01 mm
  const auto pattern = build_hessian_pattern(model);
  auto f = [&](const Eigen::VectorXd& y) {
    EnergyEval ev(n, Derivatives::Hessian, pattern);
    add_friction_energy(pairs, y, xn, h, params, ev);
    return test::Derivs{ev.value, ev.gradient, dense_hessian(ev)};
  };
  for (double slip : {0.003, 0.05}) {  // below and above ε
    Eigen::VectorXd x = xn;
    for (int i = 0; i < n; ++i) x.segment<3>(3 * i) += Vec3(slip * (1 + 0.3 * i), -0.5 * slip, 0.01 * i);
    test::expect_derivatives_match(f, x, 1e-7, 1e-4);
  }
  // Sliding along +x: force -μλ x̂ on each vertex.
  Eigen::VectorXd x = xn;
  for (int i = 0; i < n; ++i) x[3 * i] += 0.5;
  EnergyEval ev(n, Derivatives::Gradient);
  add_friction_energy(pairs, x, xn, h, params, ev);
  for (int i = 0; i < n; ++i) {
    const Vec3 g = ev.gradient.segment<3>(3 * i);
    EXPECT_NEAR(g.x(), params.friction * pairs[i].normal_force_mn, 1e-12);
    EXPECT_NEAR(g.y(), 0.0, 1e-12);
  }
}

// The whole assembled membrane + bending energy of a small deformed sheet:
// the sparse Hessian assembly and the gradient scatter agree with finite
// differences of the value (catches a wrong pattern index or a lost block).
TEST(AssembledEnergy, MeshGradientAndHessianMatchFiniteDifferences) {
  SimModel model = build_sim_model(test::knit_sheet(3, 2, 1.25, 1.0), KnitParams{});
  const int n = model.num_vertices();
  const Eigen::VectorXd x = test::perturbed(model, 11, 1.1, 0.15);
  const auto pattern = build_hessian_pattern(model);
  auto f = [&](const Eigen::VectorXd& y) {
    EnergyEval ev(n, Derivatives::Hessian, pattern);
    add_membrane_energy(model, y, PsdProjection::None, ev);
    return test::Derivs{ev.value, ev.gradient, dense_hessian(ev)};
  };
  test::expect_derivatives_match(f, x, 1e-6, 1e-5);
  // Bending, exact (unprojected) Hessian, deformed and flat.
  auto fb = [&](const Eigen::VectorXd& y) {
    EnergyEval ev(n, Derivatives::Hessian, pattern);
    add_bending_energy(model, y, ev, PsdProjection::None);
    return test::Derivs{ev.value, ev.gradient, dense_hessian(ev)};
  };
  test::expect_derivatives_match(fb, x, 1e-6, 1e-5);
  Eigen::VectorXd flat = test::flatten(model.rest_positions);
  test::expect_derivatives_match(fb, flat, 1e-6, 1e-5);
}

// A sheet large enough for the threaded path of add_element_energies()
// (2048 elements and more, in blocks of 8192): values and gradients are bit
// for bit those of a serial loop over the elements in order, for both
// terms, and so is the (serial) Hessian path.
TEST(AssembledEnergy, ThreadedSumsAreTheSerialLoopsBits) {
  const SimModel model = build_sim_model(test::knit_sheet(100, 45, 1.25, 1.0), KnitParams{});
  ASSERT_GT(model.elements.size(), 8192u);
  ASSERT_GE(model.hinges.size(), 2048u);
  const int n = model.num_vertices();
  const Eigen::VectorXd x = test::perturbed(model, 5, 1.05, 0.2);
  const auto pattern = build_hessian_pattern(model);
  for (const Derivatives what : {Derivatives::Value, Derivatives::Gradient, Derivatives::Hessian}) {
    // Some other term already in the evaluation: the sums add to it.
    EnergyEval membrane(n, what, pattern), bending(n, what, pattern), serial(n, what, pattern);
    for (EnergyEval* e : {&membrane, &bending, &serial}) {
      e->value = 0.1;
      if (what != Derivatives::Value) e->gradient.setConstant(0.01);
    }
    EnergyEval serial_bending = serial;
    add_membrane_energy(model, x, PsdProjection::Clamp, membrane);
    add_bending_energy(model, x, bending, PsdProjection::Clamp);
    const auto p = [&](int v) { return Vec3(x.segment<3>(3 * v)); };
    for (const MembraneElement& e : model.elements) {
      const ElementEnergy<3> el =
          membrane_element_energy(p(e.v[0]), p(e.v[1]), p(e.v[2]), e, model.materials[e.material], what);
      serial.value += el.value;
      if (what == Derivatives::Value) continue;
      for (int k = 0; k < 3; ++k) serial.add_gradient(e.v[k], el.gradient.segment<3>(3 * k));
      if (what == Derivatives::Hessian) serial.add_element_hessian<3>(e.v, el.hessian);
    }
    for (const BendingHinge& h : model.hinges) {
      const ElementEnergy<4> el =
          hinge_element_energy(p(h.v[0]), p(h.v[1]), p(h.v[2]), p(h.v[3]), h, what, PsdProjection::Clamp);
      serial_bending.value += el.value;
      if (what == Derivatives::Value) continue;
      for (int k = 0; k < 4; ++k) serial_bending.add_gradient(h.v[k], el.gradient.segment<3>(3 * k));
      if (what == Derivatives::Hessian) serial_bending.add_element_hessian<4>(h.v, el.hessian);
    }
    EXPECT_EQ(membrane.value, serial.value);
    EXPECT_EQ(bending.value, serial_bending.value);
    EXPECT_TRUE(membrane.gradient == serial.gradient);
    EXPECT_TRUE(bending.gradient == serial_bending.gradient);
    EXPECT_TRUE(membrane.hessian_values == serial.hessian_values);
    EXPECT_TRUE(bending.hessian_values == serial_bending.hessian_values);
  }
}

}  // namespace
}  // namespace knitforge
