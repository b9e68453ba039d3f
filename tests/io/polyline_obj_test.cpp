#include "knitforge/io/polyline_obj.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "io/io_test_util.h"

namespace knitforge {
namespace {

using test::TempDir;

std::vector<Vec3> helix(int n, double phase) {
  std::vector<Vec3> pts;
  for (int i = 0; i < n; ++i) pts.emplace_back(std::cos(i * 0.3 + phase), std::sin(i * 0.3 + phase), i / 7.0);
  return pts;
}

TEST(PolylineObj, RoundTripIsBitExactWithNames) {
  TempDir dir;
  const std::vector<std::vector<Vec3>> lines = {helix(12, 0), helix(1, 1), {}, helix(5, 2)};
  write_polylines_obj(dir.path("w.obj"), lines, {"wale 0", "single", "nothing", ""});
  const std::vector<NamedPolyline> back = read_polylines_obj(dir.path("w.obj"));
  ASSERT_EQ(back.size(), 3u);  // the empty polyline is not stored
  EXPECT_EQ(back[0].name, "wale 0");
  EXPECT_EQ(back[1].name, "single");
  EXPECT_EQ(back[2].name, "polyline_3");
  EXPECT_EQ(back[0].points, lines[0]);
  EXPECT_EQ(back[1].points, lines[1]);
  EXPECT_EQ(back[2].points, lines[3]);
}

TEST(PolylineObj, YarnModelIsOneObjectPerYarn) {
  TempDir dir;
  YarnModel model;
  model.yarns.push_back({0, helix(20, 0), std::vector<int>(20, 1)});
  model.yarns.push_back({7, helix(3, 1), {}});
  write_yarn_obj(dir.path("yarn.obj"), model);
  const std::string text = dir.read("yarn.obj");
  EXPECT_CONTAINS(text, "o yarn_0\n");
  EXPECT_CONTAINS(text, "o yarn_7\nv ");
  EXPECT_CONTAINS(text, "\nl 21 22 23\n");
  const auto back = read_polylines_obj(dir.path("yarn.obj"));
  ASSERT_EQ(back.size(), 2u);
  EXPECT_EQ(back[0].name, "yarn_0");
  EXPECT_EQ(back[1].name, "yarn_7");
  EXPECT_EQ(back[0].points, model.yarns[0].points);
  EXPECT_EQ(back[1].points, model.yarns[1].points);
  model.yarns[1].stitch = {1};
  EXPECT_CONTAINS(test::invalid_input([&] { write_yarn_obj(dir.path("bad.obj"), model); }), "yarn 7");
}

TEST(PolylineObj, ReadsOtherWritersConventions) {
  TempDir dir;
  const std::string p = dir.write("c.obj",
                                  "# curves\r\n"
                                  "v 0 0 0\r\nv 1 0 0\r\nv 2 0 0\r\nvt 0 0\r\n"
                                  "g first group\r\n"
                                  "l 1/1 2/1 3/1\r\n"
                                  "l -1 -2\r\n"
                                  "f 1 2 3\r\n"
                                  "o second\r\n"
                                  "p 3 1\r\n");
  const auto back = read_polylines_obj(p);
  ASSERT_EQ(back.size(), 4u);
  EXPECT_EQ(back[0].name, "first group");
  EXPECT_EQ(back[0].points.size(), 3u);
  EXPECT_EQ(back[1].points, (std::vector<Vec3>{Vec3(2, 0, 0), Vec3(1, 0, 0)}));
  EXPECT_EQ(back[2].name, "second");
  EXPECT_EQ(back[3].points, (std::vector<Vec3>{Vec3(0, 0, 0)}));
}

TEST(PolylineObj, MalformedFilesAndBadInput) {
  TempDir dir;
  struct Case {
    const char *name, *content, *where, *what;
  };
  const Case cases[] = {
      {"empty.obj", "", ": file is empty", "empty"},
      {"range.obj", "v 0 0 0\nv 1 0 0\nl 1 2\nl 2 3\n", ":4:", "out of range"},
      {"one.obj", "v 0 0 0\nl 1\n", ":2:", "at least 2"},
      {"zero.obj", "v 0 0 0\nv 0 0 0\nl 0 1\n", ":3:", "count from 1"},
      {"neg.obj", "v 0 0 0\nl -1 -2\n", ":2:", "before the first vertex"},
      {"nan.obj", "v 0 0 0\nv 0 nan 0\nl 1 2\n", ":2:", "not finite"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    const std::string p = dir.write(c.name, c.content);
    const std::string msg = test::io_error([&] { read_polylines_obj(p); });
    EXPECT_CONTAINS(msg, p + c.where);
    EXPECT_CONTAINS(msg, c.what);
  }
  const std::vector<std::vector<Vec3>> lines = {helix(3, 0)};
  EXPECT_CONTAINS(test::invalid_input([&] { write_polylines_obj(dir.path("x.obj"), lines, {"a\nb"}); }),
                  "line breaks");
  EXPECT_CONTAINS(test::invalid_input([&] { write_polylines_obj(dir.path("x.obj"), lines, {"a", "b"}); }),
                  "2 names given for 1 polylines");
  std::vector<std::vector<Vec3>> bad = lines;
  bad[0][1].x() = std::numeric_limits<double>::infinity();
  EXPECT_CONTAINS(test::invalid_input([&] { write_polylines_obj(dir.path("x.obj"), bad); }), "not finite");
  EXPECT_FALSE(std::filesystem::exists(dir.path("x.obj")));
}

}  // namespace
}  // namespace knitforge
