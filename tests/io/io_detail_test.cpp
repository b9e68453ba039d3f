// Messages quote input, never dump it; a directory is not read as a file.
#include "knitforge/io/io_detail.h"

#include <gtest/gtest.h>

#include <filesystem>

#include "io/io_test_util.h"
#include "knitforge/io/mesh_io.h"
#include "knitforge/io/ply.h"

namespace knitforge {
namespace {

TEST(IoDetail, PrintableMessageCutsQuotedInputAndHidesControlBytes) {
  const std::string token(5000, '7');
  const std::string m = io_detail::printable_message("'" + token + "' is not a number");
  EXPECT_LT(m.size(), 140u) << m;
  EXPECT_NE(m.find(std::string(80, '7') + "...' (4920 more characters) is not a number"), std::string::npos)
      << m;
  const std::string c = io_detail::printable_message("'a\x01\x1b[31m\x07' bad\n");
  EXPECT_EQ(c, "'a??[31m?' bad?");
  EXPECT_EQ(io_detail::printable_message("short 'ok' text"), "short 'ok' text");
}

TEST(IoDetail, ReadersSayADirectoryIsADirectory) {
  test::TempDir dir;
  const std::string d = dir.path("scan.obj");
  std::filesystem::create_directories(d);
  EXPECT_NE(test::io_error([&] { read_mesh(d); }).find("is a directory"), std::string::npos);
  EXPECT_NE(test::io_error([&] { io_detail::load_file(d); }).find("is a directory"), std::string::npos);
}

TEST(IoDetail, PlyFormatVersionMustBeOnePointZero) {
  test::TempDir dir;
  const std::string body =
      "element vertex 3\nproperty float x\nproperty float y\nproperty float z\nelement face 1\n"
      "property list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
  EXPECT_EQ(read_ply(dir.write("ok.ply", "ply\nformat ascii 1.0\n" + body)).num_faces(), 1);
  for (const char* bad : {"format ascii 2.0\n", "format ascii\n", "format ascii 1.0 extra\n"}) {
    const std::string e =
        test::io_error([&] { read_ply(dir.write("bad.ply", std::string("ply\n") + bad + body)); });
    EXPECT_NE(e.find("bad.ply:2"), std::string::npos) << e;
    EXPECT_NE(e.find("1.0"), std::string::npos) << e;
  }
}

}  // namespace
}  // namespace knitforge
