// shortrow --tube end to end: design, knitout, simulate (docs/tubes.md "Design").
#include <cmath>
#include <cstdint>
#include <vector>

#include <nlohmann/json.hpp>

#include "knitforge/geometry/shapes.h"
#include "knitforge/io/mesh_io.h"

#include "cli_fixture.h"

namespace knitforge_e2e {
namespace {

TEST_F(Cli, ShortrowTubeDesignsTheSleeveKnitsAndSimulatesIt) {
  const std::string out = path("sleeve");
  CliRun r = run("shortrow sleeve --tube --stitch 7x5.6 --edge 6 --no-report -o " + out);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.err.find("shima-swg091n2: VALID, knit graph MATCHES the map"), std::string::npos) << r.err;
  const std::string csv = slurp(fs::path(out) / "knitting_map.csv");
  EXPECT_EQ(csv.rfind("course,dir,seam,", 0), 0u) << "not a tubular map";
  EXPECT_NE(csv.find(",D"), std::string::npos) << "the tapered sleeve has decreases";
  const std::string report = slurp(fs::path(out) / "report.json");
  EXPECT_NE(report.find("\"route\": \"tube\""), std::string::npos);
  EXPECT_NE(report.find("\"rounds_off_ideal_by_more_than_1\": 0"), std::string::npos) << report;

  expect_knitted_as_designed(out + "/knitting_map.csv", path("sleeve.k"), "kniterate");
}

TEST_F(Cli, ShortrowTubeKnitsTheSleevesBendWithShortRowsOnBothMachines) {
  const std::string out = path("sleeve_sr");
  CliRun r = run("shortrow sleeve --tube --edge 5 --no-report -o " + out);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.err.find("shima-swg091n2: VALID, knit graph MATCHES the map"), std::string::npos) << r.err;
  const std::string csv = slurp(fs::path(out) / "knitting_map.csv");
  EXPECT_NE(csv.find(",-,"), std::string::npos) << "no open row (short row)";
  EXPECT_NE(csv.find(",L"), std::string::npos) << "no short-row end";
  const std::string report = slurp(fs::path(out) / "report.json");
  EXPECT_EQ(report.find("\"short_rows\": 0,"), std::string::npos) << report;
  expect_knitted_as_designed(out + "/knitting_map.csv", path("sleeve_sr.k"), "kniterate");

  const std::string plain = path("sleeve_plain");
  r = run("shortrow sleeve --tube --edge 5 --no-tube-short-rows --no-report -o " + plain);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(slurp(fs::path(plain) / "knitting_map.csv").find(",-,"), std::string::npos) << "a short row without them";
  r = run("shortrow sleeve --no-tube-short-rows --edge 8 -o " + path("sheet"));
  EXPECT_NE(r.code, 0);
  EXPECT_NE(r.err.find("--no-tube-short-rows applies to --tube only"), std::string::npos) << r.err;
}

TEST_F(Cli, ShortrowTubeKnitsAStraightTubeWithoutShortRows) {
  const std::string out = path("tube");
  CliRun r = run("shortrow tube --tube --stitch 7x5.6 --edge 5 --no-report -o " + out);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.err.find("0 short rows (0 turns) in 0 wedges,"), std::string::npos) << r.err;
  EXPECT_EQ(slurp(fs::path(out) / "knitting_map.csv").find(",-,"), std::string::npos);
  // The converged predicted shape, as the sheet routes report it (648
  // stitches: under the default limit): a straight tube knits straight.
  EXPECT_NE(r.err.find("predicted shape error RMS 0."), std::string::npos) << r.err;
  const auto report = nlohmann::json::parse(slurp(fs::path(out) / "report.json"));
  EXPECT_TRUE(report["prediction"]["converged"].get<bool>()) << report["prediction"].dump();
  EXPECT_LT(report["prediction"]["shape_error_mm"]["rms"].get<double>(), 1.0);
  EXPECT_TRUE(fs::exists(fs::path(out) / "predicted.ply"));
  // the shaping estimate: 0 on a straight tube
  EXPECT_NE(r.err.find("about 0 shaping stitches (estimate; 0 increases + decreases designed)"), std::string::npos)
      << r.err;
}

// Closed tubes (docs/tubes.md "Closed tubes"): the beanie from its rim to
// its crown, the last round joined across the beds by the closing seam.
TEST_F(Cli, ShortrowTubeKnitsTheBeanieClosedAtItsCrownOnBothMachines) {
  const std::string out = path("beanie");
  CliRun r = run("shortrow beanie --tube --stitch 7x5.6 --edge 6 --no-report -o " + out);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.err.find("shima-swg091n2: VALID, knit graph MATCHES the map"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("closed at the crown"), std::string::npos) << r.err;
  const std::string csv = slurp(fs::path(out) / "knitting_map.csv");
  EXPECT_NE(csv.find(":close"), std::string::npos) << "the top line does not close the tube";
  const std::string program = slurp(fs::path(out) / "knitout.k");
  EXPECT_NE(program.find("; bind-off: closing seam"), std::string::npos);
  expect_knitted_as_designed(out + "/knitting_map.csv", path("beanie.k"), "kniterate");
}

// The comparison tells a closed tube from an open one both ways: the
// beanie's program against its map without ':close', and the open map's
// program against the closed map.
TEST_F(Cli, SimulateTellsAClosingSeamFromAnOpenEnd) {
  const std::string out = path("beanie_c");
  CliRun r = run("shortrow beanie --tube --stitch 7x5.6 --edge 6 --no-report --no-knitout -o " + out);
  ASSERT_EQ(r.code, 0) << r.err;
  const std::string closed_csv = out + "/knitting_map.csv";
  std::string text = slurp(closed_csv);
  const size_t at = text.find(":close");
  ASSERT_NE(at, std::string::npos);
  text.erase(at, 6);
  const std::string open_csv = path("beanie_open.csv");
  {
    std::ofstream f(open_csv);
    f << text;
  }
  for (const auto& [knit, against] : {std::pair{closed_csv, open_csv}, std::pair{open_csv, closed_csv}}) {
    const std::string k = path("beanie_cmp.k");
    r = run("knitout " + knit + " --machine shima-swg091n2 -o " + k);
    ASSERT_EQ(r.code, 0) << r.err;
    r = run("simulate " + k + " --machine shima-swg091n2 --against " + against);
    EXPECT_NE(r.code, 0) << r.out;
    EXPECT_NE((r.out + r.err).find("closing:"), std::string::npos) << r.out << r.err;
  }
}

// The sock: a bent tube closed at the toe, with short-row wedges at the heel.
TEST_F(Cli, ShortrowTubeKnitsTheSockWithAHeelAndAClosedToe) {
  const std::string out = path("sock");
  CliRun r = run("shortrow sock --tube --stitch 7x5.6 --edge 6 --no-report -o " + out);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.err.find("shima-swg091n2: VALID, knit graph MATCHES the map"), std::string::npos) << r.err;
  const std::string csv = slurp(fs::path(out) / "knitting_map.csv");
  EXPECT_NE(csv.find(":close"), std::string::npos);
  EXPECT_NE(csv.find(",-,"), std::string::npos) << "no short row at the heel";
  // the toe closes along the crown segment with the asked 12 stitches
  EXPECT_NE(r.err.find("last round 12 stitches (12 asked;"), std::string::npos) << r.err;
  expect_knitted_as_designed(out + "/knitting_map.csv", path("sock.k"), "kniterate");
}

// Scanned-style closed tubes: a leg and a head cut out of a noisy stand-in
// for a scan by the fitted body model (the leg's wedges once stacked two
// turn pairs in one wale; with a 16-stitch crown its last round's halves
// lie 5 needles apart on the Kniterate, beyond its racking, so the closing
// seam walks the loops over; with the default 12 along its crown segment
// they no longer do).
TEST_F(Cli, ShortrowTubeKnitsScannedLegAndHeadClosedOnKniterate) {
  CliRun r = run("body make --edge 22 --noise 2 --height 172 --chest 100 --waist 84 --hip 102 --pose a-pose -o " +
                 path("scan.obj"));
  ASSERT_EQ(r.code, 0) << r.err;
  r = run("body fit " + path("scan.obj") + " --objective scan --iterations 20 -o " + path("fitted"));
  ASSERT_EQ(r.code, 0) << r.err;
  for (const std::string part : {"left-leg", "head"}) {
    r = run("body region " + path("fitted") + " --part " + part + " -o " + path(part + ".obj"));
    ASSERT_EQ(r.code, 0) << r.err;
    const std::string out = path(part);
    // the leg with a 16-stitch crown: its closing pairs lie beyond the racking
    r = run("shortrow " + path(part + ".obj") + " --tube --stitch 7x5.6 --machine kniterate --no-report -o " +
            out + (part == "left-leg" ? " --crown-stitches 16" : ""));
    ASSERT_EQ(r.code, 0) << part << ": " << r.err;
    EXPECT_NE(r.err.find("kniterate: VALID, knit graph MATCHES the map"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("closed at the crown"), std::string::npos) << r.err;
    if (part == "left-leg") {
      EXPECT_NE(slurp(fs::path(out) / "knitout.k").find("walks to f"), std::string::npos)
          << "the leg's closing pairs no longer lie beyond the racking limit: find another case for the walk";
    }
    expect_knitted_as_designed(out + "/knitting_map.csv", path(part + ".k"), "shima-swg091n2");
  }
}

// The cap in plain rounds: its last round crosses a fold between needles
// five apart (the machines rack 4), so the bind-off walks that loop over
// the empty needles of the other parity; knitted as designed on both.
TEST_F(Cli, ShortrowTubeBindsOffTheCapBeyondTheRackingLimit) {
  const std::string out = path("cap");
  CliRun r = run("shortrow cap --tube --no-tube-short-rows --no-report --no-predict -o " + out);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.err.find("shima-swg091n2: VALID, knit graph MATCHES the map"), std::string::npos) << r.err;
  EXPECT_NE(slurp(fs::path(out) / "knitout.k").find("walks to b"), std::string::npos)
      << "no bind-off walk: the cap no longer needs one; find another case";
  expect_knitted_as_designed(out + "/knitting_map.csv", path("cap.k"), "kniterate");
}

// --tube on the other design commands: shortcolumn runs the tube route
// (its wales start and end as increases and decreases, the short columns
// of a tube) and refuses its sheet-only options; flatten refuses --tube.
TEST_F(Cli, ShortcolumnTubeKnitsInTheRoundAndFlattenRefusesTube) {
  const std::string out = path("sc_sock");
  CliRun r = run("shortcolumn sock --tube --stitch 7x5.6 --edge 6 --no-report -o " + out);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.err.find("shima-swg091n2: VALID, knit graph MATCHES the map"), std::string::npos) << r.err;
  EXPECT_NE(slurp(fs::path(out) / "knitting_map.csv").find(":close"), std::string::npos);
  r = run("shortcolumn sock --tube --budget 5 -o " + path("sc_bad"));
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("--tube takes no --budget"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(path("sc_bad")));
  r = run("flatten sleeve --tube -o " + path("flat_bad"));
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("use `knitforge shortrow sleeve --tube`"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(path("flat_bad")));
}

// --tube-field: the field is chosen by its divergence estimate (auto), or
// forced; a forced field that cannot be knitted in rounds, an unknown name,
// and the option without --tube are refused with what to do.
TEST_F(Cli, ShortrowTubeFieldIsChosenOrForcedAndBadValuesAreRefused) {
  // The built-in tube is short and wide (h 100 < pi r): its Fiedler vector
  // runs round it, the field orthogonal to that along it.
  const std::string out = path("tube_orth");
  CliRun r = run("shortrow tube --tube --tube-field orthogonal --no-report --no-predict -o " + out);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.err.find("tube: field orthogonal (forced by --tube-field)"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("shima-swg091n2: VALID, knit graph MATCHES the map"), std::string::npos) << r.err;
  const auto report = nlohmann::json::parse(slurp(fs::path(out) / "report.json"));
  EXPECT_EQ(report["field"]["chosen"], "orthogonal");
  EXPECT_EQ(report["field"]["asked"], "orthogonal");
  ASSERT_EQ(report["field"]["candidates"].size(), 3u);
  EXPECT_FALSE(report["field"]["candidates"][1]["knittable"].get<bool>());
  expect_knitted_as_designed(out + "/knitting_map.csv", path("tube_orth.k"), "kniterate");
  r = run("shortrow tube --tube --stitch 7x5.6 --edge 6 --no-report --no-predict --no-knitout -o " +
          path("tube_auto"));
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(
      r.err.find("tube: field harmonic (the lowest knittable); candidates' shaping estimates: harmonic 0, "
                 "fiedler not knittable, orthogonal "),
      std::string::npos)
      << r.err;

  r = run("shortrow tube --tube --tube-field fiedler --no-predict -o " + path("tube_fiedler"));
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("the fiedler field cannot be knitted in rounds: its two rims lie on the same level"),
            std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("try --tube-field auto"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(path("tube_fiedler")));
  r = run("shortrow tube --tube --tube-field geodesic -o " + path("tube_bad"));
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("--tube-field: tube field 'geodesic' is not one of auto"), std::string::npos) << r.err;
  r = run("shortrow tube --tube-field fiedler -o " + path("tube_bad"));
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("--tube-field applies to --tube only"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(path("tube_bad")));
}

// A scanned-style annulus: the sleeve remeshed at 4 mm, every vertex moved
// by up to 1 mm in a pseudo-random direction (a fixed seed), the vertex
// order shuffled; knitted in the round and as designed on both machines.
TEST_F(Cli, ShortrowTubeKnitsANoisyTwoLoopSurface) {
  knitforge::TriMesh m = knitforge::make_shape("sleeve", 4.0);
  uint64_t state = 12345;
  auto uniform = [&state] {  // in [-1, 1)
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    return static_cast<double>(state >> 11) / static_cast<double>(1ULL << 52) - 1.0;
  };
  for (knitforge::Vec3& p : m.vertices) p += knitforge::Vec3(uniform(), uniform(), uniform()) / std::sqrt(3.0);
  std::vector<int> order(static_cast<size_t>(m.num_vertices()));
  for (size_t i = 0; i < order.size(); ++i) order[i] = static_cast<int>(i);
  for (size_t i = order.size() - 1; i > 0; --i)
    std::swap(order[i], order[static_cast<size_t>((uniform() + 1.0) / 2.0 * static_cast<double>(i + 1)) % (i + 1)]);
  knitforge::TriMesh shuffled;
  shuffled.vertices.resize(m.vertices.size());
  for (size_t i = 0; i < order.size(); ++i) shuffled.vertices[static_cast<size_t>(order[i])] = m.vertices[i];
  for (auto f : m.faces) shuffled.faces.push_back({order[f[0]], order[f[1]], order[f[2]]});
  knitforge::write_mesh(path("noisy_sleeve.obj"), shuffled);
  const std::string out = path("noisy");
  CliRun r = run("shortrow " + path("noisy_sleeve.obj") + " --tube --stitch 7x5.6 --machine kniterate --no-report -o " +
                 out);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.err.find("kniterate: VALID, knit graph MATCHES the map"), std::string::npos) << r.err;
  expect_knitted_as_designed(out + "/knitting_map.csv", path("noisy.k"), "shima-swg091n2");
}

// A directory named like a built-in shape (an earlier `-o sock`) does not
// hide the built-in; any other directory is refused as input.
TEST_F(Cli, ABuiltInShapeIsFoundPastADirectoryOfItsName) {
  fs::create_directories(path("tube"));
  fs::create_directories(path("panel"));
  CliRun r = run("shortrow tube --tube --stitch 7x5.6 --edge 8 --no-report --no-knitout -o again", path(""));
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(fs::exists(fs::path(path("again")) / "knitting_map.csv"));
  r = run("shortrow panel --edge 8 -o other", path(""));
  EXPECT_NE(r.code, 0);
  EXPECT_NE(r.err.find("is a directory, not a mesh file"), std::string::npos) << r.err;
}

TEST_F(Cli, ShortrowTubeRefusesASurfaceWithNeitherOneNorTwoLoopsAndWritesNothing) {
  // a closed surface (a tetrahedron, no boundary loop)
  const std::string tet = path("tet.obj");
  {
    std::ofstream f(tet);
    f << "v 0 0 0\nv 100 0 0\nv 0 100 0\nv 0 0 100\nf 1 3 2\nf 1 2 4\nf 2 3 4\nf 1 4 3\n";
  }
  const std::string out = path("tet");
  CliRun r = run("shortrow " + tet + " --tube --edge 5 -o " + out);
  EXPECT_NE(r.code, 0);
  EXPECT_NE(r.err.find("two boundary loops (a tube"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(fs::path(out) / "knitting_map.csv"));
  r = run("shortrow tube --tube --source plane:0,0,1,50 -o " + out);
  EXPECT_NE(r.code, 0);
  EXPECT_NE(r.err.find("--tube takes no --source"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace knitforge_e2e
