// The cases of "any real surface in, a clear answer out" (outputs checked
// first, option values validated, cost bounded up front, one-line messages
// without raw input): exit codes and what the messages say.
#include <algorithm>
#include <cmath>
#include <fstream>

#include "e2e/cli_fixture.h"

using namespace knitforge_e2e;

namespace {

// One line of printable ASCII.
bool one_printable_line(const std::string& s) {
  if (std::count(s.begin(), s.end(), '\n') != 1 || s.back() != '\n') return false;
  return std::all_of(s.begin(), s.end() - 1, [](char c) { return c >= 0x20 && c < 0x7f; });
}

}  // namespace

TEST_F(Cli, OutputsAreCheckedBeforeAnyWork) {
  std::ofstream(path("existing.txt")) << "keep me";
  CliRun r = run("shortrow hemisphere -o " + path("existing.txt"));
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("is not a directory"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("internal error"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("geodesic field"), std::string::npos) << r.err;  // refused before the first stage
  EXPECT_EQ(slurp(path("existing.txt")), "keep me");

  r = run("flatten hemisphere -o ''");
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_NE(r.err.find("empty"), std::string::npos) << r.err;

  ASSERT_EQ(run("sample-map cup -o " + path("cup.csv")).code, 0);
  const std::string map = slurp(path("cup.csv"));
  r = run("knitout " + path("cup.csv") + " -o " + path("cup.csv"));
  EXPECT_EQ(r.code, 1);
  EXPECT_EQ(slurp(path("cup.csv")), map);  // the input is not replaced
  r = run("map " + path("cup.csv") + " -o " + path("cup.csv"));
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("is the input file"), std::string::npos) << r.err;
  EXPECT_EQ(slurp(path("cup.csv")), map);

  fs::create_directories(path("pic.png"));
  r = run("render " + path("cup.csv") + " -o " + path("pic.png"));
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("is a directory"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("Success"), std::string::npos) << r.err;

  r = run("knitout " + path("cup.csv") + " -o " + path("no/such/dir/cup.k"));
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("does not exist"), std::string::npos) << r.err;
  r = run("knitout " + path("cup.csv") + " -o " + path("cup.txt"));
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("use .k"), std::string::npos) << r.err;
}

TEST_F(Cli, OptionValuesAreValidatedAndPrintedReadably) {
  CliRun r = run("shortrow hemisphere --edge 0 -o " + path("o"));
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("--edge: 0 must be a positive number"), std::string::npos) << r.err;
  EXPECT_LT(r.err.size(), 200u) << r.err;  // not DBL_MAX in 309 digits
  ASSERT_EQ(run("sample-map cup -o " + path("cup.csv")).code, 0);
  for (const char* bad : {"--gauge nan", "--gauge inf", "--stitch-number -5", "--speed-number -1",
                          "--waste-rows 1000000000", "--tail-rows -2"}) {
    r = run("knitout " + path("cup.csv") + " " + bad + " -o " + path("cup.k"));
    EXPECT_EQ(r.code, 2) << bad << ": " << r.err;
    EXPECT_FALSE(fs::exists(path("cup.k"))) << bad;
  }
  r = run("flatten hemisphere --stitch 3xnan -o " + path("o"));
  EXPECT_EQ(r.code, 2) << r.err;
  // Indices above 2^31 are printed as given, not as -2147483648.
  r = run("shortrow hemisphere --source vertex:3000000000 -o " + path("o"));
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_NE(r.err.find("3000000000 is not an index"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("-2147483648"), std::string::npos) << r.err;
}

TEST_F(Cli, MissingArgumentsExitTwo) {
  for (const char* cmd : {"shortrow", "flatten", "shape", "sample-map", "knitout", "render hemisphere"}) {
    EXPECT_EQ(run(cmd).code, 2) << cmd;
  }
}

TEST_F(Cli, CostIsEstimatedAndRefusedUpFront) {
  // 0.1 x 0.1 mm on the 150 mm hemisphere: 3.5 million stitches (~9 GB).
  CliRun r = run("shortrow hemisphere --stitch 0.1x0.1 -o " + path("o"));
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("3.53 million stitches"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("--max-stitches"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("geodesic field"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(path("o")));
  r = run("flatten hemisphere --stitch 0.1x0.1 -o " + path("o"));
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("--max-stitches"), std::string::npos) << r.err;
  // The limit is the user's: below the estimate it refuses a normal design too.
  r = run("shortrow hemisphere --max-stitches 1000 -o " + path("o"));
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("limit of 1,000"), std::string::npos) << r.err;

  // One stray face 70 m away: a small area but a huge, nearly empty map
  // (5.2 GB and 77 s on the mannequin panel before).
  ASSERT_EQ(run("shape disk -o " + path("disk.obj")).code, 0);
  {
    std::ofstream f(path("disk.obj"), std::ios::app);
    f << "v 70000 0 0\nv 70001 0 0\nv 70000 1 0\nf -3 -2 -1\n";
  }
  r = run("shortrow " + path("disk.obj") + " -o " + path("o"));
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("stray vertices"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("million cells"), std::string::npos) << r.err;

  r = run("close hemisphere --alpha 0.01 -o " + path("c.stl"));
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("billion triangles"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("--alpha 0.23"), std::string::npos) << r.err;
  r = run("support hemisphere --base rectangle --margin 1e5 -o " + path("s.stl"));
  EXPECT_EQ(r.code, 1);  // 1e12 ran out of memory (now outside the option range: exit 2)
  EXPECT_NE(r.err.find("smaller base margin"), std::string::npos) << r.err;
  r = run("thicken hemisphere --thickness 1e300 -o " + path("t.stl"));
  EXPECT_EQ(r.code, 2);  // was: a 1e300 mm solid with volume nan
  r = run("sample-map random --rows 100000 --cols 100000 -o " + path("r.csv"));
  EXPECT_EQ(r.code, 1);
  EXPECT_FALSE(fs::exists(path("r.csv")));
}

TEST_F(Cli, InputMessagesAreOneLineWithoutRawBytes) {
  // A directory as input.
  fs::create_directories(path("scan.obj"));
  CliRun r = run("flatten " + path("scan.obj") + " -o " + path("o"));
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("is a directory"), std::string::npos) << r.err;
  fs::create_directories(path("prog.k"));
  r = run("simulate " + path("prog.k"));
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("is a directory"), std::string::npos) << r.err;
  r = run("check " + path("scan.obj"));
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("is a directory"), std::string::npos) << r.err;

  // Control bytes and a 5 MB token in an OBJ.
  {
    std::ofstream f(path("junk.obj"), std::ios::binary);
    f << "v 0 0 0\nv 1 0 0\nv 0 1 0\nv \x01\x1b[31m\x07 0 0\n";
  }
  r = run("check " + path("junk.obj"));
  EXPECT_EQ(r.code, 1);
  EXPECT_TRUE(one_printable_line(r.err)) << r.err;
  {
    std::ofstream f(path("long.obj"), std::ios::binary);
    f << "v 0 0 0\nv " << std::string(5'000'000, '7') << "x 0 0\n";
  }
  r = run("check " + path("long.obj"));
  EXPECT_EQ(r.code, 1);
  EXPECT_TRUE(one_printable_line(r.err)) << r.err.substr(0, 300);
  EXPECT_LT(r.err.size(), 1000u);

  // PLY with a format version other than 1.0.
  std::ofstream(path("v2.ply"))
      << "ply\nformat ascii 2.0\nelement vertex 3\nproperty float x\nproperty float y\n"
         "property float z\nelement face 1\nproperty list uchar int vertex_indices\n"
         "end_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
  r = run("check " + path("v2.ply"));
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("1.0"), std::string::npos) << r.err;

  // A number out of range in darts.json names the file and the key.
  std::ofstream(path("darts.json"))
      << R"({"darts": [{"type": "one-end", "points": [{"position": [1e400, 0, 0]}]}]})";
  r = run("flatten hemisphere --darts " + path("darts.json") + " -o " + path("o"));
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("darts.json"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("\"position\""), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("json.exception"), std::string::npos) << r.err;
  EXPECT_TRUE(one_printable_line(r.err)) << r.err;
}

TEST_F(Cli, FlattenCutsAnAnnulusOfAFileAlongOneSeam) {
  // An annulus (two boundary loops) from a file: flatten cuts it into a disk
  // itself, along one seam from the inner to the outer loop (20 mm apart).
  std::ofstream f(path("ring.obj"));
  const int n = 12;
  for (int r = 0; r < 2; ++r)
    for (int s = 0; s < n; ++s)
      f << "v " << (20 + 20 * r) * std::cos(2 * M_PI * s / n) << " "
        << (20 + 20 * r) * std::sin(2 * M_PI * s / n) << " 0\n";
  for (int s = 0; s < n; ++s) {
    const int a = s + 1, b = (s + 1) % n + 1;
    f << "f " << a << " " << a + n << " " << b + n << "\nf " << a << " " << b + n << " " << b << "\n";
  }
  f.close();
  const CliRun flat = run("flatten " + path("ring.obj") + " -o " + path("o"));
  EXPECT_EQ(flat.code, 0) << flat.err;
  EXPECT_NE(flat.err.find("2 boundary loop(s), genus 0) into a disk along 1 seam(s), 20.0 mm"), std::string::npos)
      << flat.err;
  EXPECT_TRUE(fs::exists(path("o") + "/seams.obj"));
}
