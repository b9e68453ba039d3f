// End-to-end runs of the single-image reconstruction (seed §5.4):
// `knitforge body render-photo`, `body ddr-train` (a tiny model),
// `body ddr-evaluate`, `body reconstruct` (run by knitforge-ddr, which
// knitforge hands the command line to), and the refusals of bad input.
#include <fstream>

#include <fmt/core.h>
#include <nlohmann/json.hpp>

#include "e2e/cli_fixture.h"
#include "knitforge/io/mesh_io.h"
#include "knitforge/io/png_image.h"

using namespace knitforge;
using namespace knitforge_e2e;

namespace {

constexpr const char* kTinyTraining =
    "--size 32 --width 4 --samples 8 --epochs 2 --refine-epochs 1 --learning-rate 2e-4 --test-samples 2 --test-meshes 1";

}  // namespace

TEST_F(Cli, ReconstructFromARenderedPhotoWithATinyModel) {
  CliRun r = run(fmt::format("body render-photo --test 3 --size 64 -o {} --keypoints {} --truth {} --ddr {}",
                             path("photo.png"), path("photo.json"), path("truth.obj"), path("truth_ddr.png")));
  ASSERT_EQ(r.code, 0) << r.err;
  const RgbImage photo = read_png(path("photo.png"));
  EXPECT_EQ(photo.width, 64);
  const nlohmann::json kp = nlohmann::json::parse(slurp(path("photo.json")));
  EXPECT_EQ(kp["people"][0]["pose_keypoints_2d"].size(), 54u);
  EXPECT_EQ(read_png(path("truth_ddr.png")).width, 128);

  r = run(fmt::format("body ddr-train -o {} {}", path("model"), kTinyTraining));
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.err.find("EP"), std::string::npos) << r.err;
  const nlohmann::json info = nlohmann::json::parse(slurp(path("model/ddr.json")));
  EXPECT_EQ(info["size"], 32);
  EXPECT_EQ(info["evaluation"]["test_samples"], 2);
  EXPECT_GT(info["evaluation"]["EP_cm"].get<double>(), 0.0);
  EXPECT_GT(info["evaluation"]["EP_flat_cm"].get<double>(), 0.0);
  EXPECT_DOUBLE_EQ(info["training"]["learning_rate"].get<double>(), 2e-4);
  EXPECT_DOUBLE_EQ(info["training"]["epochs_log"][1]["learning_rate"].get<double>(), 2e-5);  // second half

  // The 64-pixel photo is scaled to the model's 32 pixels, keypoints with it.
  r = run(fmt::format("body reconstruct {} --keypoints {} --model {} -o {} --ddr {}", path("photo.png"),
                      path("photo.json"), path("model"), path("body.ply"), path("ddr.png")));
  ASSERT_EQ(r.code, 0) << r.err;
  // A tiny model's shape means nothing (the geometry is tested on true
  // DDRs in tests/body/ddr); here: a closed mesh and the DDR picture.
  EXPECT_GT(read_mesh(path("body.ply")).num_faces(), 100);
  EXPECT_EQ(read_png(path("ddr.png")).width, 64);
  EXPECT_NE(r.err.find("refinement views"), std::string::npos) << r.err;

  r = run(fmt::format("body ddr-evaluate {} --samples 2 --meshes 0 --json", path("model")));
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(nlohmann::json::parse(r.out)["test_samples"], 2);
}

TEST_F(Cli, ReconstructBadInputExitsNonZeroNamingTheProblem) {
  CliRun r = run(fmt::format("body render-photo --test 0 --size 32 -o {} --keypoints {}", path("p.png"), path("p.json")));
  ASSERT_EQ(r.code, 0) << r.err;
  // No model there.
  r = run(fmt::format("body reconstruct {} --keypoints {} --model {} -o {}", path("p.png"), path("p.json"),
                      path("nomodel"), path("b.ply")));
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("ddr.json"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(path("b.ply")));
  // Keypoints without a person.
  std::ofstream(path("empty.json")) << R"({"version": 1.3, "people": []})";
  r = run(fmt::format("body ddr-train -o {} --size 32 --width 2 --samples 4 --epochs 1 --refine-epochs 0 "
                      "--test-samples 1 --test-meshes 0",
                      path("model")));
  ASSERT_EQ(r.code, 0) << r.err;
  r = run(fmt::format("body reconstruct {} --keypoints {} --model {} -o {}", path("p.png"), path("empty.json"),
                      path("model"), path("b.ply")));
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("no person"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(path("b.ply")));
  // A picture that is not square.
  RgbImage wide{40, 32, std::vector<uint8_t>(40 * 32 * 3, 100)};
  write_png(path("wide.png"), wide);
  r = run(fmt::format("body reconstruct {} --keypoints {} --model {} -o {}", path("wide.png"), path("p.json"),
                      path("model"), path("b.ply")));
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("not square"), std::string::npos) << r.err;
  // A run estimated beyond --max-hours is refused before any work.
  r = run(fmt::format("body ddr-train -o {} --samples 100000 --max-hours 1", path("big")));
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("--max-hours"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(path("big")));
  // A usage error is exit 2 in both programs.
  r = run("body ddr-train -o x --size 48");
  EXPECT_EQ(r.code, 2);
}
