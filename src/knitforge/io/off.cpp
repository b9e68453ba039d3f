#include "knitforge/io/off.h"

#include <cmath>
#include <limits>
#include <ostream>

#include <fmt/core.h>
#include <fmt/format.h>

#include "knitforge/io/io_detail.h"
#include "knitforge/util/atomic_file.h"
#include "knitforge/util/errors.h"

namespace knitforge {

using namespace io_detail;

namespace {

// Next line with content (comments stripped), split into tokens; false at EOF.
bool next_tokens(LineReader& lines, std::vector<std::string_view>& tok) {
  std::string_view line;
  while (lines.next(line)) {
    split_ws(strip_comment(line), tok);
    if (!tok.empty()) return true;
  }
  return false;
}

bool is_off_keyword(std::string_view k) {
  if (k.size() < 3 || k.substr(k.size() - 3) != "OFF") return false;
  for (char c : k.substr(0, k.size() - 3)) {
    if (c != 'S' && c != 'T' && c != 'C' && c != 'N' && c != '4' && c != 'n') return false;
  }
  return true;
}

}  // namespace

TriMesh read_off(const std::string& path) {
  const std::string data = load_file(path);
  if (trim(data).empty()) throw IOError(fmt::format("{}: file is empty", path));
  LineReader lines(data);
  std::vector<std::string_view> tok;
  if (!next_tokens(lines, tok)) throw IOError(fmt::format("{}: file holds only comments", path));
  size_t first = 0;
  if (is_off_keyword(tok[0])) {
    if (tok[0].find('4') != std::string_view::npos || tok[0].find('n') != std::string_view::npos) {
      fail_line(path, lines.line_number(),
                fmt::format("'{}' (4D or n-dimensional OFF) is not supported; use 3D OFF", tok[0]));
    }
    if (tok.size() > 1 && tok[1] == "BINARY") {
      fail_line(path, lines.line_number(), "binary OFF is not supported; use text OFF, PLY or STL");
    }
    first = 1;
    if (tok.size() == 1) {
      if (!next_tokens(lines, tok)) {
        fail_line(path, lines.line_number(), "unexpected end of file: the vertex and face counts are missing");
      }
      first = 0;
    }
  }
  const int64_t count_line = lines.line_number();
  if (tok.size() < first + 2) {
    fail_line(path, count_line, "expected the counts 'vertices faces [edges]'");
  }
  int64_t nv = 0, nf = 0;
  if (!parse_int64(tok[first], nv) || !parse_int64(tok[first + 1], nf) || nv < 0 || nf < 0) {
    fail_line(path, count_line, fmt::format("bad counts '{} {}': expected two non-negative integers",
                                            tok[first], tok[first + 1]));
  }
  // Each vertex needs at least "x y z\n" (6 bytes), each face "3 a b c\n" (8).
  const int64_t remaining = static_cast<int64_t>(data.size() - lines.offset());
  if (nv > std::numeric_limits<int>::max() || nf > std::numeric_limits<int>::max() / 4 ||
      nv * 6 + nf * 8 > remaining + 1) {
    fail_line(path, count_line,
              fmt::format("the header declares {} vertices and {} faces, more than the remaining {} "
                          "bytes can hold; the file is truncated or the counts are wrong",
                          nv, nf, remaining));
  }
  TriMesh mesh;
  mesh.vertices.reserve(static_cast<size_t>(nv));
  for (int64_t i = 0; i < nv; ++i) {
    if (!next_tokens(lines, tok)) {
      fail_line(path, lines.line_number(),
                fmt::format("unexpected end of file after {} of {} vertices", i, nv));
    }
    if (tok.size() < 3) fail_line(path, lines.line_number(), "a vertex needs three coordinates 'x y z'");
    Vec3 p;
    for (int k = 0; k < 3; ++k) {
      if (!parse_double(tok[k], p[k])) {
        fail_line(path, lines.line_number(), fmt::format("'{}' is not a number", tok[k]));
      }
      if (!std::isfinite(p[k])) {
        fail_line(path, lines.line_number(), fmt::format("vertex coordinate '{}' is not finite", tok[k]));
      }
    }
    mesh.vertices.push_back(p);
  }
  std::vector<int64_t> face_line;
  std::vector<int> poly;
  for (int64_t i = 0; i < nf; ++i) {
    if (!next_tokens(lines, tok)) {
      fail_line(path, lines.line_number(), fmt::format("unexpected end of file after {} of {} faces", i, nf));
    }
    const int64_t ln = lines.line_number();
    int64_t n = 0;
    if (!parse_int64(tok[0], n) || n < 3) {
      fail_line(path, ln, fmt::format("'{}' is not a valid face size; a face needs at least 3 vertices", tok[0]));
    }
    if (static_cast<int64_t>(tok.size()) < n + 1) {
      fail_line(path, ln, fmt::format("the face declares {} vertices but lists only {}", n, tok.size() - 1));
    }
    poly.clear();
    for (int64_t k = 1; k <= n; ++k) {
      int64_t v = 0;
      if (!parse_int64(tok[k], v)) fail_line(path, ln, fmt::format("'{}' is not a vertex index", tok[k]));
      if (v < 0 || v >= nv) {
        fail_line(path, ln, fmt::format("vertex index {} is out of range: the file has {} vertices "
                                        "(OFF indices count from 0)", v, nv));
      }
      poly.push_back(static_cast<int>(v));
    }
    for (size_t k = 1; k + 1 < poly.size(); ++k) {
      mesh.faces.push_back({poly[0], poly[k], poly[k + 1]});
      face_line.push_back(ln);
    }
  }
  check_mesh(path, mesh, face_line, LocKind::Line);
  return mesh;
}

void write_off(const std::string& path, const TriMesh& mesh, const MeshWriteOptions& options) {
  check_mesh_for_writing(path, mesh, options, "OFF", true, true);
  const bool vcol = !options.vertex_colours.empty();
  fmt::memory_buffer buf;
  auto out = std::back_inserter(buf);
  fmt::format_to(out, "{}\n{} {} 0\n", vcol ? "COFF" : "OFF", mesh.num_vertices(), mesh.num_faces());
  for (int v = 0; v < mesh.num_vertices(); ++v) {
    const Vec3& p = mesh.vertices[v];
    fmt::format_to(out, "{} {} {}", p.x(), p.y(), p.z());
    if (vcol) {
      const Rgb c = options.vertex_colours[v];
      fmt::format_to(out, " {} {} {} 255", c.r, c.g, c.b);
    }
    buf.push_back('\n');
  }
  for (int f = 0; f < mesh.num_faces(); ++f) {
    const auto& t = mesh.faces[f];
    fmt::format_to(out, "3 {} {} {}", t[0], t[1], t[2]);
    if (!options.face_colours.empty()) {
      const Rgb c = options.face_colours[f];
      fmt::format_to(out, " {} {} {}", c.r, c.g, c.b);
    }
    buf.push_back('\n');
  }
  write_file_atomically(path, [&](std::ostream& o) { o.write(buf.data(), static_cast<std::streamsize>(buf.size())); });
}

}  // namespace knitforge
