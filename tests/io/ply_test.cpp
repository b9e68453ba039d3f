#include "knitforge/io/ply.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <limits>

#include <fmt/core.h>

#include "io/io_test_util.h"

namespace knitforge {
namespace {

using test::TempDir;

// Appends v as PLY type `type` in the given byte order.
void put(std::string& out, const std::string& type, double v, bool big) {
  char b[8];
  int n = 0;
  auto store = [&](auto x) {
    n = sizeof(x);
    std::memcpy(b, &x, n);
  };
  if (type == "char") store(static_cast<int8_t>(v));
  else if (type == "uchar") store(static_cast<uint8_t>(v));
  else if (type == "short") store(static_cast<int16_t>(v));
  else if (type == "ushort") store(static_cast<uint16_t>(v));
  else if (type == "int") store(static_cast<int32_t>(v));
  else if (type == "uint") store(static_cast<uint32_t>(v));
  else if (type == "float") store(static_cast<float>(v));
  else store(v);
  if (big) std::reverse(b, b + n);  // the test machine is little endian (checked below)
  out.append(b, n);
}

// A square (two triangles as one quad) plus a triangle, with an extra element
// before the vertices, extra vertex properties including a list, and extra
// face properties. Coordinates are float-exact.
std::string square_ply(const std::string& format, const std::string& count_type, const std::string& index_type,
                       const std::string& list_name = "vertex_indices") {
  const bool ascii = format == "ascii", big = format == "binary_big_endian";
  std::string h = "ply\nformat " + format + " 1.0\ncomment made by hand\nobj_info test\n";
  h += "element material 2\nproperty uchar ambient\nproperty list uchar float coeffs\n";
  h += "element vertex 5\nproperty float x\nproperty float y\nproperty float z\nproperty double nx\n"
       "property list uchar int tags\n";
  h += "element face 2\nproperty uchar flags\nproperty list " + count_type + " " + index_type + " " + list_name +
       "\nproperty float quality\n";
  h += "element edge 1\nproperty int vertex1\nproperty int vertex2\n";
  h += "end_header\n";
  const double pos[5][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0.5}, {0, 1, 0.25}, {2, 0.5, -1}};
  std::string body;
  if (ascii) {
    body += "7 2 0.5 1.5\n9 0\n";
    for (auto& p : pos) body += fmt::format("{} {} {} 0.125 2 7 8\n", p[0], p[1], p[2]);
    body += "1 4 0 1 2 3 0.5\n0 3 1 4 2 1.0\n";
    body += "0 1\n";
  } else {
    put(body, "uchar", 7, big), put(body, "uchar", 2, big), put(body, "float", 0.5, big), put(body, "float", 1.5, big);
    put(body, "uchar", 9, big), put(body, "uchar", 0, big);
    for (auto& p : pos) {
      for (double x : p) put(body, "float", x, big);
      put(body, "double", 0.125, big);
      put(body, "uchar", 2, big), put(body, "int", 7, big), put(body, "int", 8, big);
    }
    put(body, "uchar", 1, big), put(body, count_type, 4, big);
    for (int i : {0, 1, 2, 3}) put(body, index_type, i, big);
    put(body, "float", 0.5, big);
    put(body, "uchar", 0, big), put(body, count_type, 3, big);
    for (int i : {1, 4, 2}) put(body, index_type, i, big);
    put(body, "float", 1.0, big);
    put(body, "int", 0, big), put(body, "int", 1, big);
  }
  return h + body;
}

void expect_square(const TriMesh& m) {
  ASSERT_EQ(m.num_vertices(), 5);
  EXPECT_EQ(m.vertices[2], Vec3(1, 1, 0.5));
  EXPECT_EQ(m.vertices[4], Vec3(2, 0.5, -1));
  const std::vector<std::array<int, 3>> expected = {{0, 1, 2}, {0, 2, 3}, {1, 4, 2}};
  EXPECT_EQ(m.faces, expected);
}

TEST(Ply, ReadsAllEncodingsListTypesAndSkipsExtraElements) {
  uint16_t one = 1;
  ASSERT_EQ(*reinterpret_cast<uint8_t*>(&one), 1) << "test assumes a little-endian machine";
  TempDir dir;
  int n = 0;
  for (const std::string format : {"ascii", "binary_little_endian", "binary_big_endian"}) {
    for (const std::string count : {"uchar", "char", "ushort", "int", "uint"}) {
      for (const std::string index : {"int", "uint", "short", "ushort", "uchar", "char"}) {
        SCOPED_TRACE(format + " " + count + " " + index);
        const std::string p = dir.write(fmt::format("s{}.ply", n++), square_ply(format, count, index));
        expect_square(read_ply(p));
      }
    }
    const std::string p = dir.write(fmt::format("s{}.ply", n++), square_ply(format, "uchar", "int", "vertex_index"));
    expect_square(read_ply(p));
  }
}

TEST(Ply, RoundTripBinaryAndAsciiWithColours) {
  TempDir dir;
  const TriMesh mesh = test::grid_mesh(5, 4);
  MeshWriteOptions opt;
  for (int v = 0; v < mesh.num_vertices(); ++v) opt.vertex_colours.push_back({uint8_t(v), 2, 3});
  for (int f = 0; f < mesh.num_faces(); ++f) opt.face_colours.push_back({4, uint8_t(f), 6});
  for (bool ascii : {false, true}) {
    opt.ascii = ascii;
    const std::string p = dir.path(ascii ? "a.ply" : "b.ply");
    write_ply(p, mesh, opt);
    const std::string text = dir.read(ascii ? "a.ply" : "b.ply");
    EXPECT_CONTAINS(text, ascii ? "format ascii 1.0" : "format binary_little_endian 1.0");
    EXPECT_CONTAINS(text, "element vertex 30\nproperty double x\nproperty double y\nproperty double z\n"
                          "property uchar red\nproperty uchar green\nproperty uchar blue\nelement face 40\n"
                          "property list uchar int vertex_indices\nproperty uchar red\n");
    test::expect_same_mesh(read_ply(p), mesh);
  }
  // Without colours the binary body is exactly 30*24 + 40*13 bytes.
  write_ply(dir.path("plain.ply"), mesh);
  const std::string plain = dir.read("plain.ply");
  EXPECT_EQ(plain.size() - plain.find("end_header\n") - 11, 30u * 24 + 40u * 13);
}

TEST(Ply, MalformedFiles) {
  TempDir dir;
  const std::string good = square_ply("ascii", "uchar", "int");
  const std::string header_end = "end_header\n";
  const size_t body = good.find(header_end) + header_end.size();
  // Header line numbers of the square: vertex element at line 8, body starts at line 20.
  struct Case {
    std::string name, content, where, what;
  };
  std::vector<Case> cases = {
      {"empty.ply", "", ": file is empty", "empty"},
      {"notply.ply", "solid x\n", ":1:", "not a PLY file"},
      {"format.ply", "ply\nformat binary_middle_endian 1.0\nend_header\n", ":2:", "unknown PLY format"},
      {"noend.ply", "ply\nformat ascii 1.0\nelement vertex 0\nproperty float x\n", ":4:", "end_header"},
      {"type.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float128 x\nend_header\n0\n", ":4:",
       "unknown property type"},
      {"huge.ply", "ply\nformat binary_little_endian 1.0\nelement vertex 1000000000\nproperty float x\n"
                   "property float y\nproperty float z\nend_header\n\x01\x02",
       ":3:", "1000000000 'vertex' elements"},
      {"hugeascii.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                        "property float z\nelement face 99999999\nproperty list uchar int vertex_indices\n"
                        "end_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n",
       ":7:", "99999999 'face' elements"},
      {"truncated.ply", good.substr(0, good.rfind("0 3 1 4")), ":29:", "unexpected end of file"},
      {"range.ply", good.substr(0, body) + std::string(good.substr(body)).replace(
                                                 good.substr(body).find("0 3 1 4 2"), 9, "0 3 1 5 2"),
       ":30:", "out of range"},
      {"nan.ply", good.substr(0, body) + std::string(good.substr(body)).replace(
                                               good.substr(body).find("1 1 0.5"), 7, "1 nan 0.5"),
       ":26:", "non-finite"},
      {"fewvalues.ply", good.substr(0, body) + std::string(good.substr(body)).replace(
                                                   good.substr(body).find("0 3 1 4 2 1.0"), 13, "0 3 1 4 2"),
       ":30:", "too few values"},
      {"novertex.ply", "ply\nformat ascii 1.0\nelement face 0\nproperty list uchar int vertex_indices\nend_header\n",
       ":5:", "no 'vertex' element"},
      {"noface.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\n"
                     "property float z\nend_header\n0 0 0\n",
       ": the file holds 1 vertices but no faces", "no faces"},
      {"nonmanifold.ply", "ply\nformat ascii 1.0\nelement vertex 5\nproperty float x\nproperty float y\n"
                          "property float z\nelement face 3\nproperty list uchar int vertex_indices\nend_header\n"
                          "0 0 0\n1 0 0\n0 1 0\n0 -1 0\n0 0 1\n3 0 1 2\n3 1 0 3\n3 0 1 4\n",
       ":17:", "shared by 3 faces"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    const std::string p = dir.write(c.name, c.content);
    const std::string msg = test::io_error([&] { read_ply(p); });
    EXPECT_CONTAINS(msg, p + c.where);
    EXPECT_CONTAINS(msg, c.what);
  }
}

TEST(Ply, MalformedBinaryFilesNameTheByteOffset) {
  TempDir dir;
  const std::string good = square_ply("binary_little_endian", "uchar", "int");
  const size_t body = good.find("end_header\n") + 11;
  // Body layout: material 2 x 10 bytes ... see square_ply: material records are
  // 1 + 1 + 2*4 = 10 and 1 + 1 = 2 bytes; each vertex 12 + 8 + 1 + 8 = 29 bytes.
  const size_t vertices = body + 12, faces = vertices + 5 * 29;
  {
    const std::string p = dir.write("cut.ply", good.substr(0, good.size() - 3));
    const std::string msg = test::io_error([&] { read_ply(p); });
    EXPECT_CONTAINS(msg, fmt::format("{}: byte {}: unexpected end of file in element 'edge'", p, good.size() - 4));
  }
  {
    std::string bad = good;
    const float nan = std::numeric_limits<float>::quiet_NaN();
    std::memcpy(&bad[vertices + 2 * 29 + 4], &nan, 4);
    const std::string p = dir.write("nan.ply", bad);
    EXPECT_CONTAINS(test::io_error([&] { read_ply(p); }), fmt::format("{}: byte {}: vertex 2", p, vertices + 2 * 29));
  }
  {
    std::string bad = good;
    const int32_t big = 77;
    std::memcpy(&bad[faces + 2 + 4 * 2], &big, 4);  // third index of face 0
    const std::string p = dir.write("range.ply", bad);
    const std::string msg = test::io_error([&] { read_ply(p); });
    EXPECT_CONTAINS(msg, fmt::format("{}: byte {}: vertex index 77 is out of range", p, faces));
  }
  {
    std::string bad = square_ply("binary_little_endian", "char", "int");
    const size_t faces_c = bad.find("end_header\n") + 11 + 12 + 5 * 29;
    bad[faces_c + 1] = static_cast<char>(-1);  // list count -1
    const std::string p = dir.write("negative.ply", bad);
    EXPECT_CONTAINS(test::io_error([&] { read_ply(p); }), fmt::format("{}: byte {}: negative list length", p, faces_c));
  }
  {
    std::string bad = good;
    bad[faces + 1] = static_cast<char>(250);  // list longer than the file
    const std::string p = dir.write("longlist.ply", bad);
    EXPECT_CONTAINS(test::io_error([&] { read_ply(p); }), "unexpected end of file in element 'face' 0 of 2");
  }
}

}  // namespace
}  // namespace knitforge
