// End-to-end runs of `knitforge predict` (docs/sim.md): a small built-in map,
// free and on a built-in dome under gravity, its outputs, the material file
// round trip, and bad input.
#include <nlohmann/json.hpp>

#include "e2e/cli_fixture.h"
#include "knitforge/io/mesh_io.h"
#include "knitforge/io/stitch_mesh_ply.h"

using namespace knitforge;
using namespace knitforge_e2e;

TEST_F(Cli, PredictFreeAndOnADomeConvergesAndWritesItsOutputs) {
  ASSERT_EQ(run("sample-map random --rows 12 --cols 10 --short-row-ends 4 --short-columns 0 --seed 3 -o " +
                path("m.csv"))
                .code,
            0);
  CliRun r = run("predict " + path("m.csv") + " -o " + path("free"));
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.err.find("converged after"), std::string::npos) << r.err;
  nlohmann::json j = nlohmann::json::parse(slurp(path("free/predict.json")));
  EXPECT_TRUE(j["solve"]["converged"].get<bool>());
  EXPECT_LE(j["solve"]["max_free_force_mn"].get<double>(), j["solve"]["force_tolerance_mn"].get<double>());
  const StitchMesh free = read_stitch_mesh_ply(path("free/predicted.ply"));
  EXPECT_EQ(free.num_stitches(), j["input"]["stitches"].get<int>());

  // The material it used reads back, and gives the same answer.
  r = run("predict " + path("m.csv") + " --material " + path("free/material.json") + " -o " + path("again"));
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(slurp(path("free/predicted.ply")), slurp(path("again/predicted.ply")));

  r = run("predict " + path("m.csv") + " --on hemisphere --edge 6 --gravity -o " + path("dome"));
  ASSERT_EQ(r.code, 0) << r.err;
  j = nlohmann::json::parse(slurp(path("dome/predict.json")));
  EXPECT_TRUE(j["solve"]["converged"].get<bool>());
  EXPECT_TRUE(j["setup"]["settled"].get<bool>());
  EXPECT_GT(j["solve"]["contacts"].get<int>(), 0);
  EXPECT_GT(j["solve"]["min_distance_to_support_mm"].get<double>(), 0.0);
  EXPECT_GT(read_mesh(path("dome/support.ply")).num_faces(), 0);
}

TEST_F(Cli, PredictRefusesBadInputNamingTheProblem) {
  ASSERT_EQ(run("sample-map cup -o " + path("m.csv")).code, 0);
  CliRun r = run("predict " + path("m.csv") + " --gravity -o " + path("out"));
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("needs a support"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(path("out")));
  {
    std::ofstream(path("bad.json")) << R"({"bendin": 1})";
  }
  r = run("predict " + path("m.csv") + " --material " + path("bad.json") + " -o " + path("out"));
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("unknown material field 'bendin'"), std::string::npos) << r.err;
  r = run("predict " + path("nowhere") + " -o " + path("out"));
  EXPECT_EQ(r.code, 1);
}
