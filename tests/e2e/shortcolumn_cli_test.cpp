// End-to-end runs of `knitforge shortcolumn` (issue 14): optimised boundary
// conditions, short rows and short columns, machine program, on the
// built-in hemisphere, the other built-in inputs of the issue and the
// mannequin panel.
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "e2e/cli_fixture.h"
#include "knitforge/convert/map_knittability.h"
#include "knitforge/core/knittability.h"
#include "knitforge/core/stitch_mesh.h"
#include "knitforge/io/knitting_map_csv.h"
#include "knitforge/io/polyline_obj.h"
#include "knitforge/io/stitch_mesh_ply.h"

using namespace knitforge;
using namespace knitforge_e2e;

TEST_F(Cli, ShortColumnHemisphereOptimisesAndWritesAMatchingProgram) {
  const std::string out = path("hemi");
  const CliRun r = run("shortcolumn hemisphere --budget 20 -o " + out + " --json");
  ASSERT_EQ(r.code, 0) << r.err;
  for (const char* f : {"stitch_mesh.ply", "knitting_map.csv", "knitting_map.png", "knitting_map.svg", "wales.obj",
                        "field.ply", "field.txt", "divergence.ply", "target.ply", "yarn.obj", "relaxed.ply",
                        "shape_error.ply", "distortion.ply", "field.png", "divergence.png", "optimisation.json", "optimisation.svg", "knitout.k",
                        "report.json", "report.html"})
    EXPECT_TRUE(fs::exists(out + "/" + f)) << f;
  for (const char* stage : {"evaluation 20/20", "optimisation: best b", "wale curves", "tessellation", "knitting map"})
    EXPECT_NE(r.err.find(stage), std::string::npos) << stage;
  const nlohmann::json report = nlohmann::json::parse(slurp(out + "/report.json"));
  EXPECT_EQ(report, nlohmann::json::parse(r.out)) << "--json prints report.json";
  EXPECT_TRUE(report["knittable"].get<bool>());

  // The map and the stitch mesh read back pass every check; the counts agree.
  const KnittingMap map = read_knitting_map_csv(out + "/knitting_map.csv");
  EXPECT_TRUE(check_knittability(map, KnitParams{3.5, 2.8}).ok());
  const StitchMesh mesh = read_stitch_mesh_ply(out + "/stitch_mesh.ply");
  EXPECT_TRUE(check_knittability(mesh).ok());
  const nlohmann::json& c = report["counts"];
  EXPECT_EQ(mesh.num_stitches(), c["stitches"].get<int>());
  const auto types = count_stitch_types(mesh);
  EXPECT_EQ(types[static_cast<int>(StitchType::Increase)], c["increases"].get<int>());
  EXPECT_EQ(types[static_cast<int>(StitchType::Decrease)], c["decreases"].get<int>());
  EXPECT_EQ(c["transfer_stitches"].get<int>(), c["increases"].get<int>() + c["decreases"].get<int>());
  EXPECT_EQ(static_cast<int>(read_polylines_obj(out + "/wales.obj").size()), c["wales"].get<int>());
  EXPECT_LT(std::abs(c["stitches_vs_area"].get<double>()), 0.05);

  // The machine program: valid, its knit graph matches the map, and it
  // makes the map's short-column stitches.
  const nlohmann::json& m = report["machine"];
  EXPECT_EQ(m["verdict"], "VALID");
  EXPECT_TRUE(m["matches_map"].get<bool>());
  EXPECT_EQ(m["shaping"]["transfer_stitches"].get<int>(), c["transfer_stitches"].get<int>());
  EXPECT_GT(m["knit_time_s"].get<double>(), 0.0);
  const CliRun sim = run("simulate " + out + "/knitout.k --against " + out + "/knitting_map.csv");
  EXPECT_EQ(sim.code, 0) << sim.out;
  EXPECT_NE(sim.out.find("MATCHES"), std::string::npos) << sim.out;

  // The optimisation history: 20 evaluations, the best so far never rises,
  // and the design's b is the best one (the first alternative was knittable).
  const nlohmann::json h = nlohmann::json::parse(slurp(out + "/optimisation.json"));
  ASSERT_EQ(h["evaluations"].size(), 20u);
  double best = 1e300;
  for (const auto& e : h["evaluations"]) {
    best = std::min(best, e["estimated_transfers"].get<double>());
    EXPECT_DOUBLE_EQ(e["best_so_far"].get<double>(), best);
  }
  EXPECT_DOUBLE_EQ(h["best"]["estimated_transfers"].get<double>(), best);
  EXPECT_EQ(report["field"]["b"], h["best"]["b"]);

  // The comparison with the short-row-only design of the same surface.
  const nlohmann::json& sr = report["comparison"]["short_row_only"];
  EXPECT_GT(sr["stitches"].get<int>(), 0);
  EXPECT_TRUE(sr["knittable"].get<bool>());

  // The field written is the field designed with: --field gives the same design.
  const std::string again = path("again");
  const CliRun r2 = run("shortcolumn hemisphere --field " + out + "/field.txt --no-evaluate --no-compare -o " + again);
  ASSERT_EQ(r2.code, 0) << r2.err;
  const nlohmann::json rep2 = nlohmann::json::parse(slurp(again + "/report.json"));
  EXPECT_EQ(rep2["field"]["kind"], "file");
  EXPECT_EQ(rep2["counts"]["stitches"], c["stitches"]);
  EXPECT_EQ(rep2["counts"]["transfer_stitches"], c["transfer_stitches"]);
  EXPECT_FALSE(fs::exists(again + "/optimisation.json"));
}

TEST_F(Cli, ShortColumnGivenBoundaryVectorAndBadInputs) {
  const std::string out = path("bc");
  CliRun r = run("shortcolumn hemisphere --bc 0.84,0.84,1.34,1.34 --no-evaluate --no-compare --no-knitout -o " + out);
  ASSERT_EQ(r.code, 0) << r.err;
  const nlohmann::json report = nlohmann::json::parse(slurp(out + "/report.json"));
  EXPECT_EQ(report["field"]["kind"], "harmonic");
  EXPECT_DOUBLE_EQ(report["field"]["b"][0].get<double>(), 0.84);
  EXPECT_FALSE(report.contains("optimisation"));
  EXPECT_FALSE(fs::exists(out + "/knitout.k"));

  const std::string bad = path("bad");
  r = run("shortcolumn hemisphere --bc 0.5,0.4,0.6,0.7 -o " + bad);
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("feasible set"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(bad + "/report.json"));
  r = run("shortcolumn hemisphere --bc 0.1,0.2,0.3 -o " + bad);
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("four numbers"), std::string::npos) << r.err;
  {
    std::ofstream f(path("short_field.txt"));
    f << "0\n1\n2\n";
  }
  r = run("shortcolumn hemisphere --field " + path("short_field.txt") + " -o " + bad);
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("short_field.txt"), std::string::npos) << r.err;
  r = run("shortcolumn hemisphere --bc 0.84,0.84,1.34,1.34 --field fiedler -o " + bad);
  EXPECT_NE(r.code, 0);
  r = run("shortcolumn no_such_surface.obj -o " + bad);
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("no_such_surface.obj"), std::string::npos) << r.err;
}

namespace {

// Designs INPUT (a shape, or a file with its options) with the boundary
// vector BC, no evaluation or comparison, into OUT by RUN (the fixture's
// run()), and checks the design: knittable, short columns made, a VALID
// program that makes every transfer stitch of the design and whose knit
// graph matches the map (in the report and by `knitforge simulate`).
template <class Run>
void expect_knittable_with_short_columns(Run&& run, const std::string& input, const std::string& bc,
                                         const std::string& out) {
  const CliRun r = run("shortcolumn " + input + " --bc " + bc + " --no-evaluate --no-compare --no-report -o " + out);
  ASSERT_EQ(r.code, 0) << r.err;
  const nlohmann::json report = nlohmann::json::parse(slurp(out + "/report.json"));
  EXPECT_TRUE(report["knittable"].get<bool>());
  EXPECT_EQ(report["machine"]["verdict"], "VALID");
  EXPECT_TRUE(report["machine"]["matches_map"].get<bool>());
  EXPECT_GT(report["counts"]["transfer_stitches"].get<int>(), 0) << "these surfaces get short columns";
  EXPECT_EQ(report["machine"]["shaping"]["transfer_stitches"], report["counts"]["transfer_stitches"]);
  const CliRun sim = run("simulate " + out + "/knitout.k --against " + out + "/knitting_map.csv");
  EXPECT_EQ(sim.code, 0) << sim.out;
  EXPECT_NE(sim.out.find("MATCHES"), std::string::npos) << sim.out;
}

}  // namespace

TEST_F(Cli, ShortColumnBuiltInShapesAreKnittableAndTheirProgramsMatch) {
  // The other built-in inputs, each with the boundary vector that the
  // default optimisation (budget 100, seed 0) chose for it (docs/shortcolumn.md,
  // Measured; all at their 1st alternative): the cap is cut
  // into a disk first. One design each, no optimisation (the optimiser's own
  // runs are the hemisphere test above and the symmetric one below).
  const std::vector<std::pair<const char*, const char*>> inputs = {
      {"triple-peak", "5.7656218572791795e-05,0.4981904106586099,0.7031991210816163,0.705809975125701"},
      {"monkey-saddle", "0.1605718019138728,0.33576255146642625,0.4984710605818013,1.0002189353671738"},
      {"cap", "0.4286603964126085,0.8740286020191007,1.1314165871519206,1.1314165871519206"}};
  for (const auto& [shape, bc] : inputs) {
    SCOPED_TRACE(shape);
    expect_knittable_with_short_columns([this](const std::string& a) { return run(a); }, shape, bc, path(shape));
  }
}

TEST_F(Cli, ShortColumnMannequinPanelIsKnittableAtBothStitchSizes) {
  // The scanned input (cm) at 3 x 2 and 1.4 x 1.3 mm, each with the
  // boundary vector the default optimisation chose for it (at 1.4 x 1.3 its
  // 2nd alternative: the 1st breaks map-topology; docs/shortcolumn.md).
  const fs::path mannequin = fs::path(KNITFORGE_SHARED_DATA) / "mannequin_front.obj";
  if (!fs::exists(mannequin)) GTEST_SKIP() << mannequin << " is not there";
  const std::vector<std::pair<const char*, const char*>> inputs = {
      {"3x2", "0.10958692826612527,0.279488996402149,0.6018577100411485,0.8202852315284597"},
      {"1.4x1.3", "0.6003920523549068,0.8220858460352753,1.2655067318846553,1.2655067318846553"}};
  for (const auto& [stitch, bc] : inputs) {
    SCOPED_TRACE(stitch);
    expect_knittable_with_short_columns([this](const std::string& a) { return run(a); },
                                        mannequin.string() + " --units cm --stitch " + stitch, bc,
                                        path(std::string("mannequin_") + stitch));
  }
}

TEST_F(Cli, ShortColumnSymmetricOptimisationKeepsTheIntervalsMirrored) {
  // The 2D variant (L1484) on the hemisphere, symmetric about x = centre and
  // y = centre: every evaluated b has R_s centred on one crossing of the
  // mirror plane with the boundary and R_e on the other.
  const std::string out = path("sym");
  const CliRun r = run("shortcolumn hemisphere --symmetric --budget 12 --alternatives 3 --no-evaluate --no-compare "
                       "--no-report -o " + out);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.err.find("12 evaluations, symmetric"), std::string::npos) << r.err;
  const nlohmann::json report = nlohmann::json::parse(slurp(out + "/report.json"));
  EXPECT_TRUE(report["optimisation"]["symmetric"].get<bool>());
  EXPECT_TRUE(report["knittable"].get<bool>());
  EXPECT_EQ(report["machine"]["verdict"], "VALID");
  EXPECT_TRUE(report["machine"]["matches_map"].get<bool>());
  const nlohmann::json h = nlohmann::json::parse(slurp(out + "/optimisation.json"));
  ASSERT_EQ(h["evaluations"].size(), 12u);
  ASSERT_TRUE(h.contains("mirror"));
  EXPECT_LT(h["mirror"]["mean_error_mm"].get<double>(), 1.0);
  const double p = h["mirror"]["p"].get<double>(), q = p + h["mirror"]["gap"].get<double>();
  auto wrapped = [](double x) { return x - std::round(x); };  // distance on the unit circle, signed
  for (const auto& e : h["evaluations"]) {
    const std::vector<double> b = e["evaluated"].get<std::vector<double>>();
    ASSERT_EQ(b.size(), 4u);
    const double cs = 0.5 * (b[0] + b[1]), ce = 0.5 * (b[2] + b[3]);
    // R_s about one crossing and R_e about the other (either way round).
    const bool ps = std::abs(wrapped(cs - p)) < 1e-6 && std::abs(wrapped(ce - q)) < 1e-6;
    const bool qs = std::abs(wrapped(cs - q)) < 1e-6 && std::abs(wrapped(ce - p)) < 1e-6;
    EXPECT_TRUE(ps || qs) << e["evaluated"].dump() << " p " << p << " q " << q;
  }
  EXPECT_EQ(report["field"]["b"], h["alternatives"][report["field"]["candidate"].get<int>()]["b"]);

  // A plane the surface is not symmetric about is refused before any work.
  const std::string bad = path("sym_bad");
  const CliRun r2 = run("shortcolumn hemisphere --symmetric --mirror 1,0,0,30 --budget 12 -o " + bad);
  EXPECT_EQ(r2.code, 1);
  EXPECT_NE(r2.err.find("not mirror-symmetric"), std::string::npos) << r2.err;
  EXPECT_FALSE(fs::exists(bad + "/report.json"));
}
