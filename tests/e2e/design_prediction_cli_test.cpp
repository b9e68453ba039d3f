// The design routes' converged predicted shape (cli_common.h,
// report_design_shape()): shortrow, flatten and shortcolumn on a small
// built-in disk each report the same converged error as `knitforge predict`
// on their output (so the prediction is of the stitch mesh the route wrote,
// against the surface it designed for), and an unconverged prediction is
// reported as such, without an error number.
#include <cmath>

#include <nlohmann/json.hpp>

#include "e2e/cli_fixture.h"

using namespace knitforge_e2e;

namespace {

// Small designs (300 to 800 stitches, seconds each) of the three routes. The
// flatten route on a curved surface (on the flat disk its long rows, added
// beyond the pattern, make the free equilibrium hard to reach: Newton alone
// did not in 500 iterations).
const char* const kShortRow = "shortrow disk --stitch 5x4 --no-report --no-knitout";
const char* const kFlatten = "flatten hemisphere --stitch 8x6 --no-knitout";
const char* const kShortColumn =
    "shortcolumn disk --stitch 5x4 --bc 0.84,0.84,1.34,1.34 --no-compare --no-report --no-knitout";

class DesignPrediction : public Cli {
 protected:
  /// `design -o DIR` reports a converged prediction with a finite error
  /// (RMS <= max), labels its Shape-Up number a preview, writes
  /// predicted.ply, and its error is `knitforge predict DIR`'s.
  void expect_converged_as_predict(const std::string& design) {
    CliRun r = run(design + " -o " + path("d"));
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_NE(r.err.find("preview (Shape-Up)"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("predicted shape error RMS"), std::string::npos) << r.err;
    const nlohmann::json j = nlohmann::json::parse(slurp(path("d/report.json")));
    EXPECT_EQ(j["evaluation"]["predictor"], "Shape-Up preview (not a converged shape)");
    const nlohmann::json& pr = j["prediction"];
    ASSERT_TRUE(pr.is_object()) << j.dump();
    EXPECT_TRUE(pr["converged"].get<bool>()) << pr.dump();
    const double rms = pr["shape_error_mm"]["rms"].get<double>(), max = pr["shape_error_mm"]["max"].get<double>();
    EXPECT_TRUE(std::isfinite(rms) && std::isfinite(max)) << pr.dump();
    EXPECT_GT(rms, 0.0);
    EXPECT_LE(rms, max);
    EXPECT_TRUE(fs::exists(path("d/predicted.ply")));
    r = run("predict " + path("d") + " -o " + path("p"));
    ASSERT_EQ(r.code, 0) << r.err;
    const nlohmann::json p = nlohmann::json::parse(slurp(path("p/predict.json")));
    EXPECT_NEAR(rms, p["shape_error"]["rms_mm"].get<double>(), 1e-6);
    EXPECT_NEAR(max, p["shape_error"]["max_mm"].get<double>(), 1e-6);
    EXPECT_TRUE(p["shape_error"]["icp_converged"].get<bool>()) << p["shape_error"].dump();
    EXPECT_LT(p["shape_error"]["icp_rounds"].get<int>(), 30);
  }

  /// With one Newton iteration (after 20 L-BFGS ones) the prediction of `design` does not converge
  /// (converged false, a null error, no predicted.ply); --no-predict runs none.
  void expect_unconverged_and_skipped(const std::string& design) {
    CliRun r = run(design + " --predict-max-iterations 1 -o " + path("d"));
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_NE(r.err.find("NOT converged"), std::string::npos) << r.err;
    const nlohmann::json j = nlohmann::json::parse(slurp(path("d/report.json")));
    EXPECT_FALSE(j["prediction"]["converged"].get<bool>());
    EXPECT_TRUE(j["prediction"]["shape_error_mm"].is_null());
    EXPECT_FALSE(fs::exists(path("d/predicted.ply")));
    r = run(design + " --no-predict -o " + path("n"));
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_EQ(r.err.find("predicted shape"), std::string::npos) << r.err;
    EXPECT_TRUE(nlohmann::json::parse(slurp(path("n/report.json")))["prediction"].is_null());
    EXPECT_FALSE(fs::exists(path("n/predicted.ply")));
  }
};

}  // namespace

TEST_F(DesignPrediction, ShortRowReportsTheConvergedPredictionAsPredictDoes) {
  expect_converged_as_predict(kShortRow);
}

TEST_F(DesignPrediction, ShortRowSaysWhenThePredictionDidNotConverge) { expect_unconverged_and_skipped(kShortRow); }

TEST_F(DesignPrediction, FlattenReportsTheConvergedPredictionAsPredictDoes) {
  expect_converged_as_predict(kFlatten);
  // The report page embeds report.json, the converged prediction included,
  // and draws predicted.ply as its own layer (a stitch mesh with its shape error).
  const nlohmann::json data = report_page_data(path("d/report.html"));
  ASSERT_TRUE(data.is_object());
  EXPECT_TRUE(data["metrics"]["prediction"]["converged"].get<bool>());
  EXPECT_EQ(data["metrics"]["prediction"]["shape_error_mm"],
            nlohmann::json::parse(slurp(path("d/report.json")))["prediction"]["shape_error_mm"]);
  ASSERT_TRUE(data.contains("predicted"));
  EXPECT_EQ(data["predicted"]["kind"], "stitch_mesh");
  EXPECT_EQ(data["predicted"]["corners"].size(), data["stitch_mesh"]["corners"].size());
  EXPECT_EQ(data["predicted"]["scalars"]["shape_error"].size(), data["predicted"]["corners"].size() / 4);
  EXPECT_NE(data["predicted"]["positions"], data["stitch_mesh"]["positions"]);
  // Again into the same directory without a prediction: no predicted.ply of the earlier run, no layer.
  const CliRun again = run(std::string(kFlatten) + " --no-predict -o " + path("d"));
  ASSERT_EQ(again.code, 0) << again.err;
  EXPECT_FALSE(fs::exists(path("d/predicted.ply")));
  EXPECT_FALSE(report_page_data(path("d/report.html")).contains("predicted"));
}

TEST_F(DesignPrediction, FlattenSaysWhenThePredictionDidNotConverge) {
  expect_unconverged_and_skipped(kFlatten);
  // No predicted.ply, no predicted layer on the page.
  const nlohmann::json data = report_page_data(path("d/report.html"));
  ASSERT_TRUE(data.is_object());
  EXPECT_FALSE(data.contains("predicted"));
}

TEST_F(DesignPrediction, ShortColumnReportsTheConvergedPredictionAsPredictDoes) {
  expect_converged_as_predict(kShortColumn);
}

TEST_F(DesignPrediction, ShortColumnSaysWhenThePredictionDidNotConverge) {
  expect_unconverged_and_skipped(kShortColumn);
}
