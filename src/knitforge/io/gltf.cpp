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
constexpr int kFloat = 5126, kUnsignedByte = 5121, kUnsignedShort = 5123, kUnsignedInt = 5125;
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
  void f32(float f) {
    uint32_t v;
    std::memcpy(&v, &f, 4);
    u32(v);
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

/// The JSON chunk of a GLB with one buffer (the BIN chunk of `bin_length`
/// bytes), padded with spaces to 4 bytes; `total` gets the file size.
/// \throw InvalidInput when the file would exceed the 4 GiB a GLB holds
///        (`what` is what needs the bytes, `advice` what to do).
std::string glb_json_chunk(const std::string& path, const nlohmann::json& scene_nodes, const nlohmann::json& nodes,
                           const nlohmann::json& meshes, const nlohmann::json& materials,
                           const nlohmann::json& accessors, const nlohmann::json& views, uint64_t bin_length,
                           std::string_view what, std::string_view advice, uint64_t& total,
                           const nlohmann::json* animations = nullptr) {
  nlohmann::json doc = {{"asset", {{"version", "2.0"}, {"generator", "knitforge"}}},
                              {"scene", 0},
                              {"scenes", {{{"nodes", scene_nodes}}}},
                              {"nodes", nodes},
                              {"meshes", meshes},
                              {"materials", materials},
                              {"accessors", accessors},
                              {"bufferViews", views},
                              {"buffers", {{{"byteLength", bin_length}}}}};
  if (animations) doc["animations"] = *animations;
  std::string json = doc.dump();
  while (json.size() % 4 != 0) json.push_back(' ');
  total = 12 + 8 + json.size() + 8 + bin_length;
  if (total > std::numeric_limits<uint32_t>::max()) {
    throw InvalidInput(fmt::format("{}: the {} need {} bytes, more than the 4 GiB a GLB file holds; {}", path,
                                   what, total, advice));
  }
  return json;
}

/// The GLB header, the JSON chunk and the BIN chunk's header.
void write_glb_header(LittleEndianSink& out, uint64_t total, const std::string& json, uint64_t bin_length) {
  out.u32(kMagic);
  out.u32(2);
  out.u32(static_cast<uint32_t>(total));
  out.u32(static_cast<uint32_t>(json.size()));
  out.u32(kChunkJson);
  out.bytes(json.data(), json.size());
  out.u32(static_cast<uint32_t>(bin_length));
  out.u32(kChunkBin);
}

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
  uint64_t total = 0;
  const std::string json = glb_json_chunk(path, scene_nodes, nodes, gmeshes, materials, accessors, views, bin_length,
                                          "meshes", "write fewer or coarser meshes", total);

  write_file_atomically(
      path,
      [&](std::ostream& os) {
        LittleEndianSink out(os, path);
        write_glb_header(out, total, json, bin_length);
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

namespace knitforge {

namespace {

// One glTF primitive of a yarn's tube: `rings` consecutive rings of the side
// (K vertices each; 0 = the caps primitive), laid out in the BIN chunk from
// `offset` as positions (12 nv bytes), normals (12 nv) and indices
// (padded to 4 bytes).
struct TubePrimitive {
  size_t rings = 0, nv = 0, n_indices = 0;
  bool short_indices = true;
  uint64_t offset = 0;
  size_t idx_bytes = 0;
  std::array<float, 3> lo{}, hi{};
  size_t bytes() const { return 24 * nv + idx_bytes; }
};

struct YarnLayout {
  std::string name;
  RenderColour colour{};
  std::vector<Vec3> curve;  // the smoothed centre line, one ring per sample
  size_t step = 0;          // side primitive c holds rings [c step, c step + step]
  std::vector<TubePrimitive> prims;
};

constexpr size_t pad4(size_t n) { return (n + 3) & ~size_t{3}; }

template <class T>
void to_little_endian(char* p, size_t n) {
  if constexpr (std::endian::native == std::endian::big) {
    for (size_t i = 0; i < n; ++i, p += sizeof(T)) std::reverse(p, p + sizeof(T));
  } else {
    (void)p;
    (void)n;
  }
}

void put_u32(std::string& s, uint32_t v) {
  for (int k = 0; k < 4; ++k) s.push_back(static_cast<char>((v >> (8 * k)) & 0xffu));
}

// Primitives of a tube of R >= 2 rings of K vertices, from BIN offset `off`
// on (advanced past them).
std::vector<TubePrimitive> tube_layout(size_t R, size_t K, bool capped, uint64_t& off, size_t& step) {
  std::vector<TubePrimitive> prims;
  const bool short_indices = K <= 32767;
  // consecutive side primitives share a ring; at most 65535 vertices each
  step = short_indices ? 65535 / K - 1 : R - 1;
  auto add = [&](size_t rings, size_t nv, size_t n_indices, bool shorts) {
    TubePrimitive& p = prims.emplace_back();
    p.rings = rings;
    p.nv = nv;
    p.n_indices = n_indices;
    p.short_indices = shorts;
    p.offset = off;
    p.idx_bytes = pad4((shorts ? 2 : 4) * n_indices);
    p.lo.fill(std::numeric_limits<float>::infinity());
    p.hi.fill(-std::numeric_limits<float>::infinity());
    off += p.bytes();
  };
  for (size_t r0 = 0; r0 + 1 < R; r0 += step) {
    const size_t rings = std::min(step, R - 1 - r0) + 1;
    add(rings, K * rings, 6 * K * (rings - 1), short_indices);
  }
  if (capped) add(0, 2 * (K + 1), 6 * K, 2 * (K + 1) <= 65535);
  return prims;
}

// One primitive's data while it is made (typed arrays, written as bytes).
struct PrimitiveData {
  std::vector<float> pos, nrm;
  std::vector<uint16_t> idx16;
  std::vector<uint32_t> idx32;
  void reset(const TubePrimitive& p) {
    pos.resize(3 * p.nv);
    nrm.resize(3 * p.nv);
    idx16.clear();
    idx32.clear();
    if (p.short_indices)
      idx16.reserve(p.n_indices);
    else
      idx32.reserve(p.n_indices);
  }
};

template <class T>
void write_le(std::ostream& os, std::vector<T>& v) {
  char* bytes = reinterpret_cast<char*>(v.data());  // char may alias any object
  to_little_endian<T>(bytes, v.size());
  os.write(bytes, static_cast<std::streamsize>(sizeof(T) * v.size()));
}

// Writes a finished primitive in its BIN layout: positions, normals,
// indices, zero padding.
void write_primitive(std::ostream& os, const TubePrimitive& p, PrimitiveData& d) {
  write_le(os, d.pos);
  write_le(os, d.nrm);
  size_t idx_bytes = 0;
  if (p.short_indices) {
    idx_bytes = 2 * d.idx16.size();
    write_le(os, d.idx16);
  } else {
    idx_bytes = 4 * d.idx32.size();
    write_le(os, d.idx32);
  }
  const char zeros[4] = {0, 0, 0, 0};
  os.write(zeros, static_cast<std::streamsize>(p.idx_bytes - idx_bytes));
}

// Streams a yarn's primitives to `os` (BIN layout order), filling in their
// position bounds; `side` and `caps` hold one primitive each at a time.
void stream_tube(std::ostream& os, YarnLayout& y, const TubeSection& section, const TubeOptions& options,
                 PrimitiveData& side, PrimitiveData& caps) {
  const size_t K = static_cast<size_t>(section.size());
  const size_t R = y.curve.size();
  const size_t n_side = y.prims.size() - (options.capped ? 1 : 0);
  side.reset(y.prims[0]);
  if (options.capped) caps.reset(y.prims.back());

  // ring r's vertices as vertices first.. of primitive p held in `d`
  auto put_ring = [&](PrimitiveData& d, TubePrimitive& p, size_t first, const TubeRing& r) {
    float* pos = d.pos.data() + 3 * first;
    tube_ring_vertices(section, std::span<const TubeRing>(&r, 1), std::span<float>(pos, 3 * K),
                       std::span<float>(d.nrm.data() + 3 * first, 3 * K));
    for (size_t k = 0; k < K; ++k, pos += 3) {
      for (size_t c = 0; c < 3; ++c) {
        p.lo[c] = std::min(p.lo[c], pos[c]);
        p.hi[c] = std::max(p.hi[c], pos[c]);
      }
    }
  };
  const TubeRing zero{Vec3::Zero(), Vec3::Zero(), Vec3::Zero(), 0};
  std::array<TubeRing, 2> pair = {zero, zero};  // rings i-1 and i
  size_t c = 0, j = 0;                          // ring i-1 is ring j of side primitive c
  for_each_tube_ring(y.curve, options, [&](size_t i, const TubeRing& r) {
    pair[0] = pair[1];
    pair[1] = r;
    if (i == 0) {
      put_ring(side, y.prims[0], 0, r);
    } else {
      TubePrimitive& p = y.prims[c];
      put_ring(side, p, (j + 1) * K, r);
      const size_t n = 6 * K;
      const uint32_t base = static_cast<uint32_t>(j * K);
      if (p.short_indices) {
        side.idx16.resize(side.idx16.size() + n);
        tube_side_indices(pair, static_cast<int>(K), base,
                          std::span<uint16_t>(side.idx16.data() + side.idx16.size() - n, n));
      } else {
        side.idx32.resize(side.idx32.size() + n);
        tube_side_indices(pair, static_cast<int>(K), base,
                          std::span<uint32_t>(side.idx32.data() + side.idx32.size() - n, n));
      }
      ++j;
      if (j + 1 == p.rings && c + 1 < n_side) {  // the shared ring starts the next primitive
        write_primitive(os, p, side);
        ++c;
        j = 0;
        side.reset(y.prims[c]);
        put_ring(side, y.prims[c], 0, r);
      }
    }
    if (options.capped && (i == 0 || i + 1 == R)) {
      // the caps: a copy of the end ring (vertices 0..K-1) and a centre
      // (K) per end, all with the end's axial normal
      TubePrimitive& p = y.prims.back();
      const size_t end = i == 0 ? 0 : 1, first = end * (K + 1);
      put_ring(caps, p, first, r);
      const Vec3 t = r.u.cross(r.w).normalized();
      const Vec3 axis = end == 0 ? Vec3(-t) : t;
      for (size_t k = 0; k <= K; ++k) {
        for (size_t d = 0; d < 3; ++d) {
          caps.nrm[3 * (first + k) + d] = static_cast<float>(axis[static_cast<Eigen::Index>(d)]);
        }
      }
      for (size_t d = 0; d < 3; ++d) {
        const float v = static_cast<float>(r.centre[static_cast<Eigen::Index>(d)]);
        caps.pos[3 * (first + K) + d] = v;
        p.lo[d] = std::min(p.lo[d], v);
        p.hi[d] = std::max(p.hi[d], v);
      }
    }
  });
  write_primitive(os, y.prims[n_side - 1], side);
  if (options.capped) {
    // K triangles per end, CCW seen from outside
    const TubePrimitive& p = y.prims.back();
    const uint32_t k_ring = static_cast<uint32_t>(K);
    auto put = [&](uint32_t v) {
      if (p.short_indices)
        caps.idx16.push_back(static_cast<uint16_t>(v));
      else
        caps.idx32.push_back(v);
    };
    for (uint32_t end = 0; end < 2; ++end) {
      const uint32_t first = end * (k_ring + 1), centre = first + k_ring;
      for (uint32_t k = 0; k < k_ring; ++k) {
        const uint32_t k1 = k + 1 == k_ring ? 0 : k + 1;
        put(centre);
        put(end == 0 ? first + k1 : first + k);
        put(end == 0 ? first + k : first + k1);
      }
    }
    write_primitive(os, p, caps);
  }
}

// A JSON number for a float in a fixed-width slot: the shortest text that
// reads back as the same float, padded with spaces (JSON whitespace).
constexpr size_t kNumberSlot = 16;
std::string slot_marker(size_t i) { return fmt::format("~{:013}", i); }  // 14 chars + 2 quotes
std::string slot_number(float v) {
  std::string s = fmt::format("{}", v);
  if (s.find_first_of(".e") == std::string::npos && s.find("inf") == std::string::npos) s += ".0";
  s.resize(kNumberSlot, ' ');
  return s;
}

}  // namespace

YarnGlbSummary write_yarn_glb(const std::string& path, const YarnModel& yarn, const KnitParams& params,
                              const TubeOptions& options, std::span<const RenderColour> colours) {
  const double radius = tube_radius(options, params);
  const TubeSection section = tube_section(options, radius);
  const size_t K = static_cast<size_t>(section.size());
  const double spacing = tube_ring_spacing(options, radius);

  // Layout: every tube's primitives and their places in the BIN chunk.
  std::vector<YarnLayout> layouts;
  YarnGlbSummary summary;
  uint64_t bin_length = 0;
  for (size_t i = 0; i < yarn.yarns.size(); ++i) {
    const Yarn& y = yarn.yarns[i];
    YarnLayout l;
    try {
      l.curve = smooth_polyline(y.points, spacing);
    } catch (const InvalidInput& e) {
      throw InvalidInput(fmt::format("{}: yarn {} (id {}): {}", path, i, y.id, e.what()));
    }
    if (l.curve.size() < 2) continue;
    l.name = fmt::format("yarn {}", y.id);
    l.colour = colours.empty() ? RenderColour{200, 200, 200} : colours[i % colours.size()];
    l.prims = tube_layout(l.curve.size(), K, options.capped, bin_length, l.step);
    const size_t R = l.curve.size();
    summary.vertices += R * K + (options.capped ? 2 * (K + 1) : 0);
    summary.triangles += 2 * K * (R - 1) + (options.capped ? 2 * K : 0);
    if (bin_length > std::numeric_limits<uint32_t>::max()) {
      throw InvalidInput(
          fmt::format("{}: the tubes need more than the 4 GiB a GLB file holds; use a coarser tube detail "
                      "(larger ring spacing, fewer vertices per ply)",
                      path));
    }
    layouts.push_back(std::move(l));
  }
  if (layouts.empty())
    throw InvalidInput(fmt::format("{}: no yarn has 2 distinct points; nothing to write", path));

  // The JSON, with a fixed-width slot for every position bound (known only
  // once the vertices are made): written first, rewritten at the end.
  nlohmann::json accessors = nlohmann::json::array(), views = nlohmann::json::array(),
                 gmeshes = nlohmann::json::array(), nodes = nlohmann::json::array(),
                 materials = nlohmann::json::array(), scene_nodes = nlohmann::json::array();
  size_t slots = 0;
  auto view = [&](uint64_t offset, uint64_t length, int target) {
    views.push_back({{"buffer", 0}, {"byteOffset", offset}, {"byteLength", length}, {"target", target}});
    return views.size() - 1;
  };
  for (size_t m = 0; m < layouts.size(); ++m) {
    const YarnLayout& l = layouts[m];
    nlohmann::json prims = nlohmann::json::array();
    for (const TubePrimitive& p : l.prims) {
      const size_t pos = accessors.size();
      nlohmann::json lo = nlohmann::json::array(), hi = nlohmann::json::array();
      for (int k = 0; k < 3; ++k) lo.push_back(slot_marker(slots++));
      for (int k = 0; k < 3; ++k) hi.push_back(slot_marker(slots++));
      accessors.push_back({{"bufferView", view(p.offset, 12 * p.nv, kArrayBuffer)},
                           {"componentType", kFloat},
                           {"count", p.nv},
                           {"type", "VEC3"},
                           {"min", lo},
                           {"max", hi}});
      accessors.push_back({{"bufferView", view(p.offset + 12 * p.nv, 12 * p.nv, kArrayBuffer)},
                           {"componentType", kFloat},
                           {"count", p.nv},
                           {"type", "VEC3"}});
      accessors.push_back({{"bufferView", view(p.offset + 24 * p.nv, p.idx_bytes, kElementArrayBuffer)},
                           {"componentType", p.short_indices ? kUnsignedShort : kUnsignedInt},
                           {"count", p.n_indices},
                           {"type", "SCALAR"}});
      prims.push_back({{"attributes", {{"POSITION", pos}, {"NORMAL", pos + 1}}},
                       {"indices", pos + 2},
                       {"material", m},
                       {"mode", 4}});
    }
    materials.push_back({{"name", l.name},
                         {"pbrMetallicRoughness",
                          {{"baseColorFactor",
                            {srgb_to_linear(l.colour[0] / 255.0), srgb_to_linear(l.colour[1] / 255.0),
                             srgb_to_linear(l.colour[2] / 255.0), 1.0}},
                           {"metallicFactor", 0.0},
                           {"roughnessFactor", 0.8}}}});
    gmeshes.push_back({{"name", l.name}, {"primitives", prims}});
    nodes.push_back({{"name", l.name}, {"mesh", m}});
    scene_nodes.push_back(m);
  }
  uint64_t total = 0;
  std::string json = glb_json_chunk(path, scene_nodes, nodes, gmeshes, materials, accessors, views, bin_length, "tubes",
                                    "use a coarser tube detail (larger ring spacing, fewer vertices per ply)", total);
  // where each slot's marker (with its quotes) is in the JSON text
  // (names are "yarn <id>", so the only '"~' in the text are the markers)
  std::vector<size_t> slot_at(slots, std::string::npos);
  for (size_t at = json.find("\"~"); at != std::string::npos; at = json.find("\"~", at + kNumberSlot)) {
    const size_t slot = std::stoul(json.substr(at + 2, 13));
    if (slot < slots) slot_at[slot] = at;
  }
  if (std::find(slot_at.begin(), slot_at.end(), std::string::npos) != slot_at.end()) {
    throw Error(fmt::format("{}: internal error: a position bound has no place in the glTF JSON", path));
  }
  std::string head;
  put_u32(head, kMagic);
  put_u32(head, 2);
  put_u32(head, static_cast<uint32_t>(total));
  put_u32(head, static_cast<uint32_t>(json.size()));
  put_u32(head, kChunkJson);
  const size_t json_at = head.size();
  head += json;
  put_u32(head, static_cast<uint32_t>(bin_length));
  put_u32(head, kChunkBin);

  write_file_atomically(
      path,
      [&](std::ostream& os) {
        os.write(head.data(), static_cast<std::streamsize>(head.size()));
        PrimitiveData side, caps;
        for (YarnLayout& l : layouts) {
          stream_tube(os, l, section, options, side, caps);
          if (!os) throw IOError(fmt::format("{}: write failed (disk full?)", path));
          l.curve = {};
        }
        // the bounds into their slots, then the final JSON over the first
        size_t slot = 0;
        for (const YarnLayout& l : layouts) {
          for (const TubePrimitive& p : l.prims) {
            for (const auto* b : {&p.lo, &p.hi}) {
              for (float v : *b) {
                if (!std::isfinite(v)) {
                  throw InvalidInput(fmt::format("{}: {}: a coordinate overflows float32", path, l.name));
                }
                json.replace(slot_at[slot++], kNumberSlot, slot_number(v));
              }
            }
          }
        }
        os.seekp(static_cast<std::streamoff>(json_at));
        os.write(json.data(), static_cast<std::streamsize>(json.size()));
        if (!os) throw IOError(fmt::format("{}: write failed (disk full?)", path));
      },
      true);
  summary.meshes = layouts.size();
  return summary;
}

}  // namespace knitforge

namespace knitforge {

void write_animation_glb(const std::string& path, std::span<const AnimatedMesh> meshes,
                         std::span<const double> times_s) {
  const size_t nt = times_s.size();
  if (nt == 0) throw InvalidInput(fmt::format("{}: an animation needs at least one frame time", path));
  for (size_t k = 0; k < nt; ++k) {
    if (!std::isfinite(times_s[k]) || (k > 0 && !(times_s[k] > times_s[k - 1]))) {
      throw InvalidInput(fmt::format("{}: frame times must be finite and increasing (frame {}: {} s)", path, k,
                                     times_s[k]));
    }
  }
  if (meshes.empty()) throw InvalidInput(fmt::format("{}: no mesh to animate", path));
  struct Layout {
    size_t nv = 0;
    std::vector<std::array<float, 3>> lo, hi;  // per frame: frame 0 absolute, then displacements
  };
  std::vector<Layout> lay(meshes.size());
  for (size_t i = 0; i < meshes.size(); ++i) {
    const AnimatedMesh& m = meshes[i];
    if (m.frames.size() != nt) {
      throw InvalidInput(fmt::format("{}: mesh {} has {} frames for {} frame times", path, i, m.frames.size(), nt));
    }
    if (m.faces.empty()) throw InvalidInput(fmt::format("{}: mesh {} has no triangle", path, i));
    const size_t nv = m.frames[0].size();
    if (nv == 0 || nv > std::numeric_limits<uint32_t>::max() / 12) {
      throw InvalidInput(fmt::format("{}: mesh {} has {} vertices", path, i, nv));
    }
    for (const auto& f : m.faces) {
      for (int v : f) {
        if (v < 0 || static_cast<size_t>(v) >= nv) {
          throw InvalidInput(fmt::format("{}: mesh {}: face index {} out of range (0..{})", path, i, v, nv - 1));
        }
      }
    }
    lay[i].nv = nv;
    for (size_t k = 0; k < nt; ++k) {
      if (m.frames[k].size() != nv) {
        throw InvalidInput(fmt::format("{}: mesh {} frame {} has {} vertices, frame 0 {}", path, i, k,
                                       m.frames[k].size(), nv));
      }
      std::array<float, 3> lo, hi;
      lo.fill(std::numeric_limits<float>::infinity());
      hi.fill(-std::numeric_limits<float>::infinity());
      for (size_t v = 0; v < nv; ++v) {
        const Vec3 p = k == 0 ? m.frames[0][v] : Vec3(m.frames[k][v] - m.frames[0][v]);
        for (int c = 0; c < 3; ++c) {
          // The value written, so that min/max bound the float32 data exactly.
          const float f = k == 0 ? static_cast<float>(p[c])
                                 : static_cast<float>(m.frames[k][v][c]) - static_cast<float>(m.frames[0][v][c]);
          if (!std::isfinite(f))
            throw InvalidInput(fmt::format("{}: mesh {} frame {}: a coordinate overflows float32", path, i, k));
          lo[static_cast<size_t>(c)] = std::min(lo[static_cast<size_t>(c)], f);
          hi[static_cast<size_t>(c)] = std::max(hi[static_cast<size_t>(c)], f);
        }
      }
      lay[i].lo.push_back(lo);
      lay[i].hi.push_back(hi);
    }
  }

  uint64_t off = 0;
  nlohmann::json accessors = nlohmann::json::array(), views = nlohmann::json::array(),
                 gmeshes = nlohmann::json::array(), nodes = nlohmann::json::array(),
                 materials = nlohmann::json::array(), scene_nodes = nlohmann::json::array(),
                 samplers = nlohmann::json::array(), channels = nlohmann::json::array();
  auto add_view = [&](uint64_t length, int target) {
    nlohmann::json v = {{"buffer", 0}, {"byteOffset", off}, {"byteLength", length}};
    if (target) v["target"] = target;
    views.push_back(v);
    off += length;
    return views.size() - 1;
  };
  // The key times, shared by every sampler.
  const size_t time_view = add_view(4 * static_cast<uint64_t>(nt), 0);
  const size_t time_accessor = accessors.size();
  accessors.push_back({{"bufferView", time_view},
                       {"componentType", kFloat},
                       {"count", nt},
                       {"type", "SCALAR"},
                       {"min", {static_cast<float>(times_s[0])}},
                       {"max", {static_cast<float>(times_s[nt - 1])}}});
  const size_t targets = nt - 1;
  for (size_t i = 0; i < meshes.size(); ++i) {
    const AnimatedMesh& m = meshes[i];
    const Layout& L = lay[i];
    auto position_accessor = [&](size_t k) {
      const size_t view = add_view(12 * static_cast<uint64_t>(L.nv), kArrayBuffer);
      accessors.push_back({{"bufferView", view},
                           {"componentType", kFloat},
                           {"count", L.nv},
                           {"type", "VEC3"},
                           {"min", {L.lo[k][0], L.lo[k][1], L.lo[k][2]}},
                           {"max", {L.hi[k][0], L.hi[k][1], L.hi[k][2]}}});
      return accessors.size() - 1;
    };
    nlohmann::json primitive = {{"attributes", {{"POSITION", position_accessor(0)}}}, {"material", i}, {"mode", 4}};
    nlohmann::json tgts = nlohmann::json::array();
    for (size_t k = 1; k < nt; ++k) tgts.push_back({{"POSITION", position_accessor(k)}});
    const size_t idx_view = add_view(12 * static_cast<uint64_t>(m.faces.size()), kElementArrayBuffer);
    primitive["indices"] = accessors.size();
    accessors.push_back(
        {{"bufferView", idx_view}, {"componentType", kUnsignedInt}, {"count", 3 * m.faces.size()}, {"type", "SCALAR"}});
    const std::string name = m.name.empty() ? fmt::format("mesh {}", i) : m.name;
    nlohmann::json mesh = {{"name", name}};
    if (targets > 0) {
      primitive["targets"] = tgts;
      mesh["weights"] = std::vector<double>(targets, 0.0);
    }
    mesh["primitives"] = nlohmann::json::array({primitive});
    gmeshes.push_back(mesh);
    materials.push_back({{"name", name},
                         {"doubleSided", true},
                         {"pbrMetallicRoughness",
                          {{"baseColorFactor",
                            {srgb_to_linear(m.colour[0] / 255.0), srgb_to_linear(m.colour[1] / 255.0),
                             srgb_to_linear(m.colour[2] / 255.0), 1.0}},
                           {"metallicFactor", 0.0},
                           {"roughnessFactor", 0.8}}}});
    nodes.push_back({{"name", name}, {"mesh", i}});
    scene_nodes.push_back(i);
    if (targets > 0) {
      const size_t w_view = add_view(4 * static_cast<uint64_t>(nt) * targets, 0);
      accessors.push_back(
          {{"bufferView", w_view}, {"componentType", kFloat}, {"count", nt * targets}, {"type", "SCALAR"}});
      channels.push_back({{"sampler", samplers.size()}, {"target", {{"node", i}, {"path", "weights"}}}});
      samplers.push_back({{"input", time_accessor}, {"output", accessors.size() - 1}, {"interpolation", "LINEAR"}});
    }
  }
  nlohmann::json animations = nlohmann::json::array();
  if (!channels.empty()) animations.push_back({{"name", "motion"}, {"samplers", samplers}, {"channels", channels}});
  const uint64_t bin_length = off;
  uint64_t total = 0;
  const std::string json =
      glb_json_chunk(path, scene_nodes, nodes, gmeshes, materials, accessors, views, bin_length, "animated meshes",
                     "write fewer frames or coarser meshes", total, animations.empty() ? nullptr : &animations);
  write_file_atomically(
      path,
      [&](std::ostream& os) {
        LittleEndianSink out(os, path);
        write_glb_header(out, total, json, bin_length);
        for (size_t k = 0; k < nt; ++k) {
          const float t = static_cast<float>(times_s[k]);
          out.f32(t);
        }
        for (size_t i = 0; i < meshes.size(); ++i) {
          const AnimatedMesh& m = meshes[i];
          out.vec3s(m.frames[0], [](const Vec3& v) { return v; });
          for (size_t k = 1; k < nt; ++k) {
            std::vector<Vec3> d(m.frames[k].size());
            for (size_t v = 0; v < d.size(); ++v) {
              for (int c = 0; c < 3; ++c)
                d[v][c] = static_cast<double>(static_cast<float>(m.frames[k][v][c]) -
                                              static_cast<float>(m.frames[0][v][c]));
            }
            out.vec3s(d, [](const Vec3& v) { return v; });
          }
          out.triangles(m.faces);
          if (targets > 0) {
            for (size_t k = 0; k < nt; ++k) {
              for (size_t w = 0; w < targets; ++w) out.f32(k >= 1 && w == k - 1 ? 1.0f : 0.0f);
            }
          }
        }
        out.flush();
      },
      true);
}

}  // namespace knitforge
