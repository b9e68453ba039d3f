#include "knitforge/io/stitch_mesh_ply.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <iterator>
#include <limits>
#include <ostream>

#include <fmt/core.h>

#include "knitforge/io/colours.h"
#include "knitforge/io/io_detail.h"
#include "knitforge/io/ply_format.h"
#include "knitforge/util/atomic_file.h"
#include "knitforge/util/errors.h"

namespace knitforge {

using namespace io_detail;
using namespace ply_detail;

namespace {

void check_for_writing(const std::string& path, const StitchMesh& mesh) {
  for (int v = 0; v < mesh.num_vertices(); ++v) {
    if (!mesh.vertices[v].allFinite()) {
      throw InvalidInput(fmt::format("{}: vertex {} has a non-finite coordinate; cannot write it", path, v));
    }
  }
  for (int s = 0; s < mesh.num_stitches(); ++s) {
    const Stitch& st = mesh.stitches[s];
    const int t = static_cast<int>(st.type);
    if (t < 0 || t >= kNumStitchTypes) {
      throw InvalidInput(fmt::format("{}: stitch {} has unknown type {}", path, s, t));
    }
    if (st.direction != 1 && st.direction != -1) {
      throw InvalidInput(fmt::format("{}: stitch {} has direction {}; it must be +1 or -1", path, s,
                                     static_cast<int>(st.direction)));
    }
    for (int k = 0; k < 4; ++k) {
      const int v = st.v[k];
      if (k < st.corners() ? (v < 0 || v >= mesh.num_vertices()) : v != -1) {
        throw InvalidInput(
            fmt::format("{}: stitch {} ({}) has corner {} = {}; a {} stitch has {} corners "
                        "in [0, {}) and -1 after them",
                        path, s, name(st.type), k, v, name(st.type), st.corners(), mesh.num_vertices()));
      }
    }
  }
}

}  // namespace

void write_stitch_mesh_ply(const std::string& path, const StitchMesh& mesh,
                           const StitchMeshPlyOptions& options) {
  check_for_writing(path, mesh);
  PlyWriter w(options.ascii);
  w.header_line("ply");
  w.header_line(options.ascii ? "format ascii 1.0" : "format binary_little_endian 1.0");
  w.header_line("comment knitforge stitch mesh (docs/formats.md)");
  w.header_line(fmt::format("element vertex {}", mesh.num_vertices()));
  w.header_line("property double x");
  w.header_line("property double y");
  w.header_line("property double z");
  w.header_line(fmt::format("element face {}", mesh.num_stitches()));
  w.header_line("property list uchar int vertex_indices");
  w.header_line("property uchar type");
  w.header_line("property char direction");
  w.header_line("property int course");
  w.header_line("property int wale");
  w.header_line("property int yarn");
  w.header_line("property uchar roles");
  w.header_line("property uchar red");
  w.header_line("property uchar green");
  w.header_line("property uchar blue");
  for (const StitchScalar& sc : options.scalars) {
    const bool good_name = !sc.name.empty() && std::all_of(sc.name.begin(), sc.name.end(), [](char ch) {
      return std::isalnum(static_cast<unsigned char>(ch)) || ch == '_';
    });
    static const char* const kStandard[] = {"vertex_indices", "type",  "direction", "course", "wale",
                                            "yarn",           "roles", "red",       "green",  "blue"};
    const bool standard =
        std::any_of(std::begin(kStandard), std::end(kStandard), [&](const char* n) { return sc.name == n; });
    if (!good_name || standard) {
      throw InvalidInput(
          fmt::format("{}: per-stitch property name '{}' must be letters, digits and '_' and not a "
                      "standard stitch property",
                      path, sc.name));
    }
    if (static_cast<int>(sc.values.size()) != mesh.num_stitches()) {
      throw InvalidInput(fmt::format("{}: per-stitch property '{}' has {} values for {} stitches", path,
                                     sc.name, sc.values.size(), mesh.num_stitches()));
    }
    w.header_line("property float " + sc.name);
  }
  w.header_line("end_header");
  for (const Vec3& p : mesh.vertices) {
    for (int k = 0; k < 3; ++k) w.value(PlyType::Float64, p[k]);
    w.end_record();
  }
  for (const Stitch& s : mesh.stitches) {
    w.value(PlyType::UInt8, s.corners());
    for (int k = 0; k < s.corners(); ++k) w.value(PlyType::Int32, s.v[k]);
    w.value(PlyType::UInt8, static_cast<int>(s.type));
    w.value(PlyType::Int8, s.direction);
    w.value(PlyType::Int32, s.course);
    w.value(PlyType::Int32, s.wale);
    w.value(PlyType::Int32, s.yarn);
    w.value(PlyType::UInt8, s.roles);
    const Rgb c = stitch_type_colour(s.type);
    w.value(PlyType::UInt8, c.r);
    w.value(PlyType::UInt8, c.g);
    w.value(PlyType::UInt8, c.b);
    for (const StitchScalar& sc : options.scalars)
      w.value(PlyType::Float32, sc.values[&s - mesh.stitches.data()]);
    w.end_record();
  }
  write_file_atomically(
      path, [&](std::ostream& o) { o.write(w.data().data(), static_cast<std::streamsize>(w.data().size())); },
      true);
}

StitchMesh read_stitch_mesh_ply(const std::string& path) {
  const std::string data = load_file(path);
  const PlyHeader h = read_ply_header(path, data);
  const int ve = h.find("vertex"), fe = h.find("face");
  if (ve < 0 || fe < 0) {
    fail_line(path, h.header_lines, "a stitch mesh needs a 'vertex' and a 'face' element");
  }
  const PlyElement& vel = h.elements[ve];
  const PlyElement& fel = h.elements[fe];
  const int px = vel.find("x"), py = vel.find("y"), pz = vel.find("z");
  if (px < 0 || py < 0 || pz < 0) fail_line(path, vel.header_line, "the 'vertex' element needs x, y and z");
  int pv = fel.find("vertex_indices");
  if (pv < 0) pv = fel.find("vertex_index");
  const int ptype = fel.find("type"), pdir = fel.find("direction");
  if (pv < 0 || !fel.properties[pv].is_list || ptype < 0 || pdir < 0) {
    fail_line(path, fel.header_line,
              "a stitch mesh face needs the list 'vertex_indices' and the properties 'type' and "
              "'direction' (docs/formats.md)");
  }
  const int pcourse = fel.find("course"), pwale = fel.find("wale"), pyarn = fel.find("yarn"),
            proles = fel.find("roles");
  for (int p : {px, py, pz, ptype, pdir, pcourse, pwale, pyarn, proles}) {
    const auto& props = p == px || p == py || p == pz ? vel.properties : fel.properties;
    if (p >= 0 && props[p].is_list) {
      fail_line(path, (&props == &vel.properties ? vel : fel).header_line,
                fmt::format("property '{}' must not be a list", props[p].name));
    }
  }

  StitchMesh mesh;
  mesh.vertices.reserve(static_cast<size_t>(vel.count));
  mesh.stitches.reserve(static_cast<size_t>(fel.count));
  std::vector<int64_t> face_loc;
  const LocKind kind = h.loc_kind();
  auto fail = [&](int64_t loc, std::string_view msg) {
    if (kind == LocKind::Line) fail_line(path, loc, msg);
    fail_byte(path, loc, msg);
  };
  auto as_int = [&](const PlyRecord& rec, int p, const char* what, double lo, double hi) {
    const double v = rec.values[p];
    if (!(v >= lo && v <= hi) || v != std::floor(v)) {
      fail(rec.loc, fmt::format("stitch {}: {} {} is not an integer in [{}, {}]", mesh.stitches.size(), what,
                                v, lo, hi));
    }
    return static_cast<int>(v);
  };
  constexpr double kIntMin = std::numeric_limits<int>::min(), kIntMax = std::numeric_limits<int>::max();
  read_ply_body(path, data, h, [&](int e, const PlyRecord& rec) {
    if (e == ve) {
      const Vec3 p(rec.values[px], rec.values[py], rec.values[pz]);
      if (!p.allFinite()) {
        fail(rec.loc, fmt::format("vertex {} has a non-finite coordinate", mesh.vertices.size()));
      }
      mesh.vertices.push_back(p);
      return;
    }
    if (e != fe) return;
    Stitch s;
    const int t = as_int(rec, ptype, "type", 0, kNumStitchTypes - 1);
    s.type = static_cast<StitchType>(t);
    const double d = rec.values[pdir];
    if (d != 1 && d != -1) {
      fail(rec.loc, fmt::format("stitch {}: direction {} must be +1 or -1", mesh.stitches.size(), d));
    }
    s.direction = static_cast<int8_t>(d);
    const auto& items = rec.lists[pv];
    if (static_cast<int>(items.size()) != s.corners()) {
      fail(rec.loc, fmt::format("stitch {} is a {} stitch with {} corners; this type has {}",
                                mesh.stitches.size(), name(s.type), items.size(), s.corners()));
    }
    for (size_t k = 0; k < items.size(); ++k) {
      const double v = items[k];
      if (!(v >= 0) || v >= static_cast<double>(vel.count) || v != std::floor(v)) {
        fail(rec.loc, fmt::format("stitch {}: vertex index {} is out of range: the file has {} vertices",
                                  mesh.stitches.size(), v, vel.count));
      }
      s.v[k] = static_cast<int>(v);
    }
    if (pcourse >= 0) s.course = as_int(rec, pcourse, "course", kIntMin, kIntMax);
    if (pwale >= 0) s.wale = as_int(rec, pwale, "wale", kIntMin, kIntMax);
    if (pyarn >= 0) s.yarn = as_int(rec, pyarn, "yarn", kIntMin, kIntMax);
    if (proles >= 0) s.roles = static_cast<uint8_t>(as_int(rec, proles, "roles", 0, 255));
    mesh.stitches.push_back(s);
    face_loc.push_back(rec.loc);
  });
  std::vector<int> start{0}, verts;
  for (const Stitch& s : mesh.stitches) {
    for (int k = 0; k < s.corners(); ++k) verts.push_back(s.v[k]);
    start.push_back(static_cast<int>(verts.size()));
  }
  check_polygon_mesh(path, mesh.num_vertices(), start, verts, face_loc, kind);
  return mesh;
}

}  // namespace knitforge
