#include "knitforge/io/vertex_field.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>

#include <gtest/gtest.h>
#include <unistd.h>

#include "knitforge/util/errors.h"

namespace knitforge {
namespace {

std::string temp(const std::string& name) {
  return (std::filesystem::temp_directory_path() / ("knitforge_vertex_field_" + std::to_string(::getpid()) + "_" + name)).string();
}

TEST(VertexField, WrittenValuesReadBackExactly) {
  const std::vector<double> v{0.0, 1.0 / 3.0, -2.5e-17, 12345.678901234567, 1.0};
  const std::string p = temp("roundtrip.txt");
  write_vertex_field(p, v);
  EXPECT_EQ(read_vertex_field(p, 5), v);
  EXPECT_EQ(read_vertex_field(p), v);
  std::filesystem::remove(p);
}

TEST(VertexField, CommentsAndBlankLinesAreSkippedAndErrorsNamed) {
  const std::string p = temp("comments.txt");
  {
    std::ofstream f(p);
    f << "# a field\n\n 0.5 \n1\r\n";
  }
  EXPECT_EQ(read_vertex_field(p, 2), (std::vector<double>{0.5, 1.0}));
  try {
    read_vertex_field(p, 3);
    FAIL() << "no error";
  } catch (const IOError& e) {
    EXPECT_NE(std::string(e.what()).find("2 values for a surface of 3 vertices"), std::string::npos) << e.what();
  }
  {
    std::ofstream f(p);
    f << "0\n1 2\n";
  }
  try {
    read_vertex_field(p);
    FAIL() << "no error";
  } catch (const IOError& e) {
    EXPECT_NE(std::string(e.what()).find(p + ":2: '1 2'"), std::string::npos) << e.what();
  }
  {
    std::ofstream f(p);
    f << "nan\n";
  }
  EXPECT_THROW(read_vertex_field(p), IOError);
  EXPECT_THROW(read_vertex_field(temp("missing.txt")), IOError);
  EXPECT_THROW(write_vertex_field(p, {std::numeric_limits<double>::infinity()}), InvalidInput);
  std::filesystem::remove(p);
}

}  // namespace
}  // namespace knitforge
