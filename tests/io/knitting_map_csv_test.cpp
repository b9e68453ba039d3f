#include "knitforge/io/knitting_map_csv.h"

#include <gtest/gtest.h>

#include "io/io_test_util.h"

namespace knitforge {
namespace {

using test::TempDir;

// 3 x 4 map: course 0 all knit, course 1 a short row ending left with a yarn-2
// stitch, course 2 an increase, a decrease, a collapsed and an empty cell.
KnittingMap small_map() {
  KnittingMap m(3, 4, CellType::Knit);
  m.at(1, 0) = CellType::ShortRowLeft;
  m.at(1, 3) = CellType::ShortRowRight;
  m.set_yarn(1, 1, 2);
  m.at(2, 0) = CellType::Increase;
  m.at(2, 1) = CellType::Decrease;
  m.at(2, 2) = CellType::Collapsed;
  m.at(2, 3) = CellType::Empty;
  m.set_yarn(2, 0, 13);
  return m;
}

TEST(KnittingMapCsv, TextIsTopCourseFirstWithDocumentedCodes) {
  EXPECT_EQ(knitting_map_to_csv(small_map()),
            "course,dir,0,1,2,3\n"
            "2,>,I13,D,C,.\n"
            "1,<,L,K2,K,R\n"
            "0,>,K,K,K,K\n");
}

TEST(KnittingMapCsv, RoundTripIsExact) {
  TempDir dir;
  const KnittingMap m = small_map();
  write_knitting_map_csv(dir.path("map.csv"), m);
  EXPECT_EQ(read_knitting_map_csv(dir.path("map.csv")), m);
  // A map without yarns keeps an empty yarn array; odd directions survive.
  KnittingMap plain(5, 7, CellType::Knit);
  plain.direction = {1, 1, -1, 1, -1};
  write_knitting_map_csv(dir.path("plain.csv"), plain);
  const KnittingMap back = read_knitting_map_csv(dir.path("plain.csv"));
  EXPECT_EQ(back, plain);
  EXPECT_TRUE(back.yarn.empty());
  EXPECT_EQ(back.direction, plain.direction);
  // Empty maps too.
  write_knitting_map_csv(dir.path("empty.csv"), KnittingMap());
  EXPECT_EQ(read_knitting_map_csv(dir.path("empty.csv")), KnittingMap());
}

TEST(KnittingMapCsv, AcceptsSpreadsheetDialects) {
  const KnittingMap expected = small_map();
  // CRLF, a BOM, ';' separators, spaces, quotes, lower-case codes, empty fields, blank lines.
  const std::string text =
      "\xEF\xBB\xBF"
      "course ; dir ; 0 ; 1 ; 2 ; 3\r\n"
      " 2 ; > ; i13 ; \"D\" ; C ;  \r\n"
      "\r\n"
      "1;<;L;K2;k;R\r\n"
      "0;>;K;K;K;K\r\n"
      ";;;;;\r\n";
  EXPECT_EQ(knitting_map_from_csv(text, "x.csv"), expected);
  const std::string commas = "course,dir,0,1,2,3\n2,>,I13,D,C,\n1,<,L,K2,K,R\n0,>,K,K,K,K";
  EXPECT_EQ(knitting_map_from_csv(commas, "y.csv"), expected);
}

TEST(KnittingMapCsv, MalformedFilesNameLineAndColumn) {
  const std::string head = "course,dir,0,1,2\n";
  struct Case {
    std::string content, where, what;
  };
  const std::vector<Case> cases = {
      {"", "map.csv: file is empty", "empty"},
      {"\n \n", "map.csv: file is empty", "empty"},
      {"row,dir,0\n", "map.csv:1, column 1:", "must start with 'course' and 'dir'"},
      {"course,dir,0,2\n", "map.csv:1, column 4:", "should be 1"},
      {head + "1,>,K,K,K\n0,<,K,Q,K\n", "map.csv:3, column 4:",
       "unknown cell code 'Q' (expected K, L, R, I, D, C or .)"},
      {head + "1,>,K,K,K\n0,<,K,K2x,K\n", "map.csv:3, column 4:", "yarn index"},
      {head + "1,>,K,K,K\n0,<,K,K-1,K\n", "map.csv:3, column 4:", "yarn index"},
      {head + "1,>,K,K,K\n0,<,K,K\n", "map.csv:3, column 5:", "4 fields, but the header has 5"},
      {head + "1,>,K,K,K\n0,<,K,K,K,K\n", "map.csv:3, column 6:", "6 fields"},
      {head + "2,>,K,K,K\n0,<,K,K,K\n", "map.csv:3, column 1:", "course 0 where 1 was expected"},
      {head + "2,>,K,K,K\n1,<,K,K,K\n", "map.csv:3, column 1:", "bottom course must be 0"},
      {head + "0,>,K,K,K\n0,<,K,K,K\n", "map.csv:3, column 1:", "after the bottom course"},
      {head + "x,>,K,K,K\n", "map.csv:2, column 1:", "not a course index"},
      {head + "1,>,K,K,K\n0,^,K,K,K\n", "map.csv:3, column 2:", "unknown direction '^'"},
  };
  TempDir dir;
  for (const Case& c : cases) {
    SCOPED_TRACE(c.content);
    const std::string msg = test::io_error([&] { knitting_map_from_csv(c.content, "map.csv"); });
    EXPECT_CONTAINS(msg, c.where);
    EXPECT_CONTAINS(msg, c.what);
  }
  // The same through a file: the path is named.
  const std::string p = dir.write("bad.csv", head + "0,>,K,Q,K\n");
  EXPECT_CONTAINS(test::io_error([&] { read_knitting_map_csv(p); }), p + ":2, column 4: unknown cell code 'Q'");
  EXPECT_CONTAINS(test::io_error([&] { read_knitting_map_csv(dir.path("none.csv")); }), "cannot open");
}

TEST(KnittingMapCsv, WriterRejectsInconsistentMaps) {
  KnittingMap m = small_map();
  m.direction[1] = 0;
  EXPECT_CONTAINS(test::invalid_input([&] { knitting_map_to_csv(m); }), "row 1 has direction 0");
  m = small_map();
  m.cells.pop_back();
  EXPECT_CONTAINS(test::invalid_input([&] { knitting_map_to_csv(m); }), "wrong size");
  m = small_map();
  m.set_yarn(0, 0, -3);
  EXPECT_CONTAINS(test::invalid_input([&] { knitting_map_to_csv(m); }), "negative yarn");
}

}  // namespace
}  // namespace knitforge

namespace knitforge {
namespace {

TEST(KnittingMapCsv, TubeHasASeamColumnAndRoundTrips) {
  KnittingMap m(3, 4, CellType::Knit);
  m.direction = {1, -1, 1};
  m.seam = {0, -1, 2};
  m.at(1, 0) = CellType::Collapsed;
  const std::string csv = knitting_map_to_csv(m);
  EXPECT_EQ(csv, "course,dir,seam,0,1,2,3\n2,>,2,K,K,K,K\n1,<,-,C,K,K,K\n0,>,0,K,K,K,K\n");
  EXPECT_EQ(knitting_map_from_csv(csv, "t.csv"), m);
  // an empty seam field reads as an open row too
  EXPECT_EQ(knitting_map_from_csv("course,dir,seam,0,1,2,3\n2,>,2,K,K,K,K\n1,<,,C,K,K,K\n0,>,0,K,K,K,K\n", "t.csv"),
            m);
  // sheets keep their two leading columns
  KnittingMap sheet = m;
  sheet.seam.clear();
  EXPECT_EQ(knitting_map_to_csv(sheet).rfind("course,dir,0,", 0), 0u);
  try {
    knitting_map_from_csv("course,dir,seam,0,1\n0,>,7,K,K\n", "t.csv");
    FAIL() << "no exception";
  } catch (const IOError& e) {
    EXPECT_NE(std::string(e.what()).find("t.csv:2, column 3: seam '7'"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace knitforge
