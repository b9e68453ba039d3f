// Named poses (body/body_pose.h) on the generated body.
#include "knitforge/body/body_pose.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "knitforge/body/generated_body.h"
#include "knitforge/body/skin_body.h"
#include "knitforge/geometry/surface_checks.h"
#include "knitforge/util/errors.h"
#include "test_bodies.h"

namespace knitforge {
namespace {

TEST(BodyPose, APoseLowersBothArmsBy45Degrees) {
  const BodyModel& m = generated_body();
  const PosedBody t = pose_body(m, pose_preset(m, "t-pose"));
  const PosedBody a = pose_body(m, pose_preset(m, "a-pose"));
  for (const char* side : {"left", "right"}) {
    const int sh = m.joint_index(std::string(side) + "_shoulder");
    const int wr = m.joint_index(std::string(side) + "_wrist");
    const Vec3 arm_t = t.joints[wr] - t.joints[sh];
    const Vec3 arm_a = a.joints[wr] - a.joints[sh];
    EXPECT_NEAR(arm_t.z(), 0.0, 1e-9);  // horizontal in the T-pose
    EXPECT_NEAR(arm_a.norm(), arm_t.norm(), 1e-9);
    EXPECT_NEAR(std::atan2(-arm_a.z(), std::abs(arm_a.x())), std::numbers::pi / 4, 1e-9) << side;
    EXPECT_LT((a.joints[sh] - t.joints[sh]).norm(), 1e-9);  // the shoulder stays
  }
  // The posed surface is still a closed manifold (no skinning collapse).
  const SurfaceReport rep = validate_surface(posed_mesh(m, a));
  EXPECT_TRUE(rep.ok()) << rep.summary();
  EXPECT_EQ(rep.genus, 0);
}

TEST(BodyPose, UnknownNamesAreRefusedWithTheList) {
  // Names are checked before any model data is used: the tiny tube model
  // (not the generated body, 5 s to build under ASan).
  const BodyModel m = test::tube_body_model(false);
  try {
    pose_preset(m, "x-pose");
    FAIL() << "expected InvalidInput";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("a-pose"), std::string::npos) << e.what();
  }
  BodyParams p = zero_params(m);
  EXPECT_THROW(set_joint_rotation(m, p, "tail", Vec3::Zero()), InvalidInput);
}

}  // namespace
}  // namespace knitforge
