// Fitting the body model to a scan (eq. 5.1) and to a partial cloud (eq. 5.4)
// (body/fit_body.h): a body made with other measurements, another pose and a
// translation, meshed at another resolution (so no vertex correspondence),
// with noise; the fit recovers its measurements.
#include "knitforge/body/fit_body.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <random>

#include "knitforge/body/body_measurements.h"
#include "knitforge/body/body_pose.h"
#include "knitforge/body/generated_body.h"
#include "knitforge/body/skin_body.h"
#include "knitforge/evaluate/surface_distance.h"
#include "knitforge/util/errors.h"
#include "test_bodies.h"

namespace knitforge {
namespace {

struct Target {
  BodyParams params;
  TriMesh scan;              // the posed body at another resolution, with noise
  BodyMeasurements measured;  // of the default model with the target's shape
};

const BodyModel& coarse_model() {
  static const BodyModel other = [] {
    GeneratedBodyOptions coarse;
    coarse.edge_length = 22.0;
    return make_generated_body(coarse);
  }();
  return other;
}

TriMesh noisy_scan(const BodyParams& p, unsigned seed) {
  const BodyModel& other = coarse_model();
  TriMesh scan = posed_mesh(other, pose_body(other, p));
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> noise(-2.0, 2.0);
  for (Vec3& v : scan.vertices) v += Vec3(noise(rng), noise(rng), noise(rng));
  return scan;
}

// Stature +40, chest +50, waist -30, hip +25, thigh +15, arm -20 mm.
Eigen::VectorXd target_shape() {
  Eigen::VectorXd s = Eigen::VectorXd::Zero(generated_body().num_shapes());
  auto set = [&](Measurement q, double v) { s(static_cast<int>(q)) = v; };
  set(Measurement::Stature, 40.0);
  set(Measurement::ChestGirth, 50.0);
  set(Measurement::WaistGirth, -30.0);
  set(Measurement::HipGirth, 25.0);
  set(Measurement::ThighGirth, 15.0);
  set(Measurement::ArmLength, -20.0);
  return s;
}

const Target& target() {
  static const Target t = [] {
    const BodyModel& m = generated_body();
    Target out;
    out.params = pose_preset(m, "a-pose");
    out.params.shape = target_shape();
    set_joint_rotation(m, out.params, "left_elbow", {0, 0, -0.2});
    set_joint_rotation(m, out.params, "right_knee", {0.15, 0, 0});
    set_joint_rotation(m, out.params, "pelvis", {0, 0, 0.1});
    out.params.translation_mm = {15, -20, 10};
    out.scan = noisy_scan(out.params, 42);
    out.measured = measure_body(m, shape_body(m, out.params.shape));
    return out;
  }();
  return t;
}

void expect_measurements(const BodyModel& m, const BodyParams& fitted, const BodyMeasurements& want, double tol) {
  const BodyMeasurements got = measure_body(m, shape_body(m, fitted.shape));
  for (int k = 0; k < kNumMeasurements; ++k) {
    const auto q = static_cast<Measurement>(k);
    // The head, hands and feet have zero weight in eq. 5.1; the head girth
    // is not fitted.
    if (q == Measurement::HeadGirth) continue;
    std::printf("  %-18s want %7.1f got %7.1f (%+.1f mm)\n", measurement_info(q).key, want[k], got[k], got[k] - want[k]);
    EXPECT_NEAR(got[k], want[k], tol) << measurement_info(q).key;
  }
}

TEST(FitBody, TemplateToScanRecoversShapePoseAndTranslation) {
  const BodyModel& m = generated_body();
  const Target& t = target();
  const BodyParams init = pose_preset(m, "a-pose");
  const auto start = std::chrono::steady_clock::now();
  const BodyFitResult r = fit_body(m, t.scan, init);
  const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("eq. 5.1: rms %.2f -> %.2f mm in %d iterations, %.1f s, converged %d\n", r.initial_rms_mm, r.rms_mm,
              r.iterations, secs, r.converged);
  EXPECT_LT(r.rms_mm, 3.0);
  EXPECT_LT(r.rms_mm, 0.2 * r.initial_rms_mm);
  EXPECT_LT((r.params.translation_mm - t.params.translation_mm).norm(), 10.0);
  expect_measurements(m, r.params, t.measured, 10.0);
  // The objective never increases.
  for (size_t i = 1; i < r.rms_history_mm.size(); ++i) EXPECT_LE(r.rms_history_mm[i], r.rms_history_mm[i - 1] + 0.05);
}

TEST(FitBody, ScanToTemplateFitsAPartialCloud) {
  // The camera sees the front: the 30 % of the points farthest back are gone.
  const BodyModel& m = generated_body();
  const Target& t = target();
  std::vector<double> ys;
  for (const Vec3& v : t.scan.vertices) ys.push_back(v.y());
  std::vector<double> sorted = ys;
  std::sort(sorted.begin(), sorted.end());
  const double cut = sorted[static_cast<size_t>(0.7 * static_cast<double>(sorted.size()))];
  TriMesh cloud;
  for (const Vec3& v : t.scan.vertices)
    if (v.y() < cut) cloud.vertices.push_back(v);
  BodyFitOptions o;
  o.direction = BodyFitDirection::ScanToTemplate;
  const BodyFitResult r = fit_body(m, cloud, pose_preset(m, "a-pose"), o);
  std::printf("eq. 5.4: rms %.2f -> %.2f mm in %d iterations, converged %d\n", r.initial_rms_mm, r.rms_mm,
              r.iterations, r.converged);
  EXPECT_LT(r.rms_mm, 3.0);
  // Point-to-surface distance of the cloud to the fitted body, independently.
  const std::vector<double> d = distances_to_surface(posed_mesh(m, r.posed), cloud.vertices);
  double sq = 0.0;
  for (double x : d) sq += x * x;
  EXPECT_NEAR(std::sqrt(sq / static_cast<double>(d.size())), r.rms_mm, 0.05);
  expect_measurements(m, r.params, t.measured, 10.0);
}

TEST(FitBody, MultistartFitsAFarPose) {
  // The relaxed pose (arms 20 degrees lower than the initial a-pose, elbows
  // and knees bent). Here eq. 5.1 alone finds it and both directions alone
  // stretch an arm to the scan's hand; on the 8 mm scan of docs/bodies.md it
  // is the other way round. The multistart keeps the better by both
  // distances. Its runs 0 and 2 are exactly fit_body() with eq. 5.1 and with
  // both directions from the initial pose (deterministic), so their
  // symmetric rms (run_rms_mm) stands for those single fits, which this test
  // ran separately before (5 fits instead of 3: 100 s under ASan).
  const BodyModel& m = generated_body();
  BodyParams p = pose_preset(m, "relaxed");
  p.shape = target_shape();
  const TriMesh scan = noisy_scan(p, 7);
  const BodyMeasurements want = measure_body(m, shape_body(m, p.shape));
  const BodyParams init = pose_preset(m, "a-pose");
  BodyFitOptions o;
  o.max_iterations = 25;
  const BodyFitResult best = fit_body_multistart(m, scan, init, o);
  ASSERT_EQ(best.run_rms_mm.size(), 5u);  // runs 3, 4 start from the scan's girths
  std::printf("relaxed from a-pose: symmetric rms of eq. 5.1 %.2f mm, both from it %.2f mm, both directions %.2f mm; "
              "multistart chose run %d, %.2f mm, %d iterations in all\n",
              best.run_rms_mm[0], best.run_rms_mm[1], best.run_rms_mm[2], best.chosen_run, best.rms_mm,
              best.iterations);
  EXPECT_LT(best.rms_mm, 3.0);
  for (double r : best.run_rms_mm) EXPECT_LE(best.rms_mm, r + 1e-12);
  EXPECT_EQ(best.rms_mm, best.run_rms_mm[static_cast<size_t>(best.chosen_run)]);
  EXPECT_NEAR(best.rms_mm, symmetric_rms_mm(m, scan, best.params, o), 1e-9);
  // The runs differ: the choice matters (one of the single fits is worse).
  EXPECT_GT(std::max(best.run_rms_mm[0], best.run_rms_mm[2]), 1.5 * best.rms_mm);
  expect_measurements(m, best.params, want, 10.0);
}

// A plus-size body, relaxed: 160 cm, chest 110, waist 105 (1.3 x the
// model's), hip 112 cm. From the default shape every run keeps the initial
// arms inside the wide torso (rms about 5 mm, chest 113 cm); the runs that
// start from the scan's own girths find it. (The multistart itself is not
// rerun here: five fits of this body take two minutes under ASan.)
TEST(FitBody, AWideBodyIsFoundFromTheScansGirths) {
  const BodyModel& m = generated_body();
  MeasurementTargets t;
  t.mm[static_cast<size_t>(Measurement::Stature)] = 1600.0;
  t.mm[static_cast<size_t>(Measurement::ChestGirth)] = 1100.0;
  t.mm[static_cast<size_t>(Measurement::WaistGirth)] = 1050.0;
  t.mm[static_cast<size_t>(Measurement::HipGirth)] = 1120.0;
  BodyParams p = pose_preset(m, "relaxed");
  p.shape = shape_from_measurements(m, t).shape;
  const TriMesh scan = noisy_scan(p, 11);
  const BodyMeasurements want = measure_body(m, shape_body(m, p.shape));

  // The starting shape: near the truth (a start, not a measurement: the
  // chest section at the model's landmark height is 6 cm short here).
  const std::optional<Eigen::VectorXd> start = shape_from_scan_girths(m, scan);
  ASSERT_TRUE(start.has_value());
  const BodyMeasurements got = measure_body(m, shape_body(m, *start));
  for (Measurement q : {Measurement::Stature, Measurement::ChestGirth, Measurement::WaistGirth, Measurement::HipGirth}) {
    std::printf("  start %-12s want %7.1f got %7.1f\n", measurement_info(q).key, want[static_cast<size_t>(q)],
                got[static_cast<size_t>(q)]);
    EXPECT_NEAR(got[static_cast<size_t>(q)], want[static_cast<size_t>(q)], 80.0) << measurement_info(q).key;
  }

  // Runs 3 and 4 of fit_body_multistart() (whose choice among its runs
  // MultistartFitsAFarPose tests; the whole multistart chose run 4 here,
  // against 12.6, 8.4, 5.0 mm for runs 0-2: 1.12 mm, measured 2026-12-07).
  BodyFitOptions one, both;
  one.direction = BodyFitDirection::TemplateToScan;
  both.direction = BodyFitDirection::Both;
  BodyParams wide = pose_preset(m, "a-pose");
  wide.shape = *start;
  const BodyFitResult first = fit_body(m, scan, place_on_scan(m, wide, scan), one);
  const BodyFitResult fit = fit_body(m, scan, first.params, both);
  const double rms = symmetric_rms_mm(m, scan, fit.params);
  std::printf("wide body from its girths: symmetric rms %.2f mm\n", rms);
  EXPECT_LT(rms, 1.5);  // 2 mm uniform noise
  expect_measurements(m, fit.params, want, 10.0);
}

TEST(FitBody, AModelWithoutMeasurementShapesHasNoGirthStart) {
  const BodyModel tube = test::tube_body_model(false);
  EXPECT_FALSE(shape_from_scan_girths(tube, posed_mesh(tube, pose_body(tube, zero_params(tube)))).has_value());
}

TEST(FitBody, EvolutionStrategyLowersTheSameObjectiveFarMoreSlowly) {
  // The seed's gradient-free (1+1)-ES and Gauss-Newton on one small fit:
  // the tiny tube model bent at its middle joint, shifted and stretched; the
  // scan is that posed tube, the start bent 0.15 rad less, unshifted and
  // unshaped. Gauss-Newton finds it exactly in tens of evaluations; the ES
  // lowers the same cost from 3 mm rms to a few tenths in thousands
  // (measured 0.27 mm after 6000; docs/bodies.md compares the two on
  // whole bodies).
  const BodyModel m = test::tube_body_model(false);
  BodyParams truth = zero_params(m);
  truth.translation_mm = {4.0, -3.0, 2.0};
  truth.joint_rotations[1] = {0.0, 0.0, 0.35};
  truth.shape << 0.4, -0.3;
  const TriMesh scan = posed_mesh(m, pose_body(m, truth));
  BodyParams start = zero_params(m);
  start.joint_rotations[1] = {0.0, 0.0, 0.2};
  BodyFitOptions o;
  o.pose_prior = 0.0;
  o.shape_prior = 0.0;
  const BodyFitResult gn = fit_body(m, scan, start, o);
  o.optimizer = BodyFitOptimizer::EvolutionStrategy;
  o.max_evaluations = 6000;
  const BodyFitResult es = fit_body(m, scan, start, o);
  std::printf("tube: ES rms %.3f -> %.4f mm in %d evaluations (converged %d); GN %.6f mm in %d evaluations\n",
              es.initial_rms_mm, es.rms_mm, es.evaluations, es.converged, gn.rms_mm, gn.evaluations);
  EXPECT_LT(gn.rms_mm, 1e-3);
  EXPECT_LT((gn.params.translation_mm - truth.translation_mm).norm(), 1e-2);
  EXPECT_EQ(es.initial_rms_mm, gn.initial_rms_mm);
  EXPECT_GT(es.initial_rms_mm, 2.0);
  EXPECT_LT(es.rms_mm, 0.15 * es.initial_rms_mm);
  EXPECT_GT(es.rms_mm, gn.rms_mm);
  EXPECT_LE(es.evaluations, o.max_evaluations + 2);
  EXPECT_GT(es.evaluations, 20 * gn.evaluations);
  ASSERT_EQ(es.rms_history_mm.size(), 1u);
  EXPECT_EQ(es.rms_history_mm[0], es.rms_mm);
  // Deterministic for a seed; another seed takes another path.
  o.max_evaluations = 300;
  const BodyFitResult a = fit_body(m, scan, start, o);
  const BodyFitResult b = fit_body(m, scan, start, o);
  EXPECT_EQ(a.rms_mm, b.rms_mm);
  EXPECT_EQ(a.params.translation_mm, b.params.translation_mm);
  EXPECT_LT(a.rms_mm, a.initial_rms_mm);
  o.seed = 9;
  EXPECT_NE(fit_body(m, scan, start, o).rms_mm, a.rms_mm);
  o.max_evaluations = 0;
  EXPECT_THROW(fit_body(m, scan, start, o), InvalidInput);
}

TEST(FitBody, RejectsBadInput) {
  // The checks do not depend on the model: the tiny tube (not the generated
  // body, 5 s to build under ASan).
  const BodyModel m = test::tube_body_model(false);
  TriMesh cloud;
  cloud.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  EXPECT_THROW(fit_body(m, cloud, zero_params(m)), InvalidInput);  // eq. 5.1 needs faces
  EXPECT_THROW(fit_body(m, TriMesh{}, zero_params(m)), InvalidInput);
  BodyFitOptions o;
  o.max_iterations = 0;
  cloud.faces = {{0, 1, 2}};
  EXPECT_THROW(fit_body(m, cloud, zero_params(m), o), InvalidInput);
  BodyParams wrong = zero_params(m);
  wrong.shape.resize(3);
  EXPECT_THROW(fit_body(m, cloud, wrong), InvalidInput);
}

}  // namespace
}  // namespace knitforge
