// The design routes' converged predicted shape (cli_common.h,
// design_prediction()): shortrow on a small built-in disk reports the same
// converged error as `knitforge predict` on its output, and an unconverged
// prediction is reported as such, without an error number.
#include <nlohmann/json.hpp>

#include "e2e/cli_fixture.h"

using namespace knitforge_e2e;

TEST_F(Cli, ShortRowReportsTheConvergedPredictionAsPredictDoes) {
  CliRun r = run("shortrow disk --stitch 5x4 --no-report --no-knitout -o " + path("d"));
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.err.find("preview (Shape-Up)"), std::string::npos) << r.err;
  const nlohmann::json j = nlohmann::json::parse(slurp(path("d/report.json")));
  ASSERT_TRUE(j["prediction"].is_object()) << j.dump();
  EXPECT_TRUE(j["prediction"]["converged"].get<bool>());
  r = run("predict " + path("d") + " -o " + path("p"));
  ASSERT_EQ(r.code, 0) << r.err;
  const nlohmann::json p = nlohmann::json::parse(slurp(path("p/predict.json")));
  EXPECT_NEAR(j["prediction"]["shape_error_mm"]["rms"].get<double>(), p["shape_error"]["rms_mm"].get<double>(), 1e-6);
  EXPECT_NEAR(j["prediction"]["shape_error_mm"]["max"].get<double>(), p["shape_error"]["max_mm"].get<double>(), 1e-6);
  EXPECT_TRUE(fs::exists(path("d/predicted.ply")));
}

TEST_F(Cli, ShortRowSaysWhenThePredictionDidNotConverge) {
  CliRun r = run("shortrow disk --stitch 5x4 --no-report --no-knitout --predict-max-iterations 1 -o " + path("d"));
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.err.find("NOT converged"), std::string::npos) << r.err;
  const nlohmann::json j = nlohmann::json::parse(slurp(path("d/report.json")));
  EXPECT_FALSE(j["prediction"]["converged"].get<bool>());
  EXPECT_TRUE(j["prediction"]["shape_error_mm"].is_null());
  EXPECT_FALSE(fs::exists(path("d/predicted.ply")));
  r = run("shortrow disk --stitch 5x4 --no-report --no-knitout --no-predict -o " + path("n"));
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(nlohmann::json::parse(slurp(path("n/report.json")))["prediction"].is_null());
}
