#include "knitforge/io/stitch_mesh_ply.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <sstream>

#include "io/io_test_util.h"
#include "knitforge/io/colours.h"
#include "knitforge/io/ply.h"
#include "knitforge/util/errors.h"

namespace knitforge {
namespace {

using test::TempDir;

// Two courses of knit stitches with a short-row end on each side of course 0
// and a decrease/increase pair on top of it; awkward doubles everywhere.
StitchMesh small_stitch_mesh() {
  StitchMesh m;
  for (int j = 0; j < 3; ++j) {
    for (int i = 0; i < 3; ++i) {
      m.vertices.emplace_back(3.5 * i + 1e-15 * (i + j), 2.8 * j / 3.0, std::exp(i - j) * 1e-300);
    }
  }
  m.vertices.emplace_back(8.75, 1.4, -0.0);     // 9: apex right
  m.vertices.emplace_back(-1.75, 1.4, 5e-324);  // 10: apex left (denormal z)
  auto add = [&](StitchType t, int8_t dir, std::array<int, 4> v, int course, int wale, int yarn,
                 uint8_t roles) {
    Stitch s;
    s.type = t;
    s.direction = dir;
    s.v = v;
    s.course = course;
    s.wale = wale;
    s.yarn = yarn;
    s.roles = roles;
    m.stitches.push_back(s);
  };
  add(StitchType::Knit, 1, {0, 1, 4, 3}, 0, 1, 0, kRoleCastOn);
  add(StitchType::Knit, 1, {1, 2, 5, 4}, 0, 2, 0, kRoleCastOn);
  add(StitchType::Knit, -1, {3, 4, 7, 6}, 1, 1, 3, kRoleBindOff);
  add(StitchType::ShortRowRight, 1, {2, 9, 5, -1}, 0, 3, 0, kRoleCastOn | kRoleOutsideIncrease);
  add(StitchType::ShortRowLeft, 1, {10, 0, 3, -1}, 0, 0, -2, kRoleCastOn);
  add(StitchType::Decrease, -1, {4, 5, 8, -1}, 1, 2, 2147483647, 15);
  add(StitchType::Increase, -1, {4, 8, 7, -1}, -1, -2147483647 - 1, 0, kRoleBindOff);
  return m;
}

void expect_identical(const StitchMesh& a, const StitchMesh& b) {
  ASSERT_EQ(a.num_vertices(), b.num_vertices());
  ASSERT_EQ(a.num_stitches(), b.num_stitches());
  EXPECT_EQ(std::memcmp(a.vertices.data(), b.vertices.data(), a.vertices.size() * sizeof(Vec3)), 0);
  for (int s = 0; s < a.num_stitches(); ++s) {
    const Stitch &x = a.stitches[s], &y = b.stitches[s];
    EXPECT_EQ(x.type, y.type) << s;
    EXPECT_EQ(x.direction, y.direction) << s;
    EXPECT_EQ(x.v, y.v) << s;
    EXPECT_EQ(x.course, y.course) << s;
    EXPECT_EQ(x.wale, y.wale) << s;
    EXPECT_EQ(x.yarn, y.yarn) << s;
    EXPECT_EQ(x.roles, y.roles) << s;
  }
}

TEST(StitchMeshPly, BinaryAndAsciiRoundTripsAreBitExact) {
  TempDir dir;
  const StitchMesh mesh = small_stitch_mesh();
  write_stitch_mesh_ply(dir.path("b.ply"), mesh);
  write_stitch_mesh_ply(dir.path("a.ply"), mesh, {.ascii = true, .scalars = {}});
  EXPECT_CONTAINS(dir.read("b.ply"), "format binary_little_endian 1.0\n");
  EXPECT_CONTAINS(dir.read("a.ply"), "format ascii 1.0\n");
  for (const char* name : {"b.ply", "a.ply"}) {
    SCOPED_TRACE(name);
    const StitchMesh back = read_stitch_mesh_ply(dir.path(name));
    expect_identical(back, mesh);
    EXPECT_TRUE(std::signbit(back.vertices[9].z()));
  }
  // Binary size: 11 vertices x 24 bytes, 3 quads x 35 and 4 triangles x 31.
  const std::string b = dir.read("b.ply");
  EXPECT_EQ(b.size() - b.find("end_header\n") - 11, 11u * 24 + 3u * 35 + 4u * 31);
}

TEST(StitchMeshPly, ExtraPerStitchScalarsAreWrittenAndIgnoredOnReading) {
  TempDir dir;
  const StitchMesh mesh = small_stitch_mesh();
  StitchMeshPlyOptions o;
  o.scalars.push_back({"shape_error", std::vector<double>(mesh.num_stitches(), 0.25)});
  write_stitch_mesh_ply(dir.path("b.ply"), mesh, o);
  const std::string b = dir.read("b.ply");
  EXPECT_CONTAINS(b, "property float shape_error\nend_header\n");
  // 4 more bytes per stitch than without the scalar.
  EXPECT_EQ(b.size() - b.find("end_header\n") - 11, 11u * 24 + 3u * 39 + 4u * 35);
  expect_identical(read_stitch_mesh_ply(dir.path("b.ply")), mesh);
  o.ascii = true;
  write_stitch_mesh_ply(dir.path("a.ply"), mesh, o);
  EXPECT_CONTAINS(dir.read("a.ply"), " 0.25\n");
  expect_identical(read_stitch_mesh_ply(dir.path("a.ply")), mesh);

  StitchMeshPlyOptions bad;
  bad.scalars.push_back({"type", std::vector<double>(mesh.num_stitches(), 0.0)});
  EXPECT_THROW(write_stitch_mesh_ply(dir.path("c.ply"), mesh, bad), InvalidInput);
  bad.scalars = {{"ok_name", std::vector<double>(2, 0.0)}};
  EXPECT_THROW(write_stitch_mesh_ply(dir.path("c.ply"), mesh, bad), InvalidInput);
  bad.scalars = {{"bad name", std::vector<double>(mesh.num_stitches(), 0.0)}};
  EXPECT_THROW(write_stitch_mesh_ply(dir.path("c.ply"), mesh, bad), InvalidInput);
  EXPECT_FALSE(std::filesystem::exists(dir.path("c.ply")));
}

TEST(StitchMeshPly, HasThePropertiesAndColoursViewersUse) {
  TempDir dir;
  write_stitch_mesh_ply(dir.path("a.ply"), small_stitch_mesh(), {.ascii = true, .scalars = {}});
  const std::string text = dir.read("a.ply");
  EXPECT_CONTAINS(text,
                  "element face 7\nproperty list uchar int vertex_indices\nproperty uchar type\n"
                  "property char direction\nproperty int course\nproperty int wale\nproperty int yarn\n"
                  "property uchar roles\nproperty uchar red\nproperty uchar green\nproperty uchar blue\n");
  // The short-row-right stitch (type 2) line ends with its colour.
  const Rgb c = stitch_type_colour(StitchType::ShortRowRight);
  EXPECT_CONTAINS(text, "3 2 9 5 2 1 0 3 0 5 " + std::to_string(c.r) + " " + std::to_string(c.g) + " " +
                            std::to_string(c.b) + "\n");
  // Any PLY reader sees a polygon mesh: 3 quads + 4 triangles = 10 triangles.
  EXPECT_EQ(read_ply(dir.path("a.ply")).num_faces(), 10);
}

// Replaces token `k` of line `n` (1-based) of `text`.
std::string edit(const std::string& text, int n, int k, const std::string& value) {
  std::istringstream in(text);
  std::string line, out;
  for (int i = 1; std::getline(in, line); ++i) {
    if (i == n) {
      std::istringstream ls(line);
      std::vector<std::string> tok;
      for (std::string t; ls >> t;) tok.push_back(t);
      tok.at(k) = value;
      line.clear();
      for (size_t j = 0; j < tok.size(); ++j) line += (j ? " " : "") + tok[j];
    }
    out += line + "\n";
  }
  return out;
}

TEST(StitchMeshPly, MalformedFilesNameFileAndLine) {
  TempDir dir;
  write_stitch_mesh_ply(dir.path("a.ply"), small_stitch_mesh(), {.ascii = true, .scalars = {}});
  const std::string good = dir.read("a.ply");
  // 19 header lines, vertices on lines 20-30, stitches on lines 31-37.
  struct Case {
    std::string name, content, where, what;
  };
  std::string three_corners = good;
  three_corners.replace(three_corners.find("4 0 1 4 3 0"), 11, "3 0 1 4 0");
  std::string no_type = good;
  no_type.replace(no_type.find("property uchar type"), 19, "property uchar kind");
  const std::vector<Case> cases = {
      {"type.ply", edit(good, 31, 5, "7"), ":31:", "type 7 is not an integer in [0, 4]"},
      {"dir.ply", edit(good, 32, 6, "0"), ":32:", "direction 0 must be +1 or -1"},
      {"corners.ply", three_corners, ":31:", "knit stitch with 3 corners; this type has 4"},
      {"index.ply", edit(good, 33, 2, "99"), ":33:", "vertex index 99 is out of range"},
      {"nan.ply", edit(good, 22, 1, "nan"), ":22:", "vertex 2 has a non-finite coordinate"},
      {"notype.ply", no_type, ":8:", "'type' and 'direction'"},
      // Reversed short-row-right stitch (face 3): same edge direction as face 1.
      {"orient.ply", edit(edit(good, 34, 1, "5"), 34, 3, "2"), ":34:", "orientation"},
      {"truncated.ply", good.substr(0, good.rfind("3 4 8 7")), ":36:", "unexpected end of file"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    const std::string p = dir.write(c.name, c.content);
    const std::string msg = test::io_error([&] { read_stitch_mesh_ply(p); });
    EXPECT_CONTAINS(msg, p + c.where);
    EXPECT_CONTAINS(msg, c.what);
  }
  write_stitch_mesh_ply(dir.path("b.ply"), small_stitch_mesh());
  const std::string bin = dir.read("b.ply");
  const std::string p = dir.write("cut.ply", bin.substr(0, bin.size() - 5));
  EXPECT_CONTAINS(test::io_error([&] { read_stitch_mesh_ply(p); }), p + ": byte ");
}

TEST(StitchMeshPly, WriterRejectsInvalidStitches) {
  TempDir dir;
  StitchMesh m = small_stitch_mesh();
  m.stitches[2].direction = 0;
  EXPECT_CONTAINS(test::invalid_input([&] { write_stitch_mesh_ply(dir.path("x.ply"), m); }),
                  "stitch 2 has direction 0");
  m = small_stitch_mesh();
  m.stitches[4].v[3] = 1;
  EXPECT_CONTAINS(test::invalid_input([&] { write_stitch_mesh_ply(dir.path("x.ply"), m); }), "stitch 4");
  m = small_stitch_mesh();
  m.stitches[0].v[2] = 11;
  EXPECT_CONTAINS(test::invalid_input([&] { write_stitch_mesh_ply(dir.path("x.ply"), m); }), "stitch 0");
  EXPECT_EQ(dir.num_files(), 0u);
}

}  // namespace
}  // namespace knitforge
