#include "knitforge/io/obj.h"

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

TriMesh read_obj(const std::string& path) {
  const std::string data = load_file(path);
  if (trim(data).empty()) throw IOError(fmt::format("{}: file is empty", path));
  TriMesh mesh;
  std::vector<int64_t> face_line;
  LineReader lines(data);
  std::string_view line;
  std::vector<std::string_view> tok;
  std::vector<int64_t> poly;
  while (lines.next(line)) {
    const int64_t ln = lines.line_number();
    split_ws(strip_comment(line), tok);
    if (tok.empty()) continue;
    if (tok[0] == "v") {
      if (tok.size() < 4) fail_line(path, ln, "a vertex needs three coordinates: 'v x y z'");
      Vec3 p;
      for (size_t k = 1; k < tok.size(); ++k) {
        double x = 0;
        if (!parse_double(tok[k], x)) {
          fail_line(path, ln, fmt::format("'{}' is not a number", tok[k]));
        }
        if (k <= 3) {
          if (!std::isfinite(x)) {
            fail_line(path, ln, fmt::format("vertex coordinate '{}' is not finite", tok[k]));
          }
          p[static_cast<int>(k) - 1] = x;
        }
      }
      mesh.vertices.push_back(p);
    } else if (tok[0] == "f") {
      if (tok.size() < 4) {
        fail_line(path, ln, fmt::format("a face needs at least 3 vertices, this one has {}", tok.size() - 1));
      }
      poly.clear();
      const int64_t nv = static_cast<int64_t>(mesh.vertices.size());
      for (size_t k = 1; k < tok.size(); ++k) {
        const std::string_view ref = tok[k].substr(0, tok[k].find('/'));
        int64_t i = 0;
        if (!parse_int64(ref, i)) {
          fail_line(path, ln, fmt::format("'{}' is not a vertex index (expected v, v/vt, v/vt/vn or v//vn)", tok[k]));
        }
        if (i == 0) fail_line(path, ln, "vertex index 0 is invalid (OBJ indices count from 1)");
        if (i < 0) {
          if (nv + i < 0) {
            fail_line(path, ln, fmt::format("relative vertex index {} refers before the first vertex "
                                            "({} vertices defined so far)", i, nv));
          }
          i = nv + i;
        } else {
          i -= 1;  // range checked at the end (forward references are allowed)
        }
        if (i > std::numeric_limits<int>::max()) {
          fail_line(path, ln, fmt::format("vertex index {} is out of range", i + 1));
        }
        poly.push_back(i);
      }
      for (size_t k = 1; k + 1 < poly.size(); ++k) {
        mesh.faces.push_back({static_cast<int>(poly[0]), static_cast<int>(poly[k]), static_cast<int>(poly[k + 1])});
        face_line.push_back(ln);
      }
    }
    // vt, vn, vp, l, p, o, g, s, usemtl, mtllib, ...: not part of the surface.
  }
  for (int f = 0; f < mesh.num_faces(); ++f) {
    for (int i : mesh.faces[f]) {
      if (i >= mesh.num_vertices()) {
        fail_line(path, face_line[f], fmt::format("vertex index {} is out of range: the file has {} vertices",
                                                  i + 1, mesh.num_vertices()));
      }
    }
  }
  check_mesh(path, mesh, face_line, LocKind::Line);
  return mesh;
}

void write_obj(const std::string& path, const TriMesh& mesh, const MeshWriteOptions& options) {
  check_mesh_for_writing(path, mesh, options, "OBJ", true, false);
  fmt::memory_buffer buf;
  fmt::format_to(std::back_inserter(buf), "# knitforge triangle mesh: {} vertices, {} faces\n",
                 mesh.num_vertices(), mesh.num_faces());
  for (int v = 0; v < mesh.num_vertices(); ++v) {
    const Vec3& p = mesh.vertices[v];
    fmt::format_to(std::back_inserter(buf), "v {} {} {}", p.x(), p.y(), p.z());
    if (!options.vertex_colours.empty()) {
      const Rgb c = options.vertex_colours[v];
      fmt::format_to(std::back_inserter(buf), " {} {} {}", format_double(c.r / 255.0),
                     format_double(c.g / 255.0), format_double(c.b / 255.0));
    }
    buf.push_back('\n');
  }
  for (const auto& f : mesh.faces) {
    fmt::format_to(std::back_inserter(buf), "f {} {} {}\n", f[0] + 1, f[1] + 1, f[2] + 1);
  }
  write_file_atomically(path, [&](std::ostream& out) { out.write(buf.data(), static_cast<std::streamsize>(buf.size())); });
}

}  // namespace knitforge
