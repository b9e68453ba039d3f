// Body parameters as JSON (body/body_json.h).
#include "knitforge/body/body_json.h"

#include <gtest/gtest.h>

#include "body/test_bodies.h"
#include "knitforge/util/errors.h"

namespace knitforge {
namespace {

TEST(BodyJson, RoundTripsParameters) {
  const BodyModel m = test::tube_body_model(false);
  BodyParams p = zero_params(m);
  p.shape << 1.25, -3.5;
  p.joint_rotations[1] = {0.1, -0.2, 0.3};
  p.translation_mm = {4, 5, 6};
  const nlohmann::json j = body_params_to_json(m, p);
  EXPECT_EQ(j["model"], "test-tube");
  EXPECT_EQ(j["shape"]["inflate"], -3.5);
  const BodyParams q = body_params_from_json(m, nlohmann::json::parse(j.dump()), "p.json");
  EXPECT_EQ(q.shape, p.shape);
  EXPECT_EQ(q.joint_rotations, p.joint_rotations);
  EXPECT_EQ(q.translation_mm, p.translation_mm);
}

TEST(BodyJson, TheReportKeysOfBodyMakeAndBodyFitAreIgnoredOnReading) {
  const BodyModel m = test::tube_body_model(false);
  const auto j = nlohmann::json::parse(R"({"shape": {"inflate": 2}, "measurements_mm": {"stature": 1},
    "joints_mm": {"tip": [1, 2, 3]}, "targets_mm": {}, "max_measurement_error_mm": 0, "newton_iterations": 3,
    "vertex_parts": ["torso"], "fit": {"rms_mm": 1}})");
  const BodyParams p = body_params_from_json(m, j, "params.json");
  EXPECT_EQ(p.shape(1), 2.0);
  EXPECT_EQ(p.joint_rotations[2], Vec3::Zero());
}

TEST(BodyJson, DegreesAndMissingKeysDefaultToZero) {
  const BodyModel m = test::tube_body_model(false);
  const auto j = nlohmann::json::parse(R"({"rotations_deg": {"tip": [0, 90, 0]}})");
  const BodyParams p = body_params_from_json(m, j, "pose.json");
  EXPECT_NEAR(p.joint_rotations[2].y(), 1.5707963267948966, 1e-15);
  EXPECT_EQ(p.joint_rotations[0], Vec3::Zero());
  EXPECT_EQ(p.shape, Eigen::VectorXd::Zero(2));
}

TEST(BodyJson, ErrorsNameTheFileAndTheKey) {
  const BodyModel m = test::tube_body_model(false);
  auto expect_error = [&](const char* text, const char* needle) {
    try {
      body_params_from_json(m, nlohmann::json::parse(text), "pose.json");
      FAIL() << "expected InvalidInput for " << text;
    } catch (const InvalidInput& e) {
      const std::string msg = e.what();
      EXPECT_NE(msg.find("pose.json"), std::string::npos) << msg;
      EXPECT_NE(msg.find(needle), std::string::npos) << msg;
    }
  };
  expect_error(R"({"rotations_rad": {"knee": [0, 0, 0]}})", "knee");
  expect_error(R"({"rotations_rad": {"tip": [0, 0]}})", "three numbers");
  expect_error(R"({"shape": {"height": 3}})", "height");
  expect_error(R"({"model": "smpl"})", "smpl");
  expect_error(R"({"pose": {}})", "pose");
  expect_error(R"({"joints": {}})", "joints");
  expect_error(R"([1, 2])", "object");
}

}  // namespace
}  // namespace knitforge
