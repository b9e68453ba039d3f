#include "knitforge/io/gltf.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <limits>
#include <ostream>
#include <vector>

#include <fmt/core.h>
#include <nlohmann/json.hpp>

#include "knitforge/util/atomic_file.h"
#include "knitforge/util/errors.h"

namespace knitforge {

namespace {

constexpr uint32_t kMagic = 0x46546C67;      // "glTF"
constexpr uint32_t kChunkJson = 0x4E4F534A;  // "JSON"
constexpr uint32_t kChunkBin = 0x004E4942;   // "BIN\0"
constexpr int kFloat = 5126, kUnsignedByte = 5121, kUnsignedInt = 5125;
constexpr int kArrayBuffer = 34962, kElementArrayBuffer = 34963;

// A mesh ready to stream: either the input mesh or its face-colour expansion.
struct Prepared {
  const RenderMesh* mesh = nullptr;
  RenderMesh expanded;  // used when the input has face colours
  const RenderMesh& m() const { return mesh ? *mesh : expanded; }
  bool normals = false, colours = false;
  size_t nv = 0, nf = 0;
  std::array<float, 3> lo{}, hi{};
  size_t pos_off = 0, nrm_off = 0, col_off = 0, idx_off = 0;
};

RenderMesh expand_face_colours(const RenderMesh& in) {
  RenderMesh out;
  out.name = in.name;
  out.colour = in.colour;
  const size_t nf = in.mesh.faces.size();
  out.mesh.vertices.reserve(3 * nf);
  out.mesh.faces.reserve(nf);
  out.vertex_colours.reserve(3 * nf);
  out.normals.reserve(3 * nf);
  for (size_t f = 0; f < nf; ++f) {
    const auto& t = in.mesh.faces[f];
    const Vec3& a = in.mesh.vertices[static_cast<size_t>(t[0])];
    const Vec3 fn = (in.mesh.vertices[static_cast<size_t>(t[1])] - a)
                        .cross(in.mesh.vertices[static_cast<size_t>(t[2])] - a);
    const int base = static_cast<int>(out.mesh.vertices.size());
    for (int k = 0; k < 3; ++k) {
      const size_t v = static_cast<size_t>(t[static_cast<size_t>(k)]);
      out.mesh.vertices.push_back(in.mesh.vertices[v]);
      out.vertex_colours.push_back(in.face_colours[f]);
      out.normals.push_back(in.normals.empty() ? fn : in.normals[v]);
    }
    out.mesh.faces.push_back({base, base + 1, base + 2});
  }
  return out;
}

// The unit normal written for n (glTF requires unit normals; a zero normal
// becomes +z).
Vec3 unit(const Vec3& n) {
  const double l = n.norm();
  return l > 0.0 && std::isfinite(l) ? Vec3(n / l) : Vec3::UnitZ();
}

// Buffered little-endian output (GLB is little endian whatever the host).
class LittleEndianSink {
 public:
  LittleEndianSink(std::ostream& os, const std::string& path) : os_(os), path_(path), buf_(kSize) {}
  void u32(uint32_t v) {
    if constexpr (std::endian::native == std::endian::big) {
      v = (v >> 24) | ((v >> 8) & 0xff00u) | ((v << 8) & 0xff0000u) | (v << 24);
    }
    put4(&v);
  }
  void bytes(const void* p, size_t n) {
    const char* c = static_cast<const char*>(p);
    while (n > 0) {
      const size_t k = std::min(n, kSize - used_);
      std::memcpy(buf_.data() + used_, c, k);
      used_ += k;
      c += k;
      n -= k;
      if (used_ == kSize) flush();
    }
  }
  /// Writes f(v) of every v as three float32 (in blocks, little endian).
  template <class F>
  void vec3s(const std::vector<Vec3>& vs, F f) {
    float block[3 * 1024];
    for (size_t i = 0; i < vs.size(); i += 1024) {
      const size_t n = std::min<size_t>(1024, vs.size() - i);
      for (size_t j = 0; j < n; ++j) {
        const Vec3 v = f(vs[i + j]);
        block[3 * j] = static_cast<float>(v.x());
        block[3 * j + 1] = static_cast<float>(v.y());
        block[3 * j + 2] = static_cast<float>(v.z());
      }
      words(block, 3 * n);
    }
  }
  /// Writes the vertex indices of every triangle as uint32.
  void triangles(const std::vector<std::array<int, 3>>& faces) {
    uint32_t block[3 * 1024];
    for (size_t i = 0; i < faces.size(); i += 1024) {
      const size_t n = std::min<size_t>(1024, faces.size() - i);
      for (size_t j = 0; j < n; ++j) {
        for (size_t k = 0; k < 3; ++k) block[3 * j + k] = static_cast<uint32_t>(faces[i + j][k]);
      }
      words(block, 3 * n);
    }
  }
  void flush() {
    os_.write(buf_.data(), static_cast<std::streamsize>(used_));
    if (!os_) throw IOError(fmt::format("{}: write failed (disk full?)", path_));
    used_ = 0;
  }

 private:
  // n 4-byte words (float32 or uint32) in host order, written little endian.
  void words(void* p, size_t n) {
    if constexpr (std::endian::native == std::endian::big) {
      auto* w = static_cast<uint32_t*>(p);
      for (size_t i = 0; i < n; ++i) {
        const uint32_t v = w[i];
        w[i] = (v >> 24) | ((v >> 8) & 0xff00u) | ((v << 8) & 0xff0000u) | (v << 24);
      }
    }
    bytes(p, 4 * n);
  }
  void put4(const void* p) {
    if (used_ + 4 > kSize) flush();
    std::memcpy(buf_.data() + used_, p, 4);
    used_ += 4;
  }
  static constexpr size_t kSize = size_t{1} << 20;  // a multiple of 4
  std::ostream& os_;
  const std::string& path_;
  std::vector<char> buf_;
  size_t used_ = 0;
};

double srgb_to_linear(double c) { return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4); }

}  // namespace

uint8_t srgb_to_linear_byte(uint8_t c) {
  return static_cast<uint8_t>(std::lround(255.0 * srgb_to_linear(c / 255.0)));
}

void write_glb(const std::string& path, std::span<const RenderMesh> meshes) {
  std::vector<Prepared> prep;
  prep.reserve(meshes.size());
  for (size_t i = 0; i < meshes.size(); ++i) {
    const RenderMesh& m = meshes[i];
    try {
      validate_render_mesh(m);
    } catch (const InvalidInput& e) {
      throw InvalidInput(fmt::format("{}: mesh {}: {}", path, i, e.what()));
    }
    if (m.mesh.faces.empty()) continue;
    Prepared& p = prep.emplace_back();
    if (!m.face_colours.empty())
      p.expanded = expand_face_colours(m);
    else
      p.mesh = &m;
    const RenderMesh& pm = p.m();
    p.normals = !pm.normals.empty();
    p.colours = !pm.vertex_colours.empty();
    p.nv = pm.mesh.vertices.size();
    p.nf = pm.mesh.faces.size();
    if (p.nv > std::numeric_limits<uint32_t>::max() / 12 ||
        p.nf > std::numeric_limits<uint32_t>::max() / 12) {
      throw InvalidInput(fmt::format("{}: mesh {} is too large for a GLB file (4 GiB limit)", path, i));
    }
    p.lo.fill(std::numeric_limits<float>::infinity());
    p.hi.fill(-std::numeric_limits<float>::infinity());
    for (const Vec3& v : pm.mesh.vertices) {
      for (int k = 0; k < 3; ++k) {
        const float f = static_cast<float>(v[k]);
        if (!std::isfinite(f))
          throw InvalidInput(fmt::format("{}: mesh {}: a coordinate overflows float32", path, i));
        p.lo[static_cast<size_t>(k)] = std::min(p.lo[static_cast<size_t>(k)], f);
        p.hi[static_cast<size_t>(k)] = std::max(p.hi[static_cast<size_t>(k)], f);
      }
    }
  }

  if (prep.empty()) {
    throw InvalidInput(fmt::format("{}: no mesh has a triangle; nothing to write", path));
  }

  // BIN layout and JSON.
  uint64_t off = 0;
  nlohmann::json accessors = nlohmann::json::array(), views = nlohmann::json::array(),
                 gmeshes = nlohmann::json::array(), nodes = nlohmann::json::array(),
                 materials = nlohmann::json::array(), scene_nodes = nlohmann::json::array();
  auto add_view = [&](uint64_t length, int target) {
    views.push_back({{"buffer", 0}, {"byteOffset", off}, {"byteLength", length}, {"target", target}});
    const uint64_t at = off;
    off += length;
    return at;
  };
  for (size_t i = 0; i < prep.size(); ++i) {
    Prepared& p = prep[i];
    const RenderMesh& pm = p.m();
    nlohmann::json attributes;
    p.pos_off = add_view(12 * static_cast<uint64_t>(p.nv), kArrayBuffer);
    attributes["POSITION"] = accessors.size();
    accessors.push_back({{"bufferView", views.size() - 1},
                         {"componentType", kFloat},
                         {"count", p.nv},
                         {"type", "VEC3"},
                         {"min", {p.lo[0], p.lo[1], p.lo[2]}},
                         {"max", {p.hi[0], p.hi[1], p.hi[2]}}});
    if (p.normals) {
      p.nrm_off = add_view(12 * static_cast<uint64_t>(p.nv), kArrayBuffer);
      attributes["NORMAL"] = accessors.size();
      accessors.push_back(
          {{"bufferView", views.size() - 1}, {"componentType", kFloat}, {"count", p.nv}, {"type", "VEC3"}});
    }
    if (p.colours) {
      p.col_off = add_view(4 * static_cast<uint64_t>(p.nv), kArrayBuffer);
      attributes["COLOR_0"] = accessors.size();
      accessors.push_back({{"bufferView", views.size() - 1},
                           {"componentType", kUnsignedByte},
                           {"normalized", true},
                           {"count", p.nv},
                           {"type", "VEC4"}});
    }
    p.idx_off = add_view(12 * static_cast<uint64_t>(p.nf), kElementArrayBuffer);
    const size_t idx_accessor = accessors.size();
    accessors.push_back({{"bufferView", views.size() - 1},
                         {"componentType", kUnsignedInt},
                         {"count", 3 * p.nf},
                         {"type", "SCALAR"}});
    const RenderColour base = p.colours ? RenderColour{255, 255, 255} : pm.colour;
    const std::string name = pm.name.empty() ? fmt::format("mesh {}", i) : pm.name;
    materials.push_back({{"name", name},
                         {"pbrMetallicRoughness",
                          {{"baseColorFactor",
                            {srgb_to_linear(base[0] / 255.0), srgb_to_linear(base[1] / 255.0),
                             srgb_to_linear(base[2] / 255.0), 1.0}},
                           {"metallicFactor", 0.0},
                           {"roughnessFactor", 0.8}}}});
    gmeshes.push_back(
        {{"name", name},
         {"primitives",
          {{{"attributes", attributes}, {"indices", idx_accessor}, {"material", i}, {"mode", 4}}}}});
    nodes.push_back({{"name", name}, {"mesh", i}});
    scene_nodes.push_back(i);
  }
  const uint64_t bin_length = off;  // every part is a multiple of 4 bytes
  nlohmann::json doc = {{"asset", {{"version", "2.0"}, {"generator", "knitforge"}}},
                        {"scene", 0},
                        {"scenes", {{{"nodes", scene_nodes}}}},
                        {"nodes", nodes},
                        {"meshes", gmeshes},
                        {"materials", materials},
                        {"accessors", accessors},
                        {"bufferViews", views},
                        {"buffers", {{{"byteLength", bin_length}}}}};
  std::string json = doc.dump();
  while (json.size() % 4 != 0) json.push_back(' ');
  const uint64_t total = 12 + 8 + json.size() + 8 + bin_length;
  if (total > std::numeric_limits<uint32_t>::max()) {
    throw InvalidInput(
        fmt::format("{}: the meshes need {} bytes, more than the 4 GiB a GLB file holds; write "
                    "fewer or coarser meshes",
                    path, total));
  }

  write_file_atomically(
      path,
      [&](std::ostream& os) {
        LittleEndianSink out(os, path);
        out.u32(kMagic);
        out.u32(2);
        out.u32(static_cast<uint32_t>(total));
        out.u32(static_cast<uint32_t>(json.size()));
        out.u32(kChunkJson);
        out.bytes(json.data(), json.size());
        out.u32(static_cast<uint32_t>(bin_length));
        out.u32(kChunkBin);
        for (const Prepared& p : prep) {
          const RenderMesh& pm = p.m();
          out.vec3s(pm.mesh.vertices, [](const Vec3& v) { return v; });
          if (p.normals) out.vec3s(pm.normals, unit);
          if (p.colours) {
            uint8_t lut[256];
            for (int c = 0; c < 256; ++c) lut[c] = srgb_to_linear_byte(static_cast<uint8_t>(c));
            for (const RenderColour& c : pm.vertex_colours) {
              const uint8_t rgba[4] = {lut[c[0]], lut[c[1]], lut[c[2]], 255};
              out.bytes(rgba, 4);
            }
          }
          out.triangles(pm.mesh.faces);
        }
        out.flush();
      },
      true);
}

}  // namespace knitforge
