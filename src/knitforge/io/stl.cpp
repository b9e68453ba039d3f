#include "knitforge/io/stl.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <ostream>

#include <Eigen/Geometry>
#include <fmt/core.h>

#include "knitforge/io/io_detail.h"
#include "knitforge/util/atomic_file.h"
#include "knitforge/util/errors.h"

namespace knitforge {

using namespace io_detail;

namespace {

// Collects facets, then welds corners with exactly the same position into one
// vertex (vertex ids in order of first appearance). Sorting the corners is
// several times faster than a node-based hash map on large scans.
class Welder {
 public:
  void add_facet(const std::vector<Vec3>& corners, int64_t loc) {
    for (const Vec3& p : corners) pos_.push_back({p.x() + 0.0, p.y() + 0.0, p.z() + 0.0});  // -0 -> +0
    size_.push_back(static_cast<int>(corners.size()));
    loc_.push_back(loc);
  }
  // Fan-triangulates the facets; drops triangles whose corners coincide after
  // welding (no area and no edges of their own).
  void finish(TriMesh& mesh, std::vector<int64_t>& face_loc) const {
    const size_t n = pos_.size();
    std::vector<uint32_t> order(n);
    for (size_t i = 0; i < n; ++i) order[i] = static_cast<uint32_t>(i);
    std::sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) {
      return pos_[a] != pos_[b] ? pos_[a] < pos_[b] : a < b;
    });
    std::vector<uint32_t> rep(n);  // first corner with the same position
    for (size_t k = 0; k < n; ++k) {
      rep[order[k]] = k > 0 && pos_[order[k]] == pos_[order[k - 1]] ? rep[order[k - 1]] : order[k];
    }
    std::vector<int> id(n, -1);
    for (size_t i = 0; i < n; ++i) {
      if (id[rep[i]] < 0) {
        id[rep[i]] = mesh.num_vertices();
        mesh.vertices.emplace_back(pos_[i][0], pos_[i][1], pos_[i][2]);
      }
      id[i] = id[rep[i]];
    }
    size_t c = 0;
    for (size_t f = 0; f < size_.size(); ++f) {
      for (int k = 1; k + 1 < size_[f]; ++k) {
        const int a = id[c], b = id[c + k], d = id[c + k + 1];
        if (a == b || b == d || a == d) continue;
        mesh.faces.push_back({a, b, d});
        face_loc.push_back(loc_[f]);
      }
      c += size_[f];
    }
  }

 private:
  std::vector<std::array<double, 3>> pos_;
  std::vector<int> size_;
  std::vector<int64_t> loc_;
};

std::string lower(std::string_view s) {
  std::string o(s);
  for (char& c : o) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return o;
}

TriMesh read_binary_stl(const std::string& path, std::string_view data) {
  if (data.size() < 84) {
    fail_byte(path, static_cast<int64_t>(data.size()),
              fmt::format("file too short ({} bytes) for a binary STL (84-byte header) and it does not "
                          "start with 'solid'", data.size()));
  }
  const uint32_t n = load_scalar<uint32_t>(data.data() + 80, false);
  const uint64_t need = 84 + 50ull * n;
  if (data.size() < need) {
    const uint64_t full = (data.size() - 84) / 50;
    fail_byte(path, static_cast<int64_t>(84 + 50 * full),
              fmt::format("the header declares {} triangles ({} bytes) but the file has only {} bytes: it "
                          "ends inside triangle {} (truncated file?)", n, need, data.size(), full));
  }
  Welder weld;
  std::vector<Vec3> corners(3);
  for (uint32_t t = 0; t < n; ++t) {
    const size_t base = 84 + 50ull * t;
    for (int k = 0; k < 3; ++k) {
      for (int d = 0; d < 3; ++d) {
        const size_t at = base + 12 + 12 * k + 4 * d;
        const float x = load_scalar<float>(data.data() + at, false);
        if (!std::isfinite(x)) {
          fail_byte(path, static_cast<int64_t>(at),
                    fmt::format("triangle {} has a non-finite coordinate ({})", t, x));
        }
        corners[k][d] = x;
      }
    }
    weld.add_facet(corners, static_cast<int64_t>(base));
  }
  TriMesh mesh;
  std::vector<int64_t> face_loc;
  weld.finish(mesh, face_loc);
  check_mesh(path, mesh, face_loc, LocKind::Byte);
  return mesh;
}

TriMesh read_ascii_stl(const std::string& path, std::string_view data) {
  enum State { Outside, InSolid, InFacet, InLoop, AfterLoop } state = Outside;
  Welder weld;
  std::vector<Vec3> corners;
  int64_t facet_line = 0;
  LineReader lines(data);
  std::string_view line;
  std::vector<std::string_view> tok;
  while (lines.next(line)) {
    const int64_t ln = lines.line_number();
    split_ws(line, tok);
    if (tok.empty()) continue;
    const std::string key = lower(tok[0]);
    auto expect = [&](std::string_view what) {
      fail_line(path, ln, fmt::format("expected {}, found '{}'", what, trim(line)));
    };
    switch (state) {
      case Outside:
        if (key != "solid") expect("'solid'");
        state = InSolid;
        break;
      case InSolid:
        if (key == "endsolid") {
          state = Outside;
        } else if (key == "facet") {
          state = InFacet;
          facet_line = ln;
        } else {
          expect("'facet' or 'endsolid'");
        }
        break;
      case InFacet:
        if (key != "outer" || tok.size() < 2 || lower(tok[1]) != "loop") expect("'outer loop'");
        corners.clear();
        state = InLoop;
        break;
      case InLoop:
        if (key == "vertex") {
          if (tok.size() != 4) fail_line(path, ln, "a vertex needs three coordinates: 'vertex x y z'");
          Vec3 p;
          for (int d = 0; d < 3; ++d) {
            if (!parse_double(tok[d + 1], p[d])) {
              fail_line(path, ln, fmt::format("'{}' is not a number", tok[d + 1]));
            }
            if (!std::isfinite(p[d])) {
              fail_line(path, ln, fmt::format("vertex coordinate '{}' is not finite", tok[d + 1]));
            }
          }
          corners.push_back(p);
        } else if (key == "endloop") {
          if (corners.size() < 3) {
            fail_line(path, ln, fmt::format("the facet has {} vertices; it needs at least 3", corners.size()));
          }
          state = AfterLoop;
        } else {
          expect("'vertex' or 'endloop'");
        }
        break;
      case AfterLoop:
        if (key != "endfacet") expect("'endfacet'");
        weld.add_facet(corners, facet_line);
        state = InSolid;
        break;
    }
  }
  if (state != Outside) {
    fail_line(path, lines.line_number(),
              state == InSolid ? "unexpected end of file: 'endsolid' is missing (truncated file?)"
                               : "unexpected end of file inside a facet (truncated file?)");
  }
  TriMesh mesh;
  std::vector<int64_t> face_loc;
  weld.finish(mesh, face_loc);
  check_mesh(path, mesh, face_loc, LocKind::Line);
  return mesh;
}

}  // namespace

TriMesh read_stl(const std::string& path) {
  const std::string data = load_file(path);
  if (data.empty()) throw IOError(fmt::format("{}: file is empty", path));
  if (data.size() >= 84 && data.size() == 84 + 50ull * load_scalar<uint32_t>(data.data() + 80, false)) {
    return read_binary_stl(path, data);
  }
  const std::string_view head = trim(std::string_view(data).substr(0, std::min<size_t>(data.size(), 512)));
  const bool text_like = std::string_view(data).substr(0, std::min<size_t>(data.size(), 1024)).find('\0') ==
                         std::string_view::npos;
  if (text_like && head.size() >= 5 && lower(head.substr(0, 5)) == "solid") return read_ascii_stl(path, data);
  if (text_like && trim(data).empty()) throw IOError(fmt::format("{}: file is empty", path));
  return read_binary_stl(path, data);
}

void write_stl(const std::string& path, const TriMesh& mesh, const MeshWriteOptions& options) {
  check_mesh_for_writing(path, mesh, options, "STL", false, false);
  auto normal = [&](int f) {
    const auto& t = mesh.faces[f];
    const Vec3 n = (mesh.vertices[t[1]] - mesh.vertices[t[0]]).cross(mesh.vertices[t[2]] - mesh.vertices[t[0]]);
    const double len = n.norm();
    return len > 0 && std::isfinite(len) ? Vec3(n / len) : Vec3::Zero();
  };
  std::string buf;
  if (options.ascii) {
    auto f32 = [](double v) { return fmt::format("{}", static_cast<float>(v)); };
    buf += "solid knitforge\n";
    for (int f = 0; f < mesh.num_faces(); ++f) {
      const Vec3 n = normal(f);
      buf += fmt::format("facet normal {} {} {}\n outer loop\n", f32(n.x()), f32(n.y()), f32(n.z()));
      for (int k = 0; k < 3; ++k) {
        const Vec3& p = mesh.vertices[mesh.faces[f][k]];
        buf += fmt::format("  vertex {} {} {}\n", f32(p.x()), f32(p.y()), f32(p.z()));
      }
      buf += " endloop\nendfacet\n";
    }
    buf += "endsolid knitforge\n";
  } else {
    std::string header = "knitforge binary STL";
    header.resize(80, ' ');
    buf = header;
    append_le(buf, static_cast<uint32_t>(mesh.num_faces()));
    for (int f = 0; f < mesh.num_faces(); ++f) {
      const Vec3 n = normal(f);
      for (int d = 0; d < 3; ++d) append_le(buf, static_cast<float>(n[d]));
      for (int k = 0; k < 3; ++k) {
        for (int d = 0; d < 3; ++d) append_le(buf, static_cast<float>(mesh.vertices[mesh.faces[f][k]][d]));
      }
      append_le(buf, static_cast<uint16_t>(0));
    }
  }
  write_file_atomically(
      path, [&](std::ostream& o) { o.write(buf.data(), static_cast<std::streamsize>(buf.size())); }, true);
}

}  // namespace knitforge
