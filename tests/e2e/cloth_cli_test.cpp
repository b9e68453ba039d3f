// End-to-end runs of `knitforge cloth` (docs/sim.md, "Garments on a moving
// body"): a small built-in sleeve scene writes every output, and they parse;
// bad scenes and runs over the work limit are refused with one line.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <sstream>
#include <vector>

#include <nlohmann/json.hpp>

#include "e2e/cli_fixture.h"
#include "geometry/test_meshes.h"
#include "knitforge/io/mesh_io.h"

namespace knitforge_e2e {
namespace {

using nlohmann::json;

uint32_t u32(const std::string& s, size_t at) {
  uint32_t v = 0;
  for (int k = 3; k >= 0; --k) v = (v << 8) | static_cast<uint8_t>(s[at + static_cast<size_t>(k)]);
  return v;
}

// The vertex coordinates of an OBJ file, x y z in order.
std::vector<double> obj_vertices(const std::string& text) {
  std::vector<double> v;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) {
    std::istringstream l(line);
    std::string tag;
    double x, y, z;
    if (l >> tag && tag == "v" && l >> x >> y >> z) v.insert(v.end(), {x, y, z});
  }
  return v;
}

class ClothCli : public Cli {
 protected:
  void write(const std::string& name, const std::string& text) {
    std::ofstream(path(name)) << text;
  }
};

constexpr const char* kSmallSleeve = R"({"builtin": "sleeve", "frames": 3, "frame_rate_hz": 20, "substeps": 1, "newton": {"max_iterations": 8},
  "arm": {"upper_length_mm": 110, "forearm_length_mm": 100, "upper_radius_mm": 30, "forearm_radius_mm": 26,
          "body_edge_mm": 10, "sleeve_edge_mm": 9, "transition_mm": 40, "max_angle_deg": 45}})";

TEST_F(ClothCli, SmallSleeveWritesEveryOutput) {
  write("scene.json", kSmallSleeve);
  const CliRun r = run("cloth " + path("scene.json") + " -o " + path("out"));
  ASSERT_EQ(r.code, 0) << r.err;
  const json c = json::parse(slurp(path("out/cloth.json")));
  ASSERT_EQ(c["frames"].size(), 4u);
  EXPECT_DOUBLE_EQ(c["frames"][0]["elbow_angle_deg"].get<double>(), 0.0);
  EXPECT_DOUBLE_EQ(c["frames"][3]["elbow_angle_deg"].get<double>(), 45.0);
  const int nv = c["setup"]["garment_vertices"].get<int>(), nt = c["setup"]["garment_triangles"].get<int>();
  const int nb = c["setup"]["body_vertices"].get<int>();
  for (size_t f = 1; f < 4; ++f) {
    EXPECT_GT(c["frames"][f]["newton_iterations"].get<int>() + c["frames"][f]["quasi_newton_iterations"].get<int>(), 0);
    EXPECT_GE(c["frames"][f]["factorizations"].get<int>(), 1);
    EXPECT_GT(c["frames"][f]["min_distance_mm"].get<double>(), 0.0);
    // Signed, to the true capsules: inside by at most the meshes' chord sag.
    EXPECT_GT(c["frames"][f]["min_arm_clearance_mm"].get<double>(), -0.8);
    EXPECT_TRUE(c["frames"][f]["energy_uj"]["elastic"].is_number());
  }
  ASSERT_EQ(c["fields"].size(), 4u);
  EXPECT_EQ(c["fields"][2]["stress_kpa"].size(), static_cast<size_t>(nt));
  EXPECT_EQ(c["fields"][2]["sliding_mm"].size(), static_cast<size_t>(nv));
  EXPECT_EQ(c["max_stress_kpa_per_triangle"].size(), static_cast<size_t>(nt));
  EXPECT_GT(c["result"]["min_distance_mm"].get<double>(), 0.0);
  EXPECT_GT(c["result"]["quasi_newton_iterations"].get<int>(), 0);  // the L-BFGS phase is on by default
  EXPECT_GT(c["result"]["min_arm_clearance_mm"].get<double>(), -0.8);
  EXPECT_LT(c["result"]["min_arm_clearance_mm"].get<double>(), 5.0);  // the 5 mm clearance at the start
  // The glTF: a valid container, two meshes with frames - 1 morph targets and the right counts.
  const std::string glb = slurp(path("out/animation.glb"));
  ASSERT_GT(glb.size(), 28u);
  EXPECT_EQ(glb.substr(0, 4), "glTF");
  EXPECT_EQ(u32(glb, 8), glb.size());
  const json g = json::parse(glb.substr(20, u32(glb, 12)));
  EXPECT_EQ(g["asset"]["version"], "2.0");
  ASSERT_EQ(g["meshes"].size(), 2u);
  const json& garment = g["meshes"][0]["primitives"][0];
  const json& body = g["meshes"][1]["primitives"][0];
  EXPECT_EQ(g["accessors"][garment["attributes"]["POSITION"].get<int>()]["count"].get<int>(), nv);
  EXPECT_EQ(g["accessors"][garment["indices"].get<int>()]["count"].get<int>(), 3 * nt);
  EXPECT_EQ(g["accessors"][body["attributes"]["POSITION"].get<int>()]["count"].get<int>(), nb);
  EXPECT_EQ(garment["targets"].size(), 3u);
  EXPECT_EQ(body["targets"].size(), 3u);
  ASSERT_EQ(g["animations"].size(), 1u);
  const int input = g["animations"][0]["samplers"][0]["input"].get<int>();
  EXPECT_EQ(g["accessors"][input]["count"].get<int>(), 4);
  EXPECT_NEAR(g["accessors"][input]["max"][0].get<double>(), 3.0 / 20.0, 1e-6);
  // The sequence, the coloured PLYs, the report.
  for (const char* f : {"frames/0000_garment.obj", "frames/0003_garment.obj", "frames/0003_body.obj",
                        "frames/0003_garment.ply", "maxima.ply", "report.json", "report.html", "material.json"}) {
    EXPECT_TRUE(fs::exists(path("out/") + f)) << f;
  }
  const json rep = json::parse(slurp(path("out/report.json")));
  EXPECT_EQ(rep["command"], "cloth");
  EXPECT_FALSE(rep.contains("fields"));  // the page's metrics stay small
  // The page colours the garment by cloth.json's stress and sliding of every
  // frame: the embedded values are the run's, to within half a step.
  const json data = report_page_data(path("out/report.html"));
  const json& fields = data["animation"]["layers"]["relaxed"]["fields"];
  ASSERT_EQ(data["animation"]["layers"]["relaxed"]["frames"].size(), 4u);
  for (const char* key : {"stress_kpa", "sliding_mm"}) {
    const json& f = fields[key];
    ASSERT_EQ(f["frames"].size(), 4u) << key;
    const double step = f["step"].get<double>();
    double top = 0;
    for (size_t k = 0; k < 4; ++k) {
      ASSERT_EQ(f["frames"][k].size(), c["fields"][k][key].size()) << key;
      for (size_t e = 0; e < f["frames"][k].size(); ++e) {
        const double v = c["fields"][k][key][e].get<double>();
        top = std::max(top, v);
        ASSERT_NEAR(f["frames"][k][e].get<int64_t>() * step, v, 0.5 * step + 1e-9) << key << " frame " << k;
      }
    }
    EXPECT_NEAR(f["range"][1].get<double>(), top, 1e-4 * top) << key;
    EXPECT_LE(top / step, 1000.0) << key;
    if (top > 0) {
      EXPECT_GT(top / step, 100.0) << key;  // 100 to 1,000 levels
    }
  }
  EXPECT_EQ(fields["stress_kpa"]["per"], "triangle");
  EXPECT_EQ(fields["stress_kpa"]["measure"], c["result"]["stress_measure"]);
  EXPECT_EQ(fields["sliding_mm"]["per"], "vertex");

  // The animation.glb drives a second run as its body (glTF input, morph
  // targets): the run takes the animation's length (3 frames at 20 Hz) and
  // its body moves as the first run's did. Its solves are cut short (10
  // L-BFGS and 2 Newton iterations a step: 4.5 s instead of 55 s under
  // ASan); the body's motion is what is checked, and the fabric stays out.
  write("again.json", R"({"garment": {"mesh": "out/frames/0000_garment.obj",
                                      "course_axis": {"point": [0, 0, 0], "direction": [1, 0, 0]}},
                          "body": {"animation": "out/animation.glb", "mesh_name": "body"},
                          "frame_rate_hz": 20, "substeps": 1, "newton": {"max_iterations": 2}})");
  const CliRun r2 = run("cloth " + path("again.json") + " --quasi-newton 10 -o " + path("again"));
  ASSERT_EQ(r2.code, 0) << r2.err;
  const json c2 = json::parse(slurp(path("again/cloth.json")));
  EXPECT_EQ(c2["scene"]["frames"], 3);
  EXPECT_EQ(c2["setup"]["body_vertices"], nb);
  for (const char* f : {"frames/0001_body.obj", "frames/0003_body.obj"}) {
    const std::vector<double> a = obj_vertices(slurp(path("out/") + f)), b = obj_vertices(slurp(path("again/") + f));
    ASSERT_EQ(a.size(), b.size()) << f;
    ASSERT_EQ(a.size(), 3u * static_cast<size_t>(nb));
    double worst = 0;
    for (size_t i = 0; i < a.size(); ++i) worst = std::max(worst, std::abs(a[i] - b[i]));
    EXPECT_LT(worst, 1e-3) << f;  // float32 in the file
  }
  EXPECT_GT(c2["result"]["min_distance_mm"].get<double>(), 0.0);
  // Longer than the animation: refused with the frames that fit; a mesh name the file lacks: its names.
  CliRun r3 = run("cloth " + path("again.json") + " --frames 5 -o " + path("again5"));
  EXPECT_NE(r3.code, 0);
  EXPECT_NE(r3.err.find("set \"frames\" to at most 3"), std::string::npos) << r3.err;
  write("noname.json", R"({"garment": {"mesh": "out/frames/0000_garment.obj", "course_direction": [0, 0, 1]},
                           "body": {"animation": "out/animation.glb", "mesh_name": "arm"}})");
  r3 = run("cloth " + path("noname.json") + " -o " + path("noname"));
  EXPECT_NE(r3.code, 0);
  EXPECT_NE(r3.err.find("no node or mesh of the scene is named 'arm' (names: 'body', 'garment')"), std::string::npos)
      << r3.err;
  EXPECT_FALSE(fs::exists(path("again5/cloth.json")));
}

// A skinned glTF body: the seed fuzz/make_gltf_seeds.py writes (a strip
// whose hips move 10 mm along x over 1 s while its spine turns 90 degrees
// about z; two joint sets, its node's own translation to be ignored). The
// run lasts the animation, the body's frames are the skinned positions
// (read_gltf_animation_test.cpp checks the same points), and a sheet far
// above it, without gravity, stays where it is.
TEST_F(ClothCli, SkinnedGltfBodyMovesByItsJoints) {
  write("sheet.obj", "v 0 0 50\nv 10 0 50\nv 10 10 50\nv 0 10 50\nf 1 2 3\nf 1 3 4\n");
  const std::string seed = std::string(KNITFORGE_TESTS_DIR) + "/../fuzz/corpus/fuzz_gltf_animation/skinned.glb";
  write("skin.json", R"({"garment": {"mesh": "sheet.obj", "course_direction": [1, 0, 0]},
                         "body": {"animation": ")" + seed + R"("},
                         "frame_rate_hz": 4, "substeps": 1, "gravity_mm_s2": [0, 0, 0]})");
  const CliRun r = run("cloth " + path("skin.json") + " -o " + path("skin"));
  ASSERT_EQ(r.code, 0) << r.err;
  const json c = json::parse(slurp(path("skin/cloth.json")));
  EXPECT_EQ(c["scene"]["frames"], 4);
  EXPECT_EQ(c["setup"]["body_vertices"], 4);
  // Vertex k of an OBJ file written by the run is within 1e-4 mm of (x, y, z).
  auto near = [&](const std::string& file, size_t k, double x, double y, double z) {
    const std::vector<double> v = obj_vertices(slurp(path("skin/frames/") + file));
    ASSERT_EQ(v.size(), 12u) << file;
    EXPECT_LT(std::hypot(v[3 * k] - x, v[3 * k + 1] - y, v[3 * k + 2] - z), 1e-4) << file << " vertex " << k;
  };
  near("0000_body.obj", 3, 1, 1, 0);
  near("0004_body.obj", 1, 11, 0, 0);  // the hips' only
  near("0004_body.obj", 3, 10, 1, 0);  // half the hips, half the turned spine
  near("0004_garment.obj", 2, 10, 10, 50);
}

// The built-in legging, small: the knee angle per frame, the signed
// clearance to the true leg, every output.
// --quasi-newton 0: Newton alone, as before the L-BFGS phase.
TEST_F(ClothCli, QuasiNewtonZeroIsNewtonAlone) {
  write("scene.json", kSmallSleeve);
  const CliRun r = run("cloth " + path("scene.json") + " --frames 1 --quasi-newton 0 -o " + path("out"));
  ASSERT_EQ(r.code, 0) << r.err;
  const json c = json::parse(slurp(path("out/cloth.json")));
  EXPECT_EQ(c["result"]["quasi_newton_iterations"].get<int>(), 0);
  EXPECT_GT(c["result"]["newton_iterations"].get<int>(), 0);
  EXPECT_GE(c["result"]["factorizations"].get<int>(), c["result"]["newton_iterations"].get<int>());
  EXPECT_GT(c["result"]["min_distance_mm"].get<double>(), 0.0);
}

// --preview: projective dynamics instead of Newton; labelled so in cloth.json,
// the rounds counted, every output written, and the sleeve kept outside the
// true arm (by at most the meshes' chord sag, as the implicit run).
TEST_F(ClothCli, PreviewRunsProjectiveDynamics) {
  write("scene.json", kSmallSleeve);
  const CliRun r = run("cloth " + path("scene.json") + " --preview -o " + path("out"));
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.err.find("preview rounds"), std::string::npos) << r.err;
  const json c = json::parse(slurp(path("out/cloth.json")));
  EXPECT_EQ(c["result"]["solver"], "preview");
  EXPECT_EQ(c["result"]["newton_iterations"].get<int>(), 0);
  EXPECT_EQ(c["result"]["quasi_newton_iterations"].get<int>(), 0);
  // One a step; this fast bend (15 degrees a step) splits steps, as the implicit solver's.
  EXPECT_EQ(c["result"]["factorizations"].get<int>(), c["result"]["steps"].get<int>());
  EXPECT_GT(c["result"]["steps"].get<int>(), 3);
  ASSERT_EQ(c["frames"].size(), 4u);
  for (size_t f = 1; f < 4; ++f) {
    EXPECT_GE(c["frames"][f]["preview_iterations"].get<int>(), 1);
    EXPECT_TRUE(c["frames"][f]["seconds"].contains("rounds_s"));
    EXPECT_GT(c["frames"][f]["min_arm_clearance_mm"].get<double>(), -0.8);
  }
  EXPECT_NE(c["result"]["penetration"].get<std::string>().find("preview (projective dynamics)"), std::string::npos);
  for (const char* f : {"animation.glb", "frames/0003_garment.ply", "report.html", "last_frame.png"})
    EXPECT_TRUE(fs::exists(path("out/") + f)) << f;
  EXPECT_NE(run("cloth " + path("scene.json") + " --preview --preview-iterations 0 -o " + path("out2")).code, 0);
}

// The scene asks for the preview; --preview-iterations and --max-work apply
// to it, --implicit overrides it.
TEST_F(ClothCli, ASceneAsksForThePreview) {
  json scene = json::parse(kSmallSleeve);
  scene["solver"] = "preview";
  scene["preview"] = {{"max_iterations", 7}};
  write("scene.json", scene.dump());
  CliRun r = run("cloth " + path("scene.json") + " -o " + path("out"));
  ASSERT_EQ(r.code, 0) << r.err;
  json c = json::parse(slurp(path("out/cloth.json")));
  EXPECT_EQ(c["result"]["solver"], "preview");
  EXPECT_EQ(c["scene"]["preview"]["max_iterations"], 7);
  for (size_t f = 1; f < c["frames"].size(); ++f)  // the frame's rounds, over its (split) steps
    EXPECT_LE(c["frames"][f]["preview_iterations"].get<int>(), 7 * c["frames"][f]["steps"].get<int>());
  EXPECT_GT(c["result"]["preview_iterations"].get<int>(), 7);
  r = run("cloth " + path("scene.json") + " --preview-iterations 3 -o " + path("out3"));
  ASSERT_EQ(r.code, 0) << r.err;
  const int rounds7 = c["result"]["preview_iterations"].get<int>();
  c = json::parse(slurp(path("out3/cloth.json")));
  EXPECT_EQ(c["scene"]["preview"]["max_iterations"], 3);
  EXPECT_LE(c["result"]["preview_iterations"].get<int>(), 3 * c["result"]["steps"].get<int>());
  EXPECT_LT(c["result"]["preview_iterations"].get<int>(), rounds7);
  // The preview's own limit, its rounds counted: refused, nothing written.
  r = run("cloth " + path("scene.json") + " --preview-iterations 3000 --max-work 1e5 -o " + path("out4"));
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("the preview (garment vertices x frames x substeps x rounds / 30)"), std::string::npos)
      << r.err;
  EXPECT_FALSE(fs::exists(path("out4")));
  // --implicit: the implicit solver; then --preview-iterations does not apply.
  r = run("cloth " + path("scene.json") + " --implicit --preview-iterations 3 -o " + path("out5"));
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("--preview-iterations applies to the preview only"), std::string::npos) << r.err;
  EXPECT_NE(run("cloth " + path("scene.json") + " --implicit --preview -o " + path("out6")).code, 0);
}

TEST_F(ClothCli, SmallLeggingBendsTheKnee) {
  write("leg.json", R"({"builtin": "legging", "frames": 2, "frame_rate_hz": 20, "substeps": 2,
    "newton": {"max_iterations": 6},
    "leg": {"thigh_length_mm": 100, "shin_length_mm": 90, "thigh_radius_mm": 28, "shin_radius_mm": 24,
            "body_edge_mm": 10, "legging_edge_mm": 8, "transition_mm": 30, "max_angle_deg": 40}})");
  // At most 40 L-BFGS iterations a step (the default 400 is SmallSleeve's):
  // the same clearance (-0.47 mm) in 8.6 s instead of 20 s under ASan.
  const CliRun r = run("cloth " + path("leg.json") + " --quasi-newton 40 -o " + path("out"));
  ASSERT_EQ(r.code, 0) << r.err;
  const json c = json::parse(slurp(path("out/cloth.json")));
  ASSERT_EQ(c["frames"].size(), 3u);
  EXPECT_EQ(c["scene"]["builtin"], "legging");
  EXPECT_DOUBLE_EQ(c["scene"]["leg"]["thigh_length_mm"].get<double>(), 100.0);
  EXPECT_DOUBLE_EQ(c["frames"][2]["knee_angle_deg"].get<double>(), 40.0);
  EXPECT_GT(c["result"]["min_leg_clearance_mm"].get<double>(), -0.8);
  EXPECT_GT(c["result"]["min_distance_mm"].get<double>(), 0.0);
  for (const char* f : {"animation.glb", "frames/0002_garment.ply", "frames/0002_body.obj", "report.html"})
    EXPECT_TRUE(fs::exists(path("out/") + f)) << f;
}

// A stitch mesh as the garment (the cup of `relax`, a knitting map, a design
// directory): the model's triangles are the garment (knit quads split in two,
// shaping stitches one triangle), the courses and rest size are the stitches'.
TEST_F(ClothCli, StitchMeshGarmentFallsOntoAPlate) {
  ASSERT_EQ(run("sample-map cup -o " + path("map.csv")).code, 0);
  ASSERT_EQ(run("relax " + path("map.csv") + " -o " + path("cup.ply")).code, 0);
  write("plate.obj", "v -50 -50 -30\nv 200 -50 -30\nv 200 100 -30\nv -50 100 -30\nf 1 2 3\nf 1 3 4\n");
  const std::string header = slurp(path("cup.ply")).substr(0, 400);
  const size_t at = header.find("element vertex ");
  ASSERT_NE(at, std::string::npos);
  const int nv = std::stoi(header.substr(at + 15));
  const std::string run_fields = R"(, "body": {"mesh": "plate.obj"}, "frames": 1, "substeps": 1, "newton": {"max_iterations": 4}})";
  // What is read is tested here, not the solve: 10 L-BFGS iterations (0.9 s a run under ASan, 5.4 s with the default 400).
  const std::string short_solve = " --quasi-newton 10";
  write("cup.json", R"({"garment": {"stitch_mesh": "cup.ply"})" + run_fields);
  CliRun r = run("cloth " + path("cup.json") + short_solve + " -o " + path("out"));
  ASSERT_EQ(r.code, 0) << r.err;
  json c = json::parse(slurp(path("out/cloth.json")));
  EXPECT_EQ(c["setup"]["garment_vertices"], nv);
  EXPECT_EQ(c["setup"]["garment"]["stitches"], 1288);
  EXPECT_EQ(c["setup"]["garment"]["stitch_size_from"], "default");
  const int nt = c["setup"]["garment_triangles"].get<int>();
  EXPECT_GT(nt, 1288);
  EXPECT_LE(nt, 2 * 1288);
  EXPECT_EQ(c["fields"][1]["stress_kpa"].size(), static_cast<size_t>(nt));
  EXPECT_TRUE(fs::exists(path("out/frames/0001_garment.ply")));
  // The map itself, relaxed on the way; then a design directory whose report.json gives the stitch size.
  write("map.json", R"({"garment": {"stitch_mesh": "map.csv", "stitch_size": "3.5x2.8"})" + run_fields);
  r = run("cloth " + path("map.json") + short_solve + " -o " + path("out_map"));
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(json::parse(slurp(path("out_map/cloth.json")))["setup"]["garment"]["stitches"], 1288);
  fs::create_directories(path("design"));
  fs::copy_file(path("cup.ply"), path("design/stitch_mesh.ply"));
  write("design/report.json", R"({"parameters": {"stitch_width_mm": 4, "stitch_height_mm": 3}})");
  write("design.json", R"({"garment": {"design": "design"})" + run_fields);
  r = run("cloth " + path("design.json") + short_solve + " -o " + path("out_design"));
  ASSERT_EQ(r.code, 0) << r.err;
  c = json::parse(slurp(path("out_design/cloth.json")));
  EXPECT_DOUBLE_EQ(c["setup"]["garment"]["stitch_width_mm"].get<double>(), 4.0);
  EXPECT_NE(c["setup"]["garment"]["stitch_size_from"].get<std::string>().find("report.json"), std::string::npos);
  // Refused: a directory without a stitch mesh, a course direction with a stitch mesh.
  fs::create_directories(path("empty"));
  write("empty.json", R"({"garment": {"design": "empty"})" + run_fields);
  r = run("cloth " + path("empty.json") + " -o " + path("out_empty"));
  EXPECT_NE(r.code, 0);
  EXPECT_NE(r.err.find("not a design directory (no stitch_mesh.ply)"), std::string::npos) << r.err;
  write("course.json", R"({"garment": {"stitch_mesh": "cup.ply", "course_direction": [1, 0, 0]})" + run_fields);
  r = run("cloth " + path("course.json") + " -o " + path("out_course"));
  EXPECT_NE(r.code, 0);
  EXPECT_NE(r.err.find("a stitch mesh has its own courses"), std::string::npos) << r.err;
}

TEST_F(ClothCli, BadScenesAreRefusedWithOneLine) {
  write("typo.json", R"({"builtin": "sleeve", "frame": 3})");
  CliRun r = run("cloth " + path("typo.json") + " -o " + path("out"));
  EXPECT_NE(r.code, 0);
  EXPECT_NE(r.err.find("unknown field 'frame'"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(path("out/cloth.json")));
  write("broken.json", R"({"builtin": )");
  r = run("cloth " + path("broken.json") + " -o " + path("out"));
  EXPECT_NE(r.code, 0);
  EXPECT_NE(r.err.find("not valid JSON"), std::string::npos) << r.err;
  write("nobody.json",
        R"({"garment": {"mesh": "missing.obj", "course_direction": [1, 0, 0]}, "body": {"mesh": "missing.obj"}})");
  r = run("cloth " + path("nobody.json") + " -o " + path("out"));
  EXPECT_NE(r.code, 0);
  EXPECT_NE(r.err.find("missing.obj"), std::string::npos) << r.err;
  r = run("cloth " + path("typo.json") + " --builtin sleeve -o " + path("out"));
  EXPECT_EQ(r.code, 2);
  r = run("cloth --builtin sleeve --max-work 1000 -o " + path("out"));
  EXPECT_NE(r.code, 0);
  EXPECT_NE(r.err.find("--max-work"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(path("out/cloth.json")));
  // glTF bodies: a file that is not glTF, a mesh name the file lacks, a run longer than the animation.
  write("sheet.obj", "v 0 0 0\nv 10 0 0\nv 0 10 0\nf 1 2 3\n");
  write("fake.glb", "glTF but not really");
  write("gl.json", R"({"garment": {"mesh": "sheet.obj", "course_direction": [1, 0, 0]}, "body": {"animation": "fake.glb"}})");
  r = run("cloth " + path("gl.json") + " -o " + path("out"));
  EXPECT_NE(r.code, 0);
  EXPECT_NE(r.err.find("fake.glb"), std::string::npos) << r.err;
  write("legarm.json", R"({"builtin": "legging", "arm": {}})");
  r = run("cloth " + path("legarm.json") + " -o " + path("out"));
  EXPECT_NE(r.code, 0);
  EXPECT_NE(r.err.find("'arm' is a parameter of the built-in sleeve"), std::string::npos) << r.err;
}

}  // namespace

// Dressing a body: a design made on a surface (the built-in hemisphere,
// r 75) worn on a closed body a little larger (a sphere of r 75.5), so its
// stitch mesh starts just inside the body's facets. As given it is refused;
// with garment.clearance_mm the start is moved out and the run goes.
TEST_F(ClothCli, ADesignIsDressedOntoTheBodyItWasMadeOn) {
  const CliRun d = run("shortrow hemisphere --stitch 7x5.6 --edge 6 --no-report --no-knitout --no-predict -o " +
                       path("design"));
  ASSERT_EQ(d.code, 0) << d.err;
  knitforge::write_mesh(path("ball.obj"), knitforge::test::uv_sphere_mesh(75.5, 48, 24));
  json scene = {{"garment", {{"design", "design"}}},
                {"body", {{"mesh", "ball.obj"}}},
                {"frames", 1},
                {"substeps", 1},
                {"newton", {{"max_iterations", 8}}}};
  write("as_given.json", scene.dump());
  CliRun r = run("cloth " + path("as_given.json") + " -o " + path("out0"));
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("free garment vertices start inside the body"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(path("out0")));
  scene["garment"]["clearance_mm"] = 1.0;
  write("dressed.json", scene.dump());
  r = run("cloth " + path("dressed.json") + " -o " + path("out"));
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.err.find("cloth: dressed: "), std::string::npos) << r.err;
  const json c = json::parse(slurp(path("out/cloth.json")));
  const json& dress = c["setup"]["dress"];
  // (nearly all: the stitch mesh lies on the design's own facets, a few of
  // its vertices more than the clearance outside the ball's)
  EXPECT_GT(dress["moved"].get<int>(), 0.95 * c["setup"]["garment_vertices"].get<int>());
  EXPECT_GT(dress["inside"].get<int>(), 0.95 * dress["moved"].get<int>());
  EXPECT_LE(dress["inside"].get<int>(), dress["moved"].get<int>());
  // 0.5 mm (the ball's extra radius) plus the ball's and the design's
  // facets (measured: 0.597 mm, largest move 1.597 mm)
  EXPECT_GT(dress["deepest_mm"].get<double>(), 0.3);
  EXPECT_LT(dress["deepest_mm"].get<double>(), 0.9);
  EXPECT_LT(dress["largest_move_mm"].get<double>(), 1.9);
  EXPECT_EQ(c["scene"]["garment"]["clearance_mm"], 1.0);
  EXPECT_GT(c["result"]["min_distance_mm"].get<double>(), 0.0);
}

}  // namespace knitforge_e2e
