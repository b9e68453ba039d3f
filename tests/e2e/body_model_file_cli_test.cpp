// End-to-end runs of `knitforge body make/fit --model FILE.npz` with a tiny
// synthetic model in SMPL's npz format that the test writes itself.
#include <fstream>

#include <nlohmann/json.hpp>

#include "body/smpl_test_model.h"
#include "e2e/cli_fixture.h"
#include "knitforge/body/body_pose.h"
#include "knitforge/body/skin_body.h"
#include "knitforge/body/smpl_model_npz.h"
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
  // Garment regions need part labels, which a model file does not have.
  r = run("body region " + path("fitted") + " --part torso-front -o " + path("panel.obj"));
  EXPECT_NE(r.code, 0);
  EXPECT_NE(r.err.find("has no garment regions"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(path("panel.obj")));
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
