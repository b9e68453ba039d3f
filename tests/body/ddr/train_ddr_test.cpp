#include "knitforge/body/ddr/train_ddr.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "knitforge/body/ddr/evaluate_ddr.h"
#include "knitforge/body/ddr_geometry.h"
#include "knitforge/body/ddr_sample.h"
#include "knitforge/util/errors.h"

using namespace knitforge;

namespace {

DdrTrainOptions tiny() {
  DdrTrainOptions o;
  o.size = 32;
  o.width = 4;
  o.samples = 8;
  o.epochs = 6;
  o.refine_epochs = 2;
  o.learning_rate = 2e-3;
  return o;
}

const DdrModel& tiny_model() {
  static const DdrModel model = train_ddr(ddr_body_model(), tiny());
  return model;
}

}  // namespace

TEST(TrainDdr, TheReconstructionLossesFallOnTheTrainingSet) {
  const nlohmann::json& log = tiny_model().info.training.at("epochs_log");
  ASSERT_EQ(log.size(), 8u);
  const double first = log[0].at("l1_per_image").get<double>(), last = log[5].at("l1_per_image").get<double>();
  EXPECT_LT(last, 0.7 * first) << log.dump();
  EXPECT_LT(log[7].at("l1_per_image").get<double>(), log[6].at("l1_per_image").get<double>() * 1.2);
  EXPECT_EQ(tiny_model().info.training.at("steps").get<int>(), 8 * 2);
}

TEST(TrainDdr, IsDeterministic) {
  const DdrModel again = train_ddr(ddr_body_model(), tiny());
  EXPECT_EQ(again.info.training.at("epochs_log")[5].at("l1_per_image").get<double>(),
            tiny_model().info.training.at("epochs_log")[5].at("l1_per_image").get<double>());
}

TEST(TrainDdr, RefusesOptionsOutOfRange) {
  DdrTrainOptions o = tiny();
  o.size = 48;
  EXPECT_THROW(train_ddr(ddr_body_model(), o), InvalidInput);
  o = tiny();
  o.samples = 1;
  EXPECT_THROW(train_ddr(ddr_body_model(), o), InvalidInput);
  o = tiny();
  o.batch = 1;
  EXPECT_THROW(train_ddr(ddr_body_model(), o), InvalidInput);
}

TEST(TrainDdr, TheEstimateGrowsWithTheWork) {
  DdrTrainOptions o;
  const double base = estimate_ddr_training_seconds(o);
  o.samples *= 2;
  EXPECT_GT(estimate_ddr_training_seconds(o), 1.9 * base);
  o.size *= 2;
  EXPECT_GT(estimate_ddr_training_seconds(o), 3.5 * 1.9 * base);
}

TEST(DdrModel, SavesAndLoadsTheSameNetworks) {
  DdrModel model = tiny_model();
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "knitforge_ddr_model_test";
  std::filesystem::remove_all(dir);
  save_ddr_model(dir.string(), model);
  DdrModel loaded = load_ddr_model(dir.string());
  const DdrSample s = synthetic_ddr_sample(ddr_body_model(), body_keypoint_rig(ddr_body_model()), ddr_test_seed(0),
                                           {32, 90, 0});
  std::vector<float> input = s.rgb;
  input.insert(input.end(), s.heatmaps.begin(), s.heatmaps.end());
  EXPECT_EQ(predict_ddr(model, input, 5), predict_ddr(loaded, input, 5));
  EXPECT_EQ(loaded.info.training, model.info.training);
  // A damaged directory is refused, naming the file.
  std::filesystem::remove(dir / "refiner.pt");
  try {
    load_ddr_model(dir.string());
    FAIL();
  } catch (const IOError& e) {
    EXPECT_NE(std::string(e.what()).find("refiner.pt"), std::string::npos);
  }
  EXPECT_THROW(load_ddr_model((dir / "nothing").string()), IOError);
  std::filesystem::remove_all(dir);
}

TEST(EvaluateDdr, AveragesTheSeedsMetricsOverHeldOutBodies) {
  DdrModel model = tiny_model();
  const DdrEvaluation one = evaluate_ddr(model, ddr_body_model(), 1, 0);
  const DdrEvaluation three = evaluate_ddr(model, ddr_body_model(), 3, 1);
  EXPECT_EQ(three.samples, 3);
  EXPECT_EQ(three.meshes, 1);
  // The first test body's errors, recomputed from its sample.
  const DdrSample s = synthetic_ddr_sample(ddr_body_model(), body_keypoint_rig(ddr_body_model()), ddr_test_seed(0),
                                           {32, 90, 0});
  std::vector<float> input = s.rgb;
  input.insert(input.end(), s.heatmaps.begin(), s.heatmaps.end());
  const DdrErrors e = ddr_errors(predict_ddr(model, input, ddr_test_seed(0)), s.ddr, s.foreground, 32);
  EXPECT_DOUBLE_EQ(one.ei, e.ei);
  EXPECT_DOUBLE_EQ(one.ep_cm, e.ep_cm);
  // The flat prediction's EP is the mean |depth - pelvis depth| over the true foreground.
  double sum = 0.0;
  const size_t plane = s.foreground.size();
  for (size_t i = 0; i < plane; ++i)
    if (s.foreground[i] != 0) sum += std::abs(s.ddr[i]) + std::abs(s.ddr[plane + i]);
  const int foreground = static_cast<int>(std::count(s.foreground.begin(), s.foreground.end(), 1));
  EXPECT_NEAR(one.flat_ep_cm, sum / (2.0 * foreground) * kDdrDepthUnitMm / 10.0, 1e-6);
  EXPECT_GT(one.flat_ep_cm, 1.0);  // a body is centimetres deep about its pelvis
  EXPECT_GT(three.mesh_to_body_cm, 0.0);
  EXPECT_GT(three.body_to_mesh_cm, 0.0);
  EXPECT_THROW(evaluate_ddr(model, ddr_body_model(), 0, 0), InvalidInput);
}
