#include "knitforge/io/ply.h"

#include <cmath>
#include <ostream>

#include <fmt/core.h>

#include "knitforge/io/io_detail.h"
#include "knitforge/io/ply_format.h"
#include "knitforge/util/atomic_file.h"
#include "knitforge/util/errors.h"

namespace knitforge {

using namespace io_detail;
using namespace ply_detail;

TriMesh read_ply(const std::string& path) {
  const std::string data = load_file(path);
  const PlyHeader h = read_ply_header(path, data);
  const int ve = h.find("vertex");
  if (ve < 0) fail_line(path, h.header_lines, "the header declares no 'vertex' element");
  const PlyElement& vel = h.elements[ve];
  const int px = vel.find("x"), py = vel.find("y"), pz = vel.find("z");
  if (px < 0 || py < 0 || pz < 0) {
    fail_line(path, vel.header_line, "the 'vertex' element needs properties x, y and z");
  }
  for (int p : {px, py, pz}) {
    if (vel.properties[p].is_list) fail_line(path, vel.header_line, "vertex x, y, z must not be lists");
  }
  const int fe = h.find("face");
  int pf = -1;
  if (fe >= 0) {
    const PlyElement& fel = h.elements[fe];
    pf = fel.find("vertex_indices");
    if (pf < 0) pf = fel.find("vertex_index");
    if (pf < 0 || !fel.properties[pf].is_list) {
      fail_line(path, fel.header_line,
                "the 'face' element needs a list property 'vertex_indices' (or 'vertex_index')");
    }
  }
  TriMesh mesh;
  mesh.vertices.reserve(static_cast<size_t>(vel.count));
  std::vector<int64_t> face_loc;
  const LocKind kind = h.loc_kind();
  auto fail = [&](int64_t loc, std::string_view msg) {
    if (kind == LocKind::Line) fail_line(path, loc, msg);
    fail_byte(path, loc, msg);
  };
  std::vector<int> poly;
  read_ply_body(path, data, h, [&](int e, const PlyRecord& rec) {
    if (e == ve) {
      const Vec3 p(rec.values[px], rec.values[py], rec.values[pz]);
      if (!p.allFinite()) {
        fail(rec.loc, fmt::format("vertex {} has a non-finite coordinate ({}, {}, {})", mesh.vertices.size(),
                                  p.x(), p.y(), p.z()));
      }
      mesh.vertices.push_back(p);
    } else if (e == fe) {
      const auto& items = rec.lists[pf];
      if (items.size() < 3) {
        fail(rec.loc, fmt::format("face {} has {} vertices; a face needs at least 3", face_loc.size(), items.size()));
      }
      poly.clear();
      for (double v : items) {
        if (!(v >= 0) || v != std::floor(v) || v >= static_cast<double>(vel.count)) {
          fail(rec.loc, fmt::format("vertex index {} is out of range: the file has {} vertices (PLY indices "
                                    "count from 0)", v, vel.count));
        }
        poly.push_back(static_cast<int>(v));
      }
      for (size_t k = 1; k + 1 < poly.size(); ++k) {
        mesh.faces.push_back({poly[0], poly[k], poly[k + 1]});
        face_loc.push_back(rec.loc);
      }
    }
  });
  check_mesh(path, mesh, face_loc, kind);
  return mesh;
}

void write_ply(const std::string& path, const TriMesh& mesh, const MeshWriteOptions& options) {
  check_mesh_for_writing(path, mesh, options, "PLY", true, true);
  const bool vcol = !options.vertex_colours.empty(), fcol = !options.face_colours.empty();
  PlyWriter w(options.ascii);
  w.header_line("ply");
  w.header_line(options.ascii ? "format ascii 1.0" : "format binary_little_endian 1.0");
  w.header_line("comment knitforge triangle mesh");
  w.header_line(fmt::format("element vertex {}", mesh.num_vertices()));
  w.header_line("property double x");
  w.header_line("property double y");
  w.header_line("property double z");
  if (vcol) {
    w.header_line("property uchar red");
    w.header_line("property uchar green");
    w.header_line("property uchar blue");
  }
  w.header_line(fmt::format("element face {}", mesh.num_faces()));
  w.header_line("property list uchar int vertex_indices");
  if (fcol) {
    w.header_line("property uchar red");
    w.header_line("property uchar green");
    w.header_line("property uchar blue");
  }
  w.header_line("end_header");
  auto colour = [&](Rgb c) {
    w.value(PlyType::UInt8, c.r);
    w.value(PlyType::UInt8, c.g);
    w.value(PlyType::UInt8, c.b);
  };
  for (int v = 0; v < mesh.num_vertices(); ++v) {
    for (int k = 0; k < 3; ++k) w.value(PlyType::Float64, mesh.vertices[v][k]);
    if (vcol) colour(options.vertex_colours[v]);
    w.end_record();
  }
  for (int f = 0; f < mesh.num_faces(); ++f) {
    w.value(PlyType::UInt8, 3);
    for (int k = 0; k < 3; ++k) w.value(PlyType::Int32, mesh.faces[f][k]);
    if (fcol) colour(options.face_colours[f]);
    w.end_record();
  }
  write_file_atomically(
      path, [&](std::ostream& o) { o.write(w.data().data(), static_cast<std::streamsize>(w.data().size())); },
      true);
}

}  // namespace knitforge
