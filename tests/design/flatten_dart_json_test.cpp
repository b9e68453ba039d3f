#include <string>

#include <gtest/gtest.h>

#include "knitforge/design/flatten/dart_json.h"
#include "knitforge/util/errors.h"

namespace knitforge {
namespace {

std::string error_of(const std::string& text) {
  try {
    parse_darts_json(text, "darts.json");
  } catch (const InvalidInput& e) {
    return e.what();
  }
  return "";
}

TEST(DartJson, ParsesAllPointKindsAndScalesPositions) {
  const auto d = parse_darts_json(R"({"darts": [
      {"type": "two-end", "orientation": "vertical",
       "points": [{"vertex": 3}, {"face": 7, "bary": [0.2, 0.3, 0.5]}, {"position": [1, 2, 3]}]},
      {"to_boundary": true, "points": [{"position": [0, 0, 5]}]}]})",
                                  "d.json", 10.0);
  ASSERT_EQ(d.size(), 2u);
  EXPECT_EQ(d[0].type, DartType::TwoEnd);
  EXPECT_EQ(d[0].orientation, DartOrientation::Vertical);
  ASSERT_EQ(d[0].points.size(), 3u);
  EXPECT_EQ(d[0].points[0].vertex, 3);
  EXPECT_EQ(d[0].points[1].face, 7);
  EXPECT_DOUBLE_EQ(d[0].points[1].bary.z(), 0.5);
  EXPECT_TRUE(d[0].points[2].has_position);
  EXPECT_DOUBLE_EQ(d[0].points[2].position.y(), 20.0);
  EXPECT_EQ(d[1].type, DartType::OneEnd);  // defaults
  EXPECT_EQ(d[1].orientation, DartOrientation::Horizontal);
  EXPECT_TRUE(d[1].to_boundary);
  // Round trip.
  const auto again = parse_darts_json(darts_to_json(d, 10.0), "again", 10.0);
  ASSERT_EQ(again.size(), 2u);
  EXPECT_DOUBLE_EQ(again[0].points[2].position.z(), 30.0);
  EXPECT_EQ(again[0].type, DartType::TwoEnd);
  EXPECT_TRUE(again[1].to_boundary);
  // A bare array is accepted.
  EXPECT_EQ(parse_darts_json(R"([{"points": [{"vertex": 1}, {"vertex": 2}]}])", "a").size(), 1u);
}

TEST(DartJson, ErrorsNameTheDartAndField) {
  EXPECT_NE(error_of("{\"darts\": [").find("not valid JSON"), std::string::npos);
  EXPECT_NE(
      error_of(R"({"darts": [{"points": []}, {"type": "three-end", "points": []}]})").find("dart 1.type"),
      std::string::npos);
  EXPECT_NE(error_of(R"({"darts": [{"orientation": "diagonal", "points": []}]})").find("dart 0.orientation"),
            std::string::npos);
  EXPECT_NE(error_of(R"({"darts": [{"points": [{"vertex": 1}, {"face": 2}]}]})").find("dart 0.points[1]"),
            std::string::npos);
  EXPECT_NE(error_of(R"({"darts": [{"points": [{"vertex": -1}]}]})").find("dart 0.points[0].vertex"),
            std::string::npos);
  EXPECT_NE(error_of(R"({"darts": [{"points": [{"position": [1, 2]}]}]})").find("position"),
            std::string::npos);
  EXPECT_NE(error_of(R"({"darts": [{"colour": "red", "points": []}]})").find("unknown key \"colour\""),
            std::string::npos);
  EXPECT_NE(error_of(R"({"darts": [{"type": "one-end"}]})").find("missing \"points\""), std::string::npos);
  EXPECT_NE(error_of(R"({"dart": []})").find("unknown key"), std::string::npos);
}

}  // namespace
}  // namespace knitforge
