// End-to-end runs of `knitforge body make/fit --model FILE.npz` with a tiny
// synthetic model in SMPL's npz format that the test writes itself.
#include <cstdio>
#include <fstream>

#include <nlohmann/json.hpp>

#include "body/generated_smpl_npz.h"
#include "body/smpl_test_model.h"
#include "e2e/cli_fixture.h"
#include "knitforge/body/body_pose.h"
#include "knitforge/body/generated_body.h"
#include "knitforge/body/skin_body.h"
#include "knitforge/body/smpl_model_npz.h"
#include "knitforge/geometry/mesh_measures.h"
#include "knitforge/geometry/surface_checks.h"
#include "knitforge/io/mesh_io.h"

using namespace knitforge;
using namespace knitforge_e2e;

namespace {

std::string write_bytes(const std::string& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary) << bytes;
  return path;
}

}  // namespace

TEST_F(Cli, SmplModelFileMakesAndFitsABody) {
  const std::string model = write_bytes(path("tiny_smpl.npz"), test::smpl_test_npz(test::smpl_test_arrays()));
  CliRun r = run("body make --model " + model + " --shape 1.5,-0.5 --pose a-pose -o " + path("scan.obj") +
                 " --params " + path("made.json"));
  ASSERT_EQ(r.code, 0) << r.err;
  // The mesh is the library's posed model (mm, z up) with those parameters.
  const BodyModel m = load_smpl_model(model);
  BodyParams p = pose_preset(m, "a-pose");
  p.shape << 1.5, -0.5, 0.0;
  const PosedBody posed = pose_body(m, p);
  const TriMesh scan = read_mesh(path("scan.obj"));
  ASSERT_EQ(scan.num_vertices(), m.num_vertices());
  for (int i = 0; i < scan.num_vertices(); ++i)
    EXPECT_LT((scan.vertices[static_cast<size_t>(i)] - posed.vertices[static_cast<size_t>(i)]).norm(), 1e-3);
  const auto made = nlohmann::json::parse(slurp(path("made.json")));
  EXPECT_EQ(made["model"], "tiny_smpl.npz");
  EXPECT_EQ(made["shape"]["beta0"].get<double>(), 1.5);
  EXPECT_GT(made["joints_mm"]["head"][2].get<double>(), made["joints_mm"]["pelvis"][2].get<double>() + 500.0);
  EXPECT_FALSE(made.contains("measurements_mm"));

  r = run("body fit " + path("scan.obj") + " --model " + model + " -o " + path("fitted"));
  ASSERT_EQ(r.code, 0) << r.err;
  const auto fit = nlohmann::json::parse(slurp(path("fitted/params.json")));
  EXPECT_LT(fit["fit"]["rms_mm"].get<double>(), 0.5);  // 0.02 mm measured
  EXPECT_NEAR(fit["shape"]["beta0"].get<double>(), 1.5, 0.05);
  EXPECT_NEAR(fit["shape"]["beta1"].get<double>(), -0.5, 0.05);
  EXPECT_FALSE(fit.contains("measurements_mm"));
  EXPECT_FALSE(fs::exists(path("fitted/scan_parts.csv")));
  EXPECT_EQ(slurp(path("fitted/vertex_error.csv")).rfind("vertex,error_mm\n", 0), 0u);
  // Garment regions need part labels, which this tube (no arms: its
  // shoulder and elbow joints coincide) cannot be given.
  EXPECT_NE(r.err.find("no garment regions: body model 'tiny_smpl.npz' cannot be given part labels"), std::string::npos)
      << r.err;
  r = run("body region " + path("fitted") + " --part torso-front -o " + path("panel.obj"));
  EXPECT_NE(r.code, 0);
  EXPECT_NE(r.err.find("the fit used the model 'tiny_smpl.npz'"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("--model FILE.npz"), std::string::npos) << r.err;
  r = run("body region " + path("fitted") + " --model " + model + " --part torso-front -o " + path("panel.obj"));
  EXPECT_NE(r.code, 0);
  EXPECT_NE(r.err.find("has no garment regions"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("'left_shoulder' and 'left_elbow' are 0.00 mm apart"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(path("panel.obj")));
}

// Our generated body written as an SMPL-format file (SMPL's 24 joints:
// body/generated_smpl_npz.h): the loaded model gets part labels and
// landmarks, so body make reports measurements and body region cuts a panel
// out of its bodies, like the built-in model's.
TEST_F(Cli, SmplModelFileGetsGarmentRegions) {
  const std::string model = write_bytes(path("ours_as_smpl.npz"), test::generated_body_smpl_npz(generated_body()));
  CliRun r = run("body make --model " + model + " --pose a-pose -o " + path("body.obj") + " --params " +
                 path("made.json"));
  ASSERT_EQ(r.code, 0) << r.err;
  const auto made = nlohmann::json::parse(slurp(path("made.json")));
  ASSERT_TRUE(made.contains("measurements_mm"));
  // The template's measurements (the built-in model's at zero shape).
  EXPECT_NEAR(made["measurements_mm"]["stature"].get<double>(), 1760.0, 5.0);
  ASSERT_TRUE(made.contains("vertex_parts"));
  EXPECT_EQ(made["vertex_parts"].size(), static_cast<size_t>(generated_body().num_vertices()));

  r = run("body region " + path("body.obj") + " --model " + model + " --part torso-front -o " + path("panel.obj"));
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.err.find("body region: torso-front of"), std::string::npos) << r.err;
  const TriMesh panel = read_mesh(path("panel.obj"));
  const SurfaceReport rep = validate_surface(panel);
  EXPECT_TRUE(rep.is_disk) << rep.summary();
  // The built-in model's panel of the same body: about the same area.
  r = run("body make --pose a-pose -o " + path("builtin.obj"));
  ASSERT_EQ(r.code, 0) << r.err;
  r = run("body region " + path("builtin.obj") + " --part torso-front -o " + path("builtin_panel.obj"));
  ASSERT_EQ(r.code, 0) << r.err;
  const double a = total_area(panel), b = total_area(read_mesh(path("builtin_panel.obj")));
  std::printf("torso-front panel: %.0f cm² (model file) vs %.0f cm² (built-in)\n", a / 100.0, b / 100.0);
  EXPECT_NEAR(a, b, 0.03 * b);
  // body fit with the file: the fitter ignores head, hands and feet, the
  // fit is measured, the scan's vertices get parts, and body region cuts the
  // panel out of the scan.
  r = run("body fit " + path("body.obj") + " --model " + model + " --objective scan -o " + path("fitted"));
  ASSERT_EQ(r.code, 0) << r.err;
  const auto fit = nlohmann::json::parse(slurp(path("fitted/params.json")));
  EXPECT_LT(fit["fit"]["rms_mm"].get<double>(), 1.0);
  ASSERT_TRUE(fit.contains("measurements_mm"));
  EXPECT_NEAR(fit["measurements_mm"]["chest_girth"].get<double>(), made["measurements_mm"]["chest_girth"].get<double>(), 5.0);
  EXPECT_EQ(slurp(path("fitted/vertex_error.csv")).rfind("vertex,error_mm,part\n", 0), 0u);
  EXPECT_NE(slurp(path("fitted/scan_parts.csv")).find(",torso-front\n"), std::string::npos);
  r = run("body region " + path("fitted") + " --model " + model + " --part torso-back -o " + path("back.obj"));
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(validate_surface(read_mesh(path("back.obj"))).is_disk);

  // A body of another model file given without its --model.
  const std::string tube = write_bytes(path("tube.npz"), test::smpl_test_npz(test::smpl_test_arrays()));
  r = run("body make --model " + tube + " -o " + path("tube.obj"));
  ASSERT_EQ(r.code, 0) << r.err;
  r = run("body region " + path("tube.obj") + " --part torso-front -o " + path("x.obj"));
  EXPECT_NE(r.code, 0);
  EXPECT_NE(r.err.find("not a body of the built-in model"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("for a model file's body give --model"), std::string::npos) << r.err;
  r = run("body region " + path("body.obj") + " --model " + model + " --model-edge 20 --part head -o " + path("x.obj"));
  EXPECT_NE(r.code, 0);
  EXPECT_NE(r.err.find("--model-edge is the built-in model's mesh size"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(path("x.obj")));
}

TEST_F(Cli, SmplModelFileRefusesMeasurementsAndBadFiles) {
  const std::string model = write_bytes(path("m.npz"), test::smpl_test_npz(test::smpl_test_arrays()));
  CliRun r = run("body make --model " + model + " --height 170 -o " + path("x.obj"));
  EXPECT_NE(r.code, 0);
  EXPECT_NE(r.err.find("--height cannot be used with --model"), std::string::npos) << r.err;
  r = run("body make --shape 1,2 -o " + path("x.obj"));
  EXPECT_NE(r.code, 0);
  EXPECT_NE(r.err.find("--model FILE.npz"), std::string::npos) << r.err;
  r = run("body make --model " + model + " --shape 1,2,3,4 -o " + path("x.obj"));
  EXPECT_NE(r.code, 0);
  EXPECT_NE(r.err.find("4 values, the model"), std::string::npos) << r.err;
  test::SmplArrays a = test::smpl_test_arrays();
  a.w(0, 0) = 0.5;
  const std::string bad = write_bytes(path("bad.npz"), test::smpl_test_npz(a));
  r = run("body make --model " + bad + " -o " + path("x.obj"));
  EXPECT_NE(r.code, 0);
  EXPECT_NE(r.err.find("bad.npz: entry 'weights.npy': the weights of vertex 0 sum to 0.5"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(path("x.obj")));
}
