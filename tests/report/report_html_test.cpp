// Tests of the report page builder (report/report_html.h): the data object for
// hand-made output directories, the page's escaping, the atomic write, and
// the errors for bad directories and files.
#include "knitforge/report/report_html.h"

#include <gtest/gtest.h>

#include <string>

#include "io/io_test_util.h"
#include "knitforge/core/knitting_map.h"
#include "knitforge/core/stitch_mesh.h"
#include "knitforge/io/gltf.h"
#include "knitforge/io/knitting_map_csv.h"
#include "knitforge/io/mesh_io.h"
#include "knitforge/io/polyline_obj.h"
#include "knitforge/io/stitch_mesh_ply.h"

namespace knitforge {
namespace {

using nlohmann::json;
using test::TempDir;

/// A knit quad with a decrease on top; coordinates that are not multiples of 0.01.
StitchMesh two_stitches() {
  StitchMesh m;
  m.vertices = {Vec3(0.0, 0.0, 0.0), Vec3(3.504, 0.0, 0.0), Vec3(3.5, 2.806, 0.0), Vec3(0.0, 2.8, -1.234),
                Vec3(1.756, 5.0, 0.0)};
  Stitch knit;
  knit.v = {0, 1, 2, 3};
  knit.course = 0;
  knit.wale = 0;
  Stitch dec;
  dec.type = StitchType::Decrease;
  dec.direction = -1;
  dec.v = {3, 2, 4, -1};
  dec.course = 1;
  dec.wale = 0;
  dec.yarn = 2;
  m.stitches = {knit, dec};
  return m;
}

size_t count(const std::string& s, const std::string& what) {
  size_t n = 0;
  for (size_t p = s.find(what); p != std::string::npos; p = s.find(what, p + 1)) ++n;
  return n;
}

TEST(ReportHtml, EmptyDirectoryHasNothingToReport) {
  TempDir dir;
  const std::string msg = test::io_error([&] { report_data(dir.path("")); });
  EXPECT_CONTAINS(msg, "nothing to report");
  EXPECT_CONTAINS(msg, "stitch_mesh.ply");
  EXPECT_EQ(dir.num_files(), 0u);  // nothing written either
  test::io_error([&] { write_report_html(dir.path("")); });
  EXPECT_EQ(dir.num_files(), 0u);
}

TEST(ReportHtml, NotADirectory) {
  TempDir dir;
  const std::string file = dir.write("x.txt", "hello");
  EXPECT_CONTAINS(test::io_error([&] { report_data(file); }), "not a directory");
  EXPECT_CONTAINS(test::io_error([&] { report_data(dir.path("missing")); }), "not a directory");
}

TEST(ReportHtml, DataOfAStitchMeshMapMetricsAndYarn) {
  TempDir dir;
  write_stitch_mesh_ply(dir.path("stitch_mesh.ply"), two_stitches());
  KnittingMap map(2, 3, CellType::Knit);
  map.at(1, 0) = CellType::ShortRowLeft;
  map.at(1, 2) = CellType::Empty;
  write_knitting_map_csv(dir.path("knitting_map.csv"), map);
  dir.write("report.json", R"({"counts": {"stitches": 2}, "knittable": true, "label": "a </script> b"})");
  write_polylines_obj(dir.path("yarn.obj"), {{Vec3(0, 0, 0), Vec3(1.006, 2, 3)}}, {"yarn_0"});

  ReportHtmlOptions opt;
  opt.title = "t";
  const json d = report_data(dir.path(""), opt);
  EXPECT_EQ(d["format"], "knitforge-report");
  EXPECT_EQ(d["title"], "t");
  EXPECT_DOUBLE_EQ(d["scale"].get<double>(), 0.01);

  // Positions are integers in units of 0.01 mm, rounded to nearest.
  const json& sm = d["stitch_mesh"];
  EXPECT_EQ(sm["positions"], json({0, 0, 0, 350, 0, 0, 350, 281, 0, 0, 280, -123, 176, 500, 0}));
  EXPECT_EQ(sm["corners"], json({0, 1, 2, 3, 3, 2, 4, -1}));
  EXPECT_EQ(sm["type"], json({0, 4}));
  EXPECT_EQ(sm["direction"], json({1, -1}));
  EXPECT_EQ(sm["course"], json({0, 1}));
  EXPECT_EQ(sm["wale"], json({0, 0}));
  EXPECT_EQ(sm["yarn"], json({0, 2}));
  EXPECT_TRUE(sm["scalars"].empty());

  // Map cells row-major from row 0 (the CSV lists the top row first).
  EXPECT_EQ(d["map"]["rows"], 2);
  EXPECT_EQ(d["map"]["cols"], 3);
  EXPECT_EQ(d["map"]["cells"], "KKKLK.");
  EXPECT_EQ(d["map"]["direction"], json({1, -1}));
  EXPECT_FALSE(d["map"].contains("yarn"));

  EXPECT_EQ(d["metrics"]["counts"]["stitches"], 2);
  EXPECT_EQ(d["metrics"]["label"], "a </script> b");
  EXPECT_EQ(d["yarn"]["names"], json({"yarn_0"}));
  EXPECT_EQ(d["yarn"]["polylines"], json({json({0, 0, 0, 101, 200, 300})}));

  EXPECT_FALSE(d.contains("target"));
  EXPECT_FALSE(d.contains("knitout"));
  std::vector<std::string> names;
  for (const json& f : d["files"]) names.push_back(f["name"]);
  EXPECT_EQ(names,
            (std::vector<std::string>{"report.json", "stitch_mesh.ply", "knitting_map.csv", "yarn.obj"}));
  ASSERT_EQ(d["notes"].size(), 1u);
  EXPECT_CONTAINS(d["notes"][0].get<std::string>(), "target.ply");
  EXPECT_CONTAINS(d["notes"][0].get<std::string>(), "knitout.k");

  // A coarser resolution rounds to its multiples.
  opt.quantum_mm = 0.5;
  const json coarse = report_data(dir.path(""), opt);
  EXPECT_EQ(coarse["stitch_mesh"]["positions"], json({0, 0, 0, 7, 0, 0, 7, 6, 0, 0, 6, -2, 4, 10, 0}));
}

TEST(ReportHtml, ExtraFacePropertiesBecomeScalarFields) {
  TempDir dir;
  dir.write(
      "stitch_mesh.ply",
      "ply\nformat ascii 1.0\nelement vertex 5\nproperty double x\nproperty double y\nproperty double z\n"
      "element face 2\nproperty list uchar int vertex_indices\nproperty uchar type\nproperty char direction\n"
      "property float shape_error\nproperty double distortion\nproperty uchar red\nend_header\n"
      "0 0 0\n1 0 0\n1 1 0\n0 1 0\n0.5 2 0\n"
      "4 0 1 2 3 0 1 0.25 1.234567 9\n"
      "3 3 2 4 4 -1 0.5 nan 9\n");
  const json d = report_data(dir.path(""));
  const json& sc = d["stitch_mesh"]["scalars"];
  ASSERT_EQ(sc.size(), 2u);  // red is a colour, not a field
  EXPECT_EQ(sc["shape_error"], json({0.25, 0.5}));
  // 5 significant digits of the largest magnitude; NaN becomes null.
  EXPECT_EQ(sc["distortion"][0].get<double>(), 1.2346);
  EXPECT_TRUE(sc["distortion"][1].is_null());
}

TEST(ReportHtml, LongPolylinesAreThinned) {
  TempDir dir;
  std::vector<Vec3> a, b;
  for (int i = 0; i < 8; ++i) a.push_back(Vec3(i, 0, 0));
  for (int i = 0; i < 4; ++i) b.push_back(Vec3(0, i, 0));
  write_polylines_obj(dir.path("yarn.obj"), {a, b}, {"yarn_0", "yarn_1"});
  ReportHtmlOptions opt;
  opt.max_polyline_points = 6;  // 12 points -> every 2nd point and the last
  json d = report_data(dir.path(""), opt);
  EXPECT_EQ(d["yarn"]["polylines"][0], json({0, 0, 0, 200, 0, 0, 400, 0, 0, 600, 0, 0, 700, 0, 0}));
  EXPECT_EQ(d["yarn"]["polylines"][1], json({0, 0, 0, 0, 200, 0, 0, 300, 0}));
  ASSERT_EQ(d["notes"].size(), 2u);
  EXPECT_CONTAINS(d["notes"][0].get<std::string>(),
                  "yarn.obj: 12 points; the page draws one point in 2 (8 points)");
  opt.max_polyline_points = 12;  // at the limit: untouched
  d = report_data(dir.path(""), opt);
  EXPECT_EQ(d["yarn"]["polylines"][0].size(), 24u);
  EXPECT_EQ(d["notes"].size(), 1u);
}

TEST(ReportHtml, RelaxedIsAStitchMeshOrAPlainMesh) {
  TempDir dir;
  TriMesh tri;
  tri.vertices = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0.123)};
  tri.faces = {{0, 1, 2}};
  write_mesh(dir.path("relaxed.ply"), tri);
  write_mesh(dir.path("target.ply"), tri);
  json d = report_data(dir.path(""));
  EXPECT_EQ(d["relaxed"]["kind"], "mesh");
  EXPECT_EQ(d["relaxed"]["triangles"], json({0, 1, 2}));
  EXPECT_EQ(d["target"]["positions"], json({0, 0, 0, 100, 0, 0, 0, 100, 12}));
  EXPECT_FALSE(d["target"].contains("kind"));

  write_stitch_mesh_ply(dir.path("relaxed.ply"), two_stitches());
  d = report_data(dir.path(""));
  EXPECT_EQ(d["relaxed"]["kind"], "stitch_mesh");
  EXPECT_EQ(d["relaxed"]["type"], json({0, 4}));
}

/// A cloth run's outputs for the page, by hand: animation.glb (a garment of
/// one triangle rising 1 mm a frame, a body of two), relaxed.ply, target.ply
/// and cloth.json with per-frame stress (per triangle) and sliding (per vertex).
void write_cloth_run(const TempDir& dir, int frames) {
  std::vector<AnimatedMesh> meshes(2);
  meshes[0].name = "garment";
  meshes[0].faces = {{0, 1, 2}};
  meshes[1].name = "body";
  meshes[1].faces = {{0, 1, 2}, {0, 2, 3}};
  std::vector<double> times;
  json fields = json::array();
  for (int k = 0; k < frames; ++k) {
    times.push_back(0.1 * k);
    meshes[0].frames.push_back({{0, 0, 1.0 * k}, {1, 0, 0}, {0, 1, 0}});
    meshes[1].frames.push_back({{0, 0, -1}, {2, 0, -1}, {2, 2, -1.0 - k}, {0, 2, -1}});
    fields.push_back({{"frame", k},
                      {"stress_kpa", {12.34 * k}},
                      {"sliding_mm", {0.0, 0.5 * k, k == 2 ? json(nullptr) : json(0.013 * k)}}});
  }
  write_animation_glb(dir.path("animation.glb"), meshes, times);
  TriMesh g, b;
  g.faces = meshes[0].faces;
  g.vertices = meshes[0].frames.back();
  b.faces = meshes[1].faces;
  b.vertices = meshes[1].frames.back();
  write_mesh(dir.path("relaxed.ply"), g);
  write_mesh(dir.path("target.ply"), b);
  dir.write("cloth.json", json{{"command", "cloth"},
                               {"result",
                                {{"stress_measure", "largest principal Cauchy stress"},
                                 {"sliding_measure", "distance on the body"}}},
                               {"fields", fields}}
                              .dump());
}

// A cloth run's animation.glb moves the relaxed layer (mesh "garment") and
// the target layer (mesh "body"); long animations are thinned, keeping the last frame.
TEST(ReportHtml, AnimationGlbMovesTheGarmentAndTheBody) {
  TempDir dir;
  write_cloth_run(dir, 5);
  std::filesystem::remove(dir.path("cloth.json"));
  json d = report_data(dir.path(""));
  ASSERT_TRUE(d.contains("animation"));
  const json& r = d["animation"]["layers"]["relaxed"];
  ASSERT_EQ(r["frames"].size(), 5u);
  EXPECT_EQ(r["frames"][3], json({0, 0, 300, 100, 0, 0, 0, 100, 0}));
  EXPECT_NEAR(r["times"][4].get<double>(), 0.4, 1e-6);
  EXPECT_EQ(d["animation"]["layers"]["target"]["frames"][2][8], -300);
  ReportHtmlOptions o;
  o.max_animation_values = 42;  // two frames of the garment and the body (9 + 12 values each)
  d = report_data(dir.path(""), o);
  const json& t = d["animation"]["layers"]["target"];
  ASSERT_EQ(t["frames"].size(), 2u);
  EXPECT_EQ(d["animation"]["layers"]["relaxed"]["times"], t["times"]);
  EXPECT_EQ(t["frames"].back()[8], -500);  // the last frame kept
  EXPECT_NE(d["notes"].dump().find("shown every"), std::string::npos);
  // A layer with other vertices is not animated (a note says so).
  TriMesh b;
  b.vertices = {{0, 0, -1}, {2, 0, -1}, {2, 2, -6}};
  b.faces = {{0, 1, 2}};
  write_mesh(dir.path("target.ply"), b);
  d = report_data(dir.path(""));
  EXPECT_FALSE(d["animation"]["layers"].contains("target"));
  EXPECT_NE(d["notes"].dump().find("not animated"), std::string::npos);
  // Design runs have no animation.glb and no note about it.
  std::filesystem::remove(dir.path("animation.glb"));
  d = report_data(dir.path(""));
  EXPECT_FALSE(d.contains("animation"));
  EXPECT_EQ(d["notes"].dump().find("animation"), std::string::npos);
}

// cloth.json's per-frame stress and sliding colour the garment on the page:
// integers in units of a power of ten (at most 1,000 levels), the colour
// scale of all frames, the measure; thinned frames are those of the geometry.
TEST(ReportHtml, ClothFieldsPerFrameFollowTheGarmentsFrames) {
  TempDir dir;
  write_cloth_run(dir, 7);
  json d = report_data(dir.path(""));
  const json& r = d["animation"]["layers"]["relaxed"];
  ASSERT_TRUE(r.contains("fields")) << d["notes"].dump();
  EXPECT_FALSE(d["animation"]["layers"]["target"].contains("fields"));
  EXPECT_NE(d["files"].dump().find("cloth.json"), std::string::npos);
  const json& s = r["fields"]["stress_kpa"];
  EXPECT_EQ(s["unit"], "kPa");
  EXPECT_EQ(s["per"], "triangle");
  EXPECT_EQ(s["measure"], "largest principal Cauchy stress");
  EXPECT_DOUBLE_EQ(s["step"].get<double>(), 0.1);  // largest 74.04 kPa: 0.1 kPa steps
  EXPECT_EQ(s["range"], json({0.0, 74.04}));       // 5 significant digits
  ASSERT_EQ(s["frames"].size(), 7u);
  for (int k = 0; k < 7; ++k) {
    ASSERT_EQ(s["frames"][k].size(), 1u);
    EXPECT_NEAR(s["frames"][k][0].get<int>() * 0.1, 12.34 * k, 0.05) << k;
  }
  const json& l = r["fields"]["sliding_mm"];
  EXPECT_EQ(l["per"], "vertex");
  EXPECT_EQ(l["unit"], "mm");
  EXPECT_DOUBLE_EQ(l["step"].get<double>(), 0.01);  // largest 3 mm
  EXPECT_EQ(l["frames"][4], json({0, 200, 5}));     // 0.052 mm -> 5 x 0.01
  EXPECT_TRUE(l["frames"][2][2].is_null());         // null stays null

  // Thinned: every layer and field keeps the same frames, the last one too.
  ReportHtmlOptions o;
  o.max_animation_values = 3 * (9 + 12 + 1 + 3);  // three frames of everything
  d = report_data(dir.path(""), o);
  const json& t = d["animation"]["layers"];
  const size_t kept = t["relaxed"]["frames"].size();
  EXPECT_LE(kept, 3u);
  EXPECT_GE(kept, 2u);
  EXPECT_EQ(t["target"]["times"], t["relaxed"]["times"]);
  ASSERT_EQ(t["relaxed"]["fields"]["stress_kpa"]["frames"].size(), kept);
  ASSERT_EQ(t["relaxed"]["fields"]["sliding_mm"]["frames"].size(), kept);
  for (size_t i = 0; i < kept; ++i) {
    const int frame = t["relaxed"]["frames"][i][2].get<int>() / 100;  // the garment rises 1 mm a frame
    EXPECT_NEAR(t["relaxed"]["times"][i].get<double>(), 0.1 * frame, 1e-6);
    EXPECT_EQ(t["target"]["frames"][i][8].get<int>(), -100 - 100 * frame);
    EXPECT_NEAR(t["relaxed"]["fields"]["stress_kpa"]["frames"][i][0].get<int>() * 0.1, 12.34 * frame, 0.05);
    EXPECT_EQ(t["relaxed"]["fields"]["sliding_mm"]["frames"][i][1].get<int>(), 50 * frame);
  }
  EXPECT_EQ(t["relaxed"]["frames"].back()[2], 600);                    // the last frame kept
  EXPECT_EQ(t["relaxed"]["fields"]["stress_kpa"]["range"][1], 74.04);  // the scale of all frames
  EXPECT_NE(d["notes"].dump().find("shown every"), std::string::npos);

  // Fields that do not fit the garment or the frames are left out with a note.
  json c = json::parse(dir.read("cloth.json"));
  c["fields"][3]["stress_kpa"].push_back(1.0);
  dir.write("cloth.json", c.dump());
  d = report_data(dir.path(""));
  EXPECT_FALSE(d["animation"]["layers"]["relaxed"]["fields"].contains("stress_kpa"));
  EXPECT_TRUE(d["animation"]["layers"]["relaxed"]["fields"].contains("sliding_mm"));
  EXPECT_NE(d["notes"].dump().find("stress_kpa is not one value per triangle"), std::string::npos);
  c["fields"].erase(6);
  dir.write("cloth.json", c.dump());
  d = report_data(dir.path(""));
  EXPECT_FALSE(d["animation"]["layers"]["relaxed"].contains("fields"));
  EXPECT_NE(d["notes"].dump().find("6 per-frame fields for the 7 frames"), std::string::npos);
  // Without cloth.json: the geometry moves, uncoloured.
  std::filesystem::remove(dir.path("cloth.json"));
  d = report_data(dir.path(""));
  EXPECT_EQ(d["animation"]["layers"]["relaxed"]["frames"].size(), 7u);
  EXPECT_FALSE(d["animation"]["layers"]["relaxed"].contains("fields"));
}

// predicted.ply (a design's converged predicted shape) is its own layer,
// present only when the file is.
TEST(ReportHtml, PredictedShapeIsALayerWhenPresent) {
  TempDir dir;
  write_stitch_mesh_ply(dir.path("stitch_mesh.ply"), two_stitches());
  json d = report_data(dir.path(""));
  EXPECT_FALSE(d.contains("predicted"));
  EXPECT_NE(d["notes"].dump().find("predicted.ply"), std::string::npos);  // listed as not there
  StitchMesh p = two_stitches();
  p.vertices[4] = Vec3(1.756, 5.0, 0.5);
  StitchMeshPlyOptions ply;
  ply.scalars = {{"shape_error", {0.25, 1.5}}};
  write_stitch_mesh_ply(dir.path("predicted.ply"), p, ply);
  d = report_data(dir.path(""));
  ASSERT_TRUE(d.contains("predicted"));
  EXPECT_EQ(d["predicted"]["kind"], "stitch_mesh");
  EXPECT_EQ(d["predicted"]["positions"][14], 50);
  EXPECT_EQ(d["predicted"]["scalars"]["shape_error"], json({0.25, 1.5}));
  EXPECT_EQ(d["stitch_mesh"]["positions"][14], 0);
  EXPECT_NE(d["files"].dump().find("predicted.ply"), std::string::npos);
  EXPECT_EQ(d["notes"].dump().find("predicted.ply"), std::string::npos);
}

TEST(ReportHtml, KnitoutStatistics) {
  TempDir dir;
  dir.write("knitout.k",
            ";!knitout-2\n;;Carriers: 1 2 3\n;;Machine: NoSuchMachine\nin 3\n"
            "knit + f1 3\nknit + f2 3\nknit - f2 3\nout 3\n");
  const json d = report_data(dir.path(""));
  const json& k = d["knitout"];
  EXPECT_EQ(k["lines"], 8);
  EXPECT_EQ(k["operations"]["knit"], 3);
  EXPECT_EQ(k["operations"]["in"], 1);
  EXPECT_EQ(k["carriers"], json({"1", "2", "3"}));
  EXPECT_CONTAINS(k["simulation"].get<std::string>(), "NoSuchMachine");
}

TEST(ReportHtml, BadFilesAreReportedWithTheirName) {
  TempDir dir;
  dir.write("report.json", "{\"a\": 1,");
  EXPECT_CONTAINS(test::io_error([&] { report_data(dir.path("")); }), "report.json");
  dir.write("report.json", "{}");
  dir.write("knitting_map.csv", "course,dir,0\n0,>,Q\n");
  EXPECT_CONTAINS(test::io_error([&] { report_data(dir.path("")); }), "knitting_map.csv:2");
  dir.write("knitting_map.csv", "course,dir,0\n0,>,K\n");
  ReportHtmlOptions opt;
  opt.quantum_mm = 0.0;
  EXPECT_CONTAINS(test::invalid_input([&] { report_data(dir.path(""), opt); }), "resolution");
}

TEST(ReportHtml, PageEmbedsDataAndViewerAndIsWrittenAtomically) {
  TempDir dir;
  dir.write("report.json", R"({"note": "</script><script>alert(1)</script>", "x": 1.5})");
  ReportHtmlOptions opt;
  opt.title = "a<b";
  const json d = report_data(dir.path(""), opt);
  const std::string page = report_html_page(d);
  // Exactly the two script elements close; the text of report.json cannot.
  EXPECT_EQ(count(page, "</script>"), 2u);
  EXPECT_EQ(count(page, "<script"), 2u);
  EXPECT_CONTAINS(page, "<title>knitforge report: a&lt;b</title>");
  EXPECT_CONTAINS(page, "\\u003c/script>\\u003cscript>alert(1)\\u003c/script>");

  // The data element holds exactly report_data() (after JSON unescaping).
  const std::string open = "<script type=\"application/json\" id=\"knitforge-data\">";
  const size_t a = page.find(open);
  ASSERT_NE(a, std::string::npos);
  const size_t b = page.find("</script>", a);
  EXPECT_EQ(json::parse(page.substr(a + open.size(), b - a - open.size())), d);

  // The viewer is the built web bundle (three.js + the page code).
  const std::string_view script = report_viewer_script();
  EXPECT_GT(script.size(), 100000u);
  EXPECT_NE(script.find("knitforge-data"), std::string_view::npos);
  EXPECT_NE(page.find(script), std::string::npos);

  write_report_html(dir.path(""), opt);
  EXPECT_EQ(dir.read("report.html"), page);
  EXPECT_EQ(dir.num_files(), 2u);  // report.json and report.html, no temporary left

  opt.output = dir.path("elsewhere.html");
  write_report_html(dir.path(""), opt);
  EXPECT_EQ(dir.read("elsewhere.html"), page);
}

}  // namespace
}  // namespace knitforge
