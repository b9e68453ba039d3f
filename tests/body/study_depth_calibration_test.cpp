#include "knitforge/body/study_depth_calibration.h"

#include <gtest/gtest.h>

#include <cmath>

#include "knitforge/util/errors.h"

using namespace knitforge;

TEST(StudyDepthCalibration, CapturesAreRoundedToTheCamerasUnitsAndSeeTheBoard) {
  const DepthRig rig = seed_depth_rig();
  const std::vector<RigidTransform> poses = random_board_poses(rig, 2, 3);
  const std::vector<BoardCapture> caps = synthetic_board_captures(rig, poses, {}, {1.0, 0.0, 7});
  ASSERT_EQ(caps.size(), 2u);
  for (const BoardCapture& c : caps)
    for (const DepthImage* img : {&c.image1, &c.image2}) {
      size_t seen = 0;
      for (double z : img->depth_mm) {
        EXPECT_EQ(z, std::round(z));  // whole millimetres (1 mm units)
        seen += z > 0.0 ? 1 : 0;
      }
      // A 600 x 450 mm board about 1 m from a 280 px camera, tilted by up
      // to 40°: 168 x 126 px face on, over 10,000 pixels in every image.
      EXPECT_GT(seen, 10000u);
      EXPECT_LT(seen, 168u * 126u * 3u / 2u);
    }
  // The noise differs from image to image (seed + 2i, + 2i + 1).
  EXPECT_NE(caps[0].image1.depth_mm, synthetic_board_captures(rig, poses, {}, {1.0, 0.0, 8})[0].image1.depth_mm);
}

TEST(StudyDepthCalibration, TheErrorGrowsWithTheNoiseAndMeetsTheBarAtOneMillimetre) {
  DepthCalibrationStudyOptions o;
  o.noise_mm = {0.0, 1.0, 6.0};
  o.poses = {3, 6};
  o.runs = 2;
  const std::vector<DepthCalibrationStudyRow> rows = study_depth_calibration(o);
  ASSERT_EQ(rows.size(), 6u);
  for (size_t i = 0; i < rows.size(); ++i) {
    EXPECT_EQ(rows[i].noise_mm, o.noise_mm[i / 2]);
    EXPECT_EQ(rows[i].poses, o.poses[i % 2]);
    EXPECT_EQ(rows[i].runs + rows[i].failed, 2);
    EXPECT_LE(rows[i].rotation_mean_deg, rows[i].rotation_max_deg);
    EXPECT_LE(rows[i].translation_mean_mm, rows[i].translation_max_mm);
  }
  // Without noise only the 1 mm rounding is left.
  for (int i : {0, 1}) {
    EXPECT_EQ(rows[i].failed, 0);
    EXPECT_LT(rows[i].rotation_max_deg, 0.05);
    EXPECT_LT(rows[i].translation_max_mm, 0.5);
  }
  // The bar at 1 mm noise: rotation < 0.5°, translation < 5 mm.
  for (int i : {2, 3}) {
    EXPECT_EQ(rows[i].failed, 0);
    EXPECT_LT(rows[i].rotation_max_deg, 0.5);
    EXPECT_LT(rows[i].translation_max_mm, 5.0);
  }
  // Six times the noise, a larger error (same poses: the seeds depend on k and the run only).
  for (int k : {0, 1}) {
    EXPECT_EQ(rows[4 + k].failed, 0);
    EXPECT_GT(rows[4 + k].rotation_mean_deg, rows[2 + k].rotation_mean_deg);
    EXPECT_GT(rows[4 + k].translation_mean_mm, rows[0 + k].translation_mean_mm);
  }
}

TEST(StudyDepthCalibration, RefusesBadOptions) {
  DepthCalibrationStudyOptions o;
  o.poses = {2};
  EXPECT_THROW(study_depth_calibration(o), InvalidInput);
  o = {};
  o.noise_mm = {-1.0};
  EXPECT_THROW(study_depth_calibration(o), InvalidInput);
  o = {};
  o.runs = 0;
  EXPECT_THROW(study_depth_calibration(o), InvalidInput);
  o = {};
  o.noise_mm.clear();
  EXPECT_THROW(study_depth_calibration(o), InvalidInput);
}
