#include "knitforge/io/off.h"

#include <gtest/gtest.h>

#include "io/io_test_util.h"

namespace knitforge {
namespace {

using test::TempDir;

TEST(Off, RoundTripIsBitExactWithAndWithoutColours) {
  TempDir dir;
  const TriMesh mesh = test::grid_mesh(3, 3);
  write_off(dir.path("m.off"), mesh);
  EXPECT_EQ(dir.read("m.off").substr(0, 4), "OFF\n");
  test::expect_same_mesh(read_off(dir.path("m.off")), mesh);
  MeshWriteOptions opt;
  opt.vertex_colours.assign(mesh.vertices.size(), {10, 20, 30});
  opt.face_colours.assign(mesh.faces.size(), {40, 50, 60});
  write_off(dir.path("c.off"), mesh, opt);
  const std::string text = dir.read("c.off");
  EXPECT_EQ(text.substr(0, 5), "COFF\n");
  EXPECT_CONTAINS(text, " 10 20 30 255\n");
  EXPECT_CONTAINS(text, "3 0 1 5 40 50 60\n");
  test::expect_same_mesh(read_off(dir.path("c.off")), mesh);
}

TEST(Off, AcceptsCommentsCountsOnTheKeywordLinePolygonsAndColours) {
  TempDir dir;
  const std::string p = dir.write("h.off",
                                  "# hand made\n"
                                  "OFF 5 2 0\n"
                                  "\n"
                                  "0 0 0\n1 0 0\n1 1 0\n0 1 0  # corner\n2 0.5 0\n"
                                  "4 0 1 2 3 255 0 0\n"
                                  "3 1 4 2 0.1 0.2 0.3 1\n");
  const TriMesh m = read_off(p);
  ASSERT_EQ(m.num_vertices(), 5);
  const std::vector<std::array<int, 3>> expected = {{0, 1, 2}, {0, 2, 3}, {1, 4, 2}};
  EXPECT_EQ(m.faces, expected);
  // The keyword is optional.
  EXPECT_EQ(read_off(dir.write("nokey.off", "3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n")).num_faces(), 1);
}

TEST(Off, MalformedFilesNameFileAndLine) {
  struct Case {
    const char *name, *content, *where, *what;
  };
  const Case cases[] = {
      {"empty.off", "", ": file is empty", "empty"},
      {"huge.off", "OFF\n# counts\n100000000 1 0\n0 0 0\n", ":3:", "more than the remaining"},
      {"counts.off", "OFF\n3 x 0\n", ":2:", "bad counts"},
      {"truncv.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n# padding padding padding\n", ":5:", "after 2 of 3 vertices"},
      {"truncf.off", "OFF\n3 2 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n# padding padding\n", ":7:", "after 1 of 2 faces"},
      {"range.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n", ":6:", "out of range"},
      {"negidx.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 -1 2\n", ":6:", "out of range"},
      {"nan.off", "OFF\n3 1 0\n0 0 0\n1 NaN 0\n0 1 0\n3 0 1 2\n", ":4:", "not finite"},
      {"size.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n2 0 1\n# pad\n", ":6:", "not a valid face size"},
      {"short.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n4 0 1 2\n", ":6:", "lists only 3"},
      {"nofaces.off", "OFF\n3 0 0\n0 0 0\n1 0 0\n0 1 0\n", ": the file holds 3 vertices", "no faces"},
      {"4d.off", "4OFF\n1 0 0\n0 0 0 0\n", ":1:", "not supported"},
      {"binary.off", "OFF BINARY\n", ":1:", "binary OFF"},
      {"orient.off", "OFF\n4 2 0\n0 0 0\n1 0 0\n0 1 0\n1 1 0\n3 0 1 2\n3 1 2 3\n", ":8:", "orientation"},
  };
  TempDir dir;
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    const std::string p = dir.write(c.name, c.content);
    const std::string msg = test::io_error([&] { read_off(p); });
    EXPECT_CONTAINS(msg, p + c.where);
    EXPECT_CONTAINS(msg, c.what);
  }
}

}  // namespace
}  // namespace knitforge
