#include "knitforge/report/program_report.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include <unistd.h>

#include "convert/map_test_helpers.h"
#include "knitforge/core/stitch_adjacency.h"
#include "knitforge/io/knitting_map_csv.h"
#include "knitforge/io/stitch_mesh_ply.h"
#include "knitforge/machine/knitout_parse.h"
#include "knitforge/machine/knitout_simulate.h"
#include "knitforge/machine/knitout_writer.h"
#include "knitforge/machine/machine_profile.h"

namespace knitforge {
namespace {

namespace fs = std::filesystem;

const fs::path kData = fs::path(KNITFORGE_TESTS_DIR) / "machine" / "data" / "published_style";

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

class ProgramReportTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("knitforge_program_report_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()) +
            "_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  ProgramReport make(const char* file, const char* machine, ProgramReportOptions o = {}) {
    const std::string text = slurp(kData / file);
    const KnitoutSimulation sim = simulate_knitout(parse_knitout(text), machine_profile(machine));
    o.html = false;
    return write_program_report(file, text, sim, dir_.string(), o);
  }
  fs::path dir_;
};

TEST_F(ProgramReportTest, ASwatchIsDrawnWithItsDropsOnTheLastCourse) {
  const ProgramReport r = make("swatch_drop.k", "kniterate");
  for (const char* f : {"knitout.k", "report.json", "knitting_map.csv", "stitch_mesh.ply", "yarn.obj"})
    EXPECT_TRUE(fs::exists(dir_ / f)) << f;
  EXPECT_EQ(slurp(dir_ / "knitout.k"), slurp(kData / "swatch_drop.k"));
  const nlohmann::json j = nlohmann::json::parse(slurp(dir_ / "report.json"));
  EXPECT_EQ(j, r.json);
  EXPECT_EQ(j["machine"]["verdict"], "VALID");
  EXPECT_EQ(j["fabric"]["kind"], "sheet");
  EXPECT_EQ(j["fabric"]["courses"], 8);
  EXPECT_EQ(j["fabric"]["wales"], 10);
  // one entry per knit pass: 2 tuck passes of the cast-on, 8 courses
  ASSERT_EQ(j["courses"].size(), 10u);
  EXPECT_EQ(j["courses"][2]["knits"], 10);
  EXPECT_EQ(j["courses"][2]["direction"], "+");
  // the ten drops sit on the ten stitches of the last course, at their
  // centroids on the relaxed mesh
  const StitchMesh mesh = read_stitch_mesh_ply((dir_ / "stitch_mesh.ply").string());
  ASSERT_EQ(mesh.num_stitches(), 80);
  ASSERT_EQ(j["diagnostics_placed"], 10);
  std::set<int> stitches;
  for (const auto& d : j["diagnostics"]) {
    EXPECT_EQ(d["check"], "run");
    const int s = d["stitch"];
    stitches.insert(s);
    EXPECT_EQ(mesh.stitches[static_cast<size_t>(s)].course, 7);
    const Vec3 c = stitch_centroid(mesh, s);
    EXPECT_NEAR(d["position"][0].get<double>(), c.x(), 1e-6);
    EXPECT_NEAR(d["position"][1].get<double>(), c.y(), 1e-6);
  }
  EXPECT_EQ(stitches.size(), 10u);
  // the map on disk is the reconstructed one
  EXPECT_EQ(read_knitting_map_csv((dir_ / "knitting_map.csv").string()), r.fabric.map);
  // the stitch size follows the gauge (7: 3.63 mm pitch)
  EXPECT_NEAR(j["fabric"]["stitch_size_mm"][0].get<double>(), 25.4 / 7.0, 1e-9);
}

TEST_F(ProgramReportTest, ATubeIsARingOfStitchesClosedAround) {
  const ProgramReport r = make("tube_loops_left.k", "shima-swg091n2");
  ASSERT_EQ(r.fabric.kind, "tube");
  const StitchMesh mesh = read_stitch_mesh_ply((dir_ / "stitch_mesh.ply").string());
  ASSERT_EQ(mesh.num_stitches(), 8 * 20);
  // closed around: every stitch has a Left and a Right neighbour, and the
  // first and last round only lack their Bottom / Top
  const StitchAdjacency adj(mesh);
  for (int s = 0; s < mesh.num_stitches(); ++s) {
    EXPECT_GE(adj.neighbor(s, Side::Left), 0);
    EXPECT_GE(adj.neighbor(s, Side::Right), 0);
    const int course = mesh.stitches[static_cast<size_t>(s)].course;
    EXPECT_EQ(adj.neighbor(s, Side::Bottom) >= 0, course > 0);
    EXPECT_EQ(adj.neighbor(s, Side::Top) >= 0, course < 7);
  }
  // relaxed from a cylinder of the ring's circumference: a ring of 20
  // stitches of about one pitch each
  double y0 = 1e9, y1 = -1e9, r_sum = 0;
  for (const Vec3& v : mesh.vertices) {
    y0 = std::min(y0, v.y());
    y1 = std::max(y1, v.y());
  }
  Vec3 centre = Vec3::Zero();
  for (const Vec3& v : mesh.vertices) centre += v;
  centre /= static_cast<double>(mesh.num_vertices());
  for (const Vec3& v : mesh.vertices) r_sum += std::hypot(v.x() - centre.x(), v.z() - centre.z());
  const double pitch = 25.4 / 15.0;
  EXPECT_NEAR(r_sum / mesh.num_vertices(), 20 * pitch / (2 * M_PI), 0.1 * 20 * pitch / (2 * M_PI));
  EXPECT_NEAR(y1 - y0, 8 * 0.75 * pitch, 0.2 * 8 * 0.75 * pitch);
  // read back as its tubular map (knit_graph_to_map.h): the map and its yarn
  ASSERT_TRUE(r.fabric.map.tubular());
  EXPECT_EQ(read_knitting_map_csv((dir_ / "knitting_map.csv").string()), r.fabric.map);
  EXPECT_TRUE(fs::exists(dir_ / "yarn.obj"));
  EXPECT_EQ(r.json["fabric"]["rounds"], 8);
  EXPECT_EQ(r.json["fabric"]["ring"], 20);
  EXPECT_EQ(r.json["diagnostics"][0]["check"], "loops-left");
  EXPECT_TRUE(r.json["diagnostics"][0].contains("position"));
}

TEST_F(ProgramReportTest, AShapedTubeIsDrawnFromItsTubularMap) {
  const KnittingMap map = test::small_tapered_tube();
  const KnitoutProgram p = write_knitout(map, machine_profile("kniterate"));
  ProgramReportOptions ro;
  ro.html = false;
  const ProgramReport r = write_program_report("tapered.k", p.text, *p.simulation, dir_.string(), ro);
  ASSERT_EQ(r.fabric.kind, "tube") << r.fabric.reason;
  EXPECT_EQ(read_knitting_map_csv((dir_ / "knitting_map.csv").string()), map);
  EXPECT_EQ(read_stitch_mesh_ply((dir_ / "stitch_mesh.ply").string()).num_stitches(), map.num_stitches());
  EXPECT_EQ(r.json["fabric"]["courses"], 8);
  EXPECT_EQ(r.json["fabric"]["rounds"], 8);
  EXPECT_EQ(r.json["fabric"]["wales"], 16);
  EXPECT_FALSE(r.json["fabric"].contains("ring"));  // the rounds change
}

TEST_F(ProgramReportTest, AFabricThatIsNoSheetIsReportedNotDrawn) {
  const ProgramReport r = make("split_increase.k", "generic");
  EXPECT_EQ(r.json["fabric"]["kind"], "none");
  EXPECT_FALSE(r.json["fabric"]["reason"].get<std::string>().empty());
  EXPECT_FALSE(fs::exists(dir_ / "stitch_mesh.ply"));
  EXPECT_TRUE(fs::exists(dir_ / "report.json"));
  EXPECT_EQ(r.json["diagnostics_placed"], 0);
  // and a limit on what is drawn
  ProgramReportOptions small;
  small.max_stitches = 10;
  const ProgramReport s = make("swatch_drop.k", "kniterate", small);
  EXPECT_FALSE(fs::exists(dir_ / "yarn.obj"));
  EXPECT_FALSE(fs::exists(dir_ / "stitch_mesh.ply"));
  EXPECT_NE(s.json["notes"][0].get<std::string>().find("more than the 10 drawn"), std::string::npos);
}

}  // namespace
}  // namespace knitforge
