// Static validation against analytic answers: uniaxial stretch along courses
// and along wales (the orthotropic, piecewise-linear material with its
// Poisson coupling), a pure-shear patch test, and a cantilever strip's
// small-deflection tip displacement q L⁴ / (8 D), converging as the mesh is
// refined. Every solve must report convergence (largest free force below
// the tolerance).

#include <cmath>
#include <functional>

#include <gtest/gtest.h>

#include "knitforge/sim/bending_energy.h"
#include "knitforge/sim/membrane_energy.h"
#include "knitforge/sim/newton_solve.h"
#include "knitforge/sim/step_simulation.h"
#include "sim_test_meshes.h"

namespace knitforge {
namespace {

// Root of a monotone increasing f on [lo, hi] by bisection.
double bisect(const std::function<double(double)>& f, double lo, double hi) {
  for (int k = 0; k < 200; ++k) {
    const double mid = 0.5 * (lo + hi);
    (f(mid) > 0 ? hi : lo) = mid;
  }
  return 0.5 * (lo + hi);
}

// The homogeneous answer of a strip under nominal tension T (N/m) along
// one material direction with the other direction traction free:
//   Φ_a'(ε_a) + c ε_b = T,   Φ_b'(ε_b) + c ε_a = 0,   c = ν k_w.
struct StripAnswer {
  double along = 0.0, across = 0.0;
};
StripAnswer strip_answer(const TensionCurve& along, const TensionCurve& across, double c, double T) {
  auto across_of = [&](double ea) {
    return bisect([&](double eb) { return evaluate_curve(across, eb).tension + c * ea; }, -0.9, 5.0);
  };
  const double ea = bisect([&](double e) { return evaluate_curve(along, e).tension + c * across_of(e) - T; }, -0.9, 5.0);
  return {ea, across_of(ea)};
}

struct StretchCase {
  bool along_courses;
  double tension_n_per_m;
};

class UniaxialStretch : public ::testing::TestWithParam<StretchCase> {};

// A 6 x 4 sheet of 1.25 x 1 mm stitches, held on one edge (normal coordinate
// only, plus one corner in the other in-plane direction; z fixed: a planar
// test), pulled on the opposite edge by consistent nodal loads.
TEST_P(UniaxialStretch, MatchesTheOrthotropicAnswer) {
  const StretchCase c = GetParam();
  KnitParams p;
  p.stitch_width = 1.25;
  p.stitch_height = 1.0;
  const int cols = 6, rows = 4;
  const SimModel model = build_sim_model(test::knit_sheet(cols, rows, p.stitch_width, p.stitch_height), p);
  const KnitMaterial& m = model.materials[0];
  const int n = model.num_vertices();
  auto id = [&](int i, int j) { return j * (cols + 1) + i; };
  const int a = c.along_courses ? 0 : 1;  // the pulled coordinate
  const int b = 1 - a;
  std::vector<char> fixed(3 * n, 0);
  Eigen::VectorXd load = Eigen::VectorXd::Zero(3 * n);
  for (int j = 0; j <= rows; ++j) {
    for (int i = 0; i <= cols; ++i) {
      const int v = id(i, j);
      fixed[3 * v + 2] = 1;
      const bool held = c.along_courses ? i == 0 : j == 0;
      const bool pulled = c.along_courses ? i == cols : j == rows;
      if (held) fixed[3 * v + a] = 1;
      if (pulled) {
        const bool corner = c.along_courses ? (j == 0 || j == rows) : (i == 0 || i == cols);
        const double spacing = c.along_courses ? p.stitch_height : p.stitch_width;
        load[3 * v + a] = c.tension_n_per_m * spacing * (corner ? 0.5 : 1.0);
      }
    }
  }
  fixed[3 * id(0, 0) + b] = 1;
  const auto pattern = build_hessian_pattern(model);
  const EvaluateEnergy evaluate = [&](const Eigen::VectorXd& y, Derivatives what) {
    EnergyEval ev(n, what, what == Derivatives::Hessian ? pattern : nullptr);
    add_membrane_energy(model, y, PsdProjection::Clamp, ev);
    ev.value -= load.dot(y);
    if (ev.wants_gradient()) ev.gradient -= load;
    return ev;
  };
  NewtonOptions opt;
  opt.force_tolerance_mn = 1e-10;
  SparseSolver solver;
  const NewtonResult r = newton_solve(test::flatten(model.rest_positions), fixed, evaluate,
                                      [](const Eigen::VectorXd&, const Eigen::VectorXd&) { return 1.0; }, opt, solver);
  ASSERT_TRUE(r.converged) << r.stop_reason << ", max force " << r.max_force_mn << " mN";
  EXPECT_LE(r.max_force_mn, 1e-10);
  EXPECT_LT(r.iterations, 40);
  const double c12 = m.poisson_course_wale * m.wale.initial_stiffness();
  const StripAnswer want = c.along_courses ? strip_answer(m.course, m.wale, c12, c.tension_n_per_m)
                                           : strip_answer(m.wale, m.course, c12, c.tension_n_per_m);
  const double L = (c.along_courses ? cols * p.stitch_width : rows * p.stitch_height);
  const double H = (c.along_courses ? rows * p.stitch_height : cols * p.stitch_width);
  // Strains from the corner positions: far edge minus near edge.
  const int far_a = c.along_courses ? id(cols, 0) : id(0, rows);
  const int far_b = c.along_courses ? id(0, rows) : id(cols, 0);
  const double ea = (r.x[3 * far_a + a] - r.x[3 * id(0, 0) + a]) / L - 1.0;
  const double eb = (r.x[3 * far_b + b] - r.x[3 * id(0, 0) + b]) / H - 1.0;
  EXPECT_NEAR(ea, want.along, 1e-8);
  EXPECT_NEAR(eb, want.across, 1e-8);
  // And every element carries the same stress: the loaded tension.
  for (const MembraneElement& e : model.elements) {
    const MembraneStress s = membrane_stress(r.x.segment<3>(3 * e.v[0]), r.x.segment<3>(3 * e.v[1]),
                                             r.x.segment<3>(3 * e.v[2]), e, m);
    EXPECT_NEAR(c.along_courses ? s.course_n_per_m : s.wale_n_per_m, c.tension_n_per_m, 1e-7);
    EXPECT_NEAR(c.along_courses ? s.wale_n_per_m : s.course_n_per_m, 0.0, 1e-7);
    EXPECT_NEAR(s.shear_n_per_m, 0.0, 1e-7);
  }
}

// Soft (first segment) and stiffened (past the curve's knee) loads; along
// courses 20 N/m passes the knee at 30 % strain, along wales 40 N/m passes 15 %.
INSTANTIATE_TEST_SUITE_P(Loads, UniaxialStretch,
                         ::testing::Values(StretchCase{true, 5.0}, StretchCase{true, 20.0}, StretchCase{false, 5.0},
                                           StretchCase{false, 40.0}));

TEST(UniaxialStretch, StiffLoadsPassTheKnee) {
  // The instantiation above really exercises the stiff segment.
  const KnitMaterial m = default_single_jersey();
  const double c12 = m.poisson_course_wale * m.wale.initial_stiffness();
  EXPECT_GT(strip_answer(m.course, m.wale, c12, 20.0).along, m.course.segments[1].first);
  EXPECT_GT(strip_answer(m.wale, m.course, c12, 40.0).along, m.wale.segments[1].first);
  EXPECT_LT(strip_answer(m.course, m.wale, c12, 5.0).along, m.course.segments[1].first);
}

// Patch test: the boundary of a sheet placed by a homogeneous pure shear
// (course and wale line elements turned towards each other by ±a, lengths
// kept), the interior free in its plane (z held: a sheet in pure shear is
// compressed along one diagonal and would wrinkle out of plane): the
// equilibrium is the homogeneous map and the energy is the area times
// Φ_s(sin 2a).
TEST(PureShear, HomogeneousPatchAndEnergy) {
  KnitParams p;
  p.stitch_width = 1.25;
  p.stitch_height = 1.0;
  const int cols = 6, rows = 5;
  const SimModel model = build_sim_model(test::knit_sheet(cols, rows, p.stitch_width, p.stitch_height), p);
  const int n = model.num_vertices();
  const double ang = 0.2;
  Mat3 F = Mat3::Identity();
  F(0, 0) = std::cos(ang);
  F(1, 0) = std::sin(ang);
  F(0, 1) = std::sin(ang);
  F(1, 1) = std::cos(ang);
  Eigen::VectorXd want(3 * n);
  for (int v = 0; v < n; ++v) want.segment<3>(3 * v) = F * model.rest_positions[v];
  // Interior start: the homogeneous map disturbed in-plane by up to 0.2 mm.
  Eigen::VectorXd x0 = want;
  for (int v = 0; v < n; ++v) {
    x0[3 * v] += 0.2 * std::sin(1.7 * v);
    x0[3 * v + 1] += 0.2 * std::cos(2.3 * v);
  }
  std::vector<char> fixed(3 * n, 0);
  for (int j = 0; j <= rows; ++j) {
    for (int i = 0; i <= cols; ++i) {
      const int v = j * (cols + 1) + i;
      fixed[3 * v + 2] = 1;
      if (i == 0 || j == 0 || i == cols || j == rows) {
        for (int k = 0; k < 3; ++k) fixed[3 * v + k] = 1;
        x0.segment<3>(3 * v) = want.segment<3>(3 * v);
      }
    }
  }
  const auto pattern = build_hessian_pattern(model);
  const EvaluateEnergy evaluate = [&](const Eigen::VectorXd& y, Derivatives what) {
    EnergyEval ev(n, what, what == Derivatives::Hessian ? pattern : nullptr);
    add_membrane_energy(model, y, PsdProjection::Clamp, ev);
    add_bending_energy(model, y, ev);
    return ev;
  };
  NewtonOptions opt;
  opt.force_tolerance_mn = 1e-10;
  SparseSolver solver;
  const NewtonResult r = newton_solve(x0, fixed, evaluate,
                                      [](const Eigen::VectorXd&, const Eigen::VectorXd&) { return 1.0; }, opt, solver);
  ASSERT_TRUE(r.converged) << r.stop_reason << ", max force " << r.max_force_mn << " mN";
  EXPECT_LT((r.x - want).cwiseAbs().maxCoeff(), 1e-7);
  const double area = cols * rows * p.stitch_width * p.stitch_height;
  const double gamma = std::sin(2 * ang);
  const KnitMaterial& m = model.materials[0];
  EXPECT_NEAR(elastic_energy(model, r.x), area * evaluate_curve(m.shear, gamma, true).energy, 1e-9 * r.energy);
  for (const MembraneElement& e : model.elements) {
    const MembraneStress s =
        membrane_stress(r.x.segment<3>(3 * e.v[0]), r.x.segment<3>(3 * e.v[1]), r.x.segment<3>(3 * e.v[2]), e, m);
    EXPECT_NEAR(s.shear_strain, gamma, 1e-9);
    EXPECT_NEAR(s.shear_n_per_m, evaluate_curve(m.shear, gamma, true).tension, 1e-7);
    EXPECT_NEAR(s.course_strain, 0.0, 1e-9);
    EXPECT_NEAR(s.wale_strain, 0.0, 1e-9);
  }
}

// Cantilever: a strip clamped at one end (its first two columns of vertices
// held) sagging under its own weight; small-deflection beam theory gives the
// tip deflection δ = q L⁴ / (8 D) for the load q per area and the rigidity D
// per width along the strip. The membrane is made nearly inextensible.
double cantilever_tip_error(double spacing_mm) {
  const double length = 20.0;
  const test::ClampedStrip strip = test::clamped_strip(spacing_mm, 80.0, length);
  const SimModel& model = strip.model;
  const KnitMaterial& m = model.materials[0];
  SimWorkspace ws(model);
  EquilibriumOptions o;
  const double g = 9810.0;
  o.gravity_mm_s2 = Vec3(0, 0, -g);
  o.newton.force_tolerance_mn = 1e-8;  // 1e-4 of a vertex's weight
  const EquilibriumResult r = solve_equilibrium(ws, test::flatten(model.rest_positions), nullptr, o);
  EXPECT_TRUE(r.converged) << r.stop_reason << " after " << r.iterations << " iterations, force " << r.max_force_mn;
  const double tip = strip.tip_height_mm(r.positions_mm);
  const double q = areal_density_kg_mm2(m) * g;  // mN/mm²
  const double want = -q * std::pow(length, 4) / (8.0 * m.bending_course_un_m);
  std::printf("spacing %.2f: tip %.5f mm, beam theory %.5f mm, %d iterations, force %.3g mN\n", spacing_mm, tip, want, r.iterations, r.max_force_mn);
  return std::abs(tip - want) / std::abs(want);
}

TEST(Cantilever, SmallDeflectionMatchesBeamTheoryAndConverges) {
  const double coarse = cantilever_tip_error(1.0);
  const double fine = cantilever_tip_error(0.5);
  // First-order convergence (a discrete beam with hinges at the nodes and
  // lumped loads is 1 + 2.05/N of the beam answer: 10 % and 5 % here).
  EXPECT_LT(fine, 0.65 * coarse);
  EXPECT_LT(fine, 0.08);
  std::printf("cantilever tip error: %.4f (1 mm mesh), %.4f (0.5 mm mesh)\n", coarse, fine);
}

}  // namespace
}  // namespace knitforge
